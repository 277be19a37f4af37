#!/usr/bin/env bash
# `plenopath render-scene --scene X.blend`: a Blender scene that this test makes with Blender's own Python (a
# box room whose walls glow in distinct colours) rendered along waypoints with Cycles, laid out as `render`
# writes (ground truth, frames, 16-bit depth): depth that matches the room's walls, the red east wall ahead
# at heading 0, online sampling, and clear errors (a broken .blend, no blender, POV-Ray's options).
# Skipped (exit 77) where blender is not installed.
set -u
cli=$1
fail() { echo "FAIL: $*"; exit 1; }
if ! command -v blender > /dev/null; then
  echo "SKIP: blender is not installed (cmake/install-deps.sh installs it): the Blender route is not tested"
  exit 77
fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# A room 10 x 6 x 3 m around the plan origin (Blender is z up: plan x, y = Blender x, y), drawn in
# centimetres (unit scale 0.01), with a camera of its own (replaced).
cat > "$tmp/make_room.py" <<'PY'
import bpy, sys
out = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.unit_settings.system = 'METRIC'
scene.unit_settings.scale_length = 0.01
scene.view_settings.view_transform = 'Standard'
def wall(name, corners, rgb):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.node_tree.nodes.clear()
    e = m.node_tree.nodes.new("ShaderNodeEmission")
    e.inputs[0].default_value = rgb + (1,)
    o = m.node_tree.nodes.new("ShaderNodeOutputMaterial")
    m.node_tree.links.new(e.outputs[0], o.inputs[0])
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(100 * x, 100 * y, 100 * z) for x, y, z in corners], [], [(0, 1, 2, 3)])
    mesh.materials.append(m)
    scene.collection.objects.link(bpy.data.objects.new(name, mesh))
wall("east", [(5, -3, 0), (5, 3, 0), (5, 3, 3), (5, -3, 3)], (1, 0, 0))
wall("west", [(-5, -3, 0), (-5, 3, 0), (-5, 3, 3), (-5, -3, 3)], (0, 1, 0))
wall("north", [(-5, 3, 0), (5, 3, 0), (5, 3, 3), (-5, 3, 3)], (0, 0, 1))
wall("south", [(-5, -3, 0), (5, -3, 0), (5, -3, 3), (-5, -3, 3)], (1, 1, 0))
wall("floor", [(-5, -3, 0), (5, -3, 0), (5, 3, 0), (-5, 3, 0)], (0.3, 0.3, 0.3))
wall("ceiling", [(-5, -3, 3), (5, -3, 3), (5, 3, 3), (-5, 3, 3)], (1, 1, 1))
camera = bpy.data.objects.new("Own", bpy.data.cameras.new("Own"))
scene.collection.objects.link(camera)
scene.camera = camera
bpy.ops.wm.save_as_mainfile(filepath=out)
PY
blender -b --factory-startup --python-exit-code 1 --python "$tmp/make_room.py" -- "$tmp/room.blend" \
  > "$tmp/make.log" 2>&1 || fail "blender could not make the scene: $(tail -5 "$tmp/make.log")"

"$cli" render-scene --scene "$tmp/room.blend" --waypoints "-4,0 -2.5,0 -2.5,1" --step 0.5 --size 64x32 \
  --samples 1 --out "$tmp/out" --quiet || fail "render-scene exit $?"
[[ $(ls "$tmp/out/frames" | wc -l) -eq 6 ]] || fail "expected 6 frames, got $(ls "$tmp/out/frames" | wc -l)"
[[ $(ls "$tmp/out/depth" | wc -l) -eq 6 ]] || fail "expected 6 depth maps"
[[ ! -e "$tmp/out/.blender" ]] || fail "the work folder was left behind"
python3 - "$tmp/out" "$(dirname "$0")" <<'PY' || fail "ground truth or depth content"
import json, math, struct, sys, zlib
out = sys.argv[1]
g = json.load(open(out + "/groundtruth.json"))
fr = g["frames"]
assert len(fr) == 6, len(fr)
assert fr[0]["x"] == -4.0 and fr[0]["y"] == 0.0 and abs(fr[0]["heading_deg"]) < 1e-9, fr[0]
assert abs(fr[-1]["y"] - 1.0) < 1e-9 and abs(fr[-1]["heading_deg"] - 90) < 1e-6, fr[-1]
for i, f in enumerate(fr):
    assert f["index"] == i and f["file"] == "frames/%06d.jpg" % i, f
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, sys.argv[2])
from png16 import read_png16
def png_rows(name):
    w, h, rows = read_png16(name)
    assert (w, h) == (64, 32), (w, h)
    return lambda u, v: rows[v][u]
# Frame 0 looks along +x from (-4, 0), 1.6 m up: the pixel just right of the centre of row 16 (elevation
# -2.8 deg) sees the far wall x = 5 at 9 m / cos(2.8 deg) / cos(2.8 deg azimuth); straight behind, x = -5 at
# 1 m. Frame 5 at (-2.5, 1) looks along +y: the north wall y = 3 is 2 m ahead.
depth = png_rows(out + "/depth/000000.png")
el = math.radians(90 - 16.5 / 32 * 180)
az = math.radians(32.5 / 64 * 360 - 180)
ahead = 9 / math.cos(el) / math.cos(az)
behind = 1 / math.cos(el) / math.cos(math.radians(0.5 / 64 * 360))
assert abs(depth(32, 16) - 1000 * ahead) <= 1, (depth(32, 16), ahead)
assert abs(depth(0, 16) - 1000 * behind) <= 1, (depth(0, 16), behind)
depth = png_rows(out + "/depth/000005.png")
assert abs(depth(32, 16) - 1000 * 2 / math.cos(el) / math.cos(az)) <= 1, depth(32, 16)
PY
# The colour: frame 0 sees the red east wall ahead, the green west wall behind, the yellow south wall (-y)
# on its right (azimuth +90 deg: clockwise seen from above) and the blue north wall on its left.
pixel() { convert "$tmp/out/frames/000000.jpg" -crop "1x1+$1+$2" -depth 8 txt:- | tail -1 | sed 's/.*(\([0-9,]*\).*/\1/'; }
near() { python3 -c "import sys; a=[int(x) for x in '$1'.split(',')[:3]]; b=[int(x) for x in '$2'.split(',')]; sys.exit(max(abs(x-y) for x,y in zip(a,b)) > 40)"; }
near "$(pixel 32 15)" "255,0,0" || fail "ahead is not the red east wall: $(pixel 32 15)"
near "$(pixel 0 15)" "0,255,0" || fail "behind is not the green west wall: $(pixel 0 15)"
near "$(pixel 48 15)" "255,255,0" || fail "right is not the yellow south wall: $(pixel 48 15)"
near "$(pixel 16 15)" "0,0,255" || fail "left is not the blue north wall: $(pixel 16 15)"
"$cli" capture-info "$tmp/out/frames" > "$tmp/info.txt" 2>&1 || fail "the frames are no capture: $(cat "$tmp/info.txt")"

# Online sampling: the whole walk as coarse depth, full frames only for the keyframes; the capture is them.
"$cli" render-scene --scene "$tmp/room.blend" --waypoints "-4,0 4,0 4,2" --step 0.25 --size 128x64 --online \
  --ratio 8 --coarse-width 64 --samples 1 --out "$tmp/online" --quiet || fail "render-scene --online exit $?"
python3 - "$tmp/online" <<'PY' || fail "online sampling output"
import json, os, sys
out = sys.argv[1]
r = json.load(open(out + "/online_sampling.json"))
assert r["path_frames"] == 41 and r["coarse_frames"] == 41 and r["coarse_width"] == 64, r
assert 2 <= r["full_frames"] <= 41 // 4 and r["full_frames"] == len(r["keyframes"]), r
assert r["full_size"] == [128, 64], r
g = json.load(open(out + "/groundtruth.json"))
assert [f["index"] for f in g["frames"]] == r["keyframes"], (g["frames"], r["keyframes"])
assert sorted(os.listdir(out + "/frames")) == ["%06d.jpg" % k for k in r["keyframes"]], os.listdir(out + "/frames")
assert len(os.listdir(out + "/depth")) == r["full_frames"]
PY

# Errors: a broken .blend (Blender's own message), no blender, POV-Ray's options on a Blender scene.
echo 'not a blend file' > "$tmp/broken.blend"
"$cli" render-scene --scene "$tmp/broken.blend" --waypoints "0,0 1,0" --size 32x16 --out "$tmp/e1" 2> "$tmp/err" \
  && fail "broken scene accepted"
grep -q "Blender failed on .*broken.blend" "$tmp/err" || fail "broken scene error: $(cat "$tmp/err")"
grep -q "not supported" "$tmp/err" || fail "broken scene error without Blender's message: $(cat "$tmp/err")"
"$cli" render-scene --scene "$tmp/room.blend" --waypoints "0,0 1,0" --blender no-such-blender --out "$tmp/e2" \
  2> "$tmp/err" && fail "missing blender accepted"
grep -q "apt-get install blender" "$tmp/err" || fail "no blender error: $(cat "$tmp/err")"
[[ ! -e "$tmp/e2" ]] || fail "output written although blender is missing"
"$cli" render-scene --scene "$tmp/room.blend" --waypoints "0,0 1,0" --quality 5 --out "$tmp/e3" 2> "$tmp/err" \
  && fail "a POV-Ray option accepted for a Blender scene"
grep -q -- "--quality is for POV-Ray scenes" "$tmp/err" || fail "POV-Ray option error: $(cat "$tmp/err")"
"$cli" render-scene --scene "$tmp/missing.blend" --waypoints "0,0 1,0" --out "$tmp/e4" 2> "$tmp/err" \
  && fail "missing scene accepted"
grep -q "missing.blend" "$tmp/err" || fail "missing scene error: $(cat "$tmp/err")"
echo "render-scene (Blender): ok"
