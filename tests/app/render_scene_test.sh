#!/usr/bin/env bash
# `plenopath render-scene`: the author's POV-Ray scene along waypoints, laid out as `render` writes (ground
# truth, frames, 16-bit depth), headings along the walk, depth that matches the room's walls, and clear errors.
set -u
cli=$1
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
command -v povray > /dev/null || fail "povray is not installed (cmake/install-deps.sh installs it)"

# A room 10 x 6 x 3 m around the plan origin, its own camera (replaced), a sphere.
cat > "$tmp/room.pov" <<'POV'
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0, 10, -10> look_at 0 }
light_source { <2, 2.8, 1> color rgb 1 }
box { <-5, 0, -3>, <5, 3, 3> inverse pigment { checker rgb <0.8, 0.7, 0.6> rgb <0.2, 0.3, 0.4> scale 0.5 } }
sphere { <2, 1, 1.5>, 0.5 pigment { rgb 1 } }
POV
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "-4,0 -2.5,0 -2.5,1" --step 0.5 --size 64x32 \
  --out "$tmp/out" --quiet || fail "render-scene exit $?"
[[ $(ls "$tmp/out/frames" | wc -l) -eq 6 ]] || fail "expected 6 frames, got $(ls "$tmp/out/frames" | wc -l)"
[[ $(ls "$tmp/out/depth" | wc -l) -eq 6 ]] || fail "expected 6 depth maps"
[[ ! -e "$tmp/out/.povray" ]] || fail "the work folder was left behind"
python3 - "$tmp/out" "$(dirname "$0")" <<'PY' || fail "ground truth or depth content"
import json, struct, sys, zlib
out = sys.argv[1]
g = json.load(open(out + "/groundtruth.json"))
fr = g["frames"]
assert len(fr) == 6, len(fr)
assert fr[0]["x"] == -4.0 and fr[0]["y"] == 0.0 and abs(fr[0]["heading_deg"]) < 1e-9, fr[0]
assert abs(fr[-1]["y"] - 1.0) < 1e-9 and abs(fr[-1]["heading_deg"] - 90) < 1e-6, fr[-1]
for i, f in enumerate(fr):
    assert f["index"] == i and f["file"] == "frames/%06d.jpg" % i, f
# Frame 0 looks along +x from (-4, 0), 1.6 m up: the pixel just right of the centre of row 16 (elevation
# -2.8 deg) sees the far wall x = 5 at 9 m / cos(2.8 deg) / cos(2.8 deg azimuth); straight behind, x = -5 at 1 m.
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, sys.argv[2])
from png16 import read_png16
w, h, rows = read_png16(out + "/depth/000000.png")
assert (w, h) == (64, 32), (w, h)
def depth_mm(u, v):
    return rows[v][u]
import math
el = math.radians(90 - 16.5 / 32 * 180)
az = math.radians(32.5 / 64 * 360 - 180)
ahead = 9 / math.cos(el) / math.cos(az)
behind = 1 / math.cos(el) / math.cos(math.radians(0.5 / 64 * 360))
assert abs(depth_mm(32, 16) - 1000 * ahead) <= 2, (depth_mm(32, 16), ahead)
assert abs(depth_mm(0, 16) - 1000 * behind) <= 2, (depth_mm(0, 16), behind)
PY
"$cli" capture-info "$tmp/out/frames" > "$tmp/info.txt" 2>&1 || fail "the frames are no capture: $(cat "$tmp/info.txt")"

# Online sampling: the whole walk as coarse depth, full frames only for the keyframes; the capture is them.
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "-4,0 4,0 4,2" --step 0.25 --size 128x64 --online \
  --ratio 8 --coarse-width 64 --out "$tmp/online" --quiet || fail "render-scene --online exit $?"
python3 - "$tmp/online" <<'PY' || fail "online sampling output"
import json, os, sys
out = sys.argv[1]
r = json.load(open(out + "/online_sampling.json"))
assert r["path_frames"] == 41 and r["coarse_frames"] == 41 and r["coarse_width"] == 64, r
assert 2 <= r["full_frames"] <= 41 // 4 and r["full_frames"] == len(r["keyframes"]), r
g = json.load(open(out + "/groundtruth.json"))
assert [f["index"] for f in g["frames"]] == r["keyframes"], (g["frames"], r["keyframes"])
assert sorted(os.listdir(out + "/frames")) == ["%06d.jpg" % k for k in r["keyframes"]], os.listdir(out + "/frames")
assert len(os.listdir(out + "/depth")) == r["full_frames"]
PY

# Online with a loss target: the fewest keyframes whose loss on the coarse depth's envelopes meets it.
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "-4,0 4,0 4,2" --step 0.25 --size 128x64 --online \
  --loss-target 0.08 --coarse-width 64 --out "$tmp/target" --quiet || fail "render-scene --loss-target exit $?"
python3 - "$tmp/target" <<'PY' || fail "online sampling with a loss target"
import json, sys
r = json.load(open(sys.argv[1] + "/online_sampling.json"))
assert r["loss_target"] == 0.08 and r["loss_target_met"] and r["loss_mean"] <= 0.08, r
assert 1 <= r["full_frames"] < 41 and r["full_frames"] == len(r["keyframes"]), r
PY
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "0,0 1,0" --loss-target 0.1 --out "$tmp/e6" 2> "$tmp/err" \
  && fail "--loss-target without --online accepted"
grep -q -- "--online" "$tmp/err" || fail "loss target error: $(cat "$tmp/err")"

# Into a project, as the studio's Process > Render CG scene does: its plan (drawn by ezdxf, not by us), the
# frames as its capture and their true poses as its path; then sampled and exported from the command line.
/usr/bin/python3 - "$tmp/room.dxf" <<'PY' || fail "ezdxf could not write the room's plan"
import sys, ezdxf
doc = ezdxf.new("R2010")
doc.header["$INSUNITS"] = 6  # metres
doc.layers.add("WALLS")
doc.modelspace().add_lwpolyline([(-5, -3), (5, -3), (5, 3), (-5, 3)], close=True, dxfattribs={"layer": "WALLS"})
doc.saveas(sys.argv[1])
PY
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "-4,0 4,0 4,2" --step 0.25 --size 128x64 \
  --project "$tmp/room.plenopath" --plan "$tmp/room.dxf" --out "$tmp/proj-capture" --quiet \
  || fail "render-scene --project exit $?"
"$cli" info "$tmp/room.plenopath" --json > "$tmp/info.json" || fail "info on the rendered project"
python3 - "$tmp/info.json" <<'PY' || fail "the rendered project: $(cat "$tmp/info.json")"
import json, sys
i = json.load(open(sys.argv[1]))
assert i["capture"]["frames"] == 41 and i["capture"]["depth"] and i["capture"]["size"] == [128, 64], i
assert i["path"]["frames"] == 41 and abs(i["path"]["length_m"] - 10.0) < 1e-6, i["path"]
assert i["path"]["scale_source"] == "ground_truth", i["path"]
assert i["plan"]["occluder_segments"] == 4, i["plan"]
PY
"$cli" sample --project "$tmp/room.plenopath" --method depth --count 4 --save --json > "$tmp/sample.json" \
  || fail "sample on the rendered project"
"$cli" export --project "$tmp/room.plenopath" --out "$tmp/room-tour.zip" > /dev/null \
  || fail "export of the rendered project"
python3 - "$tmp/room-tour.zip" <<'PY' || fail "the exported tour"
import json, sys, zipfile
z = zipfile.ZipFile(sys.argv[1])
assert z.testzip() is None
tour = json.loads(z.read("tour.json"))
assert len(tour["keyframes"]) == 4, len(tour["keyframes"])
PY
# Online into a project, its plan cut from the render itself: the keyframes are there, so it exports at once.
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "-4,0 4,0 4,2" --step 0.25 --size 128x64 --online \
  --ratio 8 --coarse-width 128 --project "$tmp/online.plenopath" --section-plan --out "$tmp/online-capture" \
  --quiet || fail "render-scene --online --project --section-plan exit $?"
"$cli" info "$tmp/online.plenopath" --json > "$tmp/info2.json" || fail "info on the online project"
python3 - "$tmp/info2.json" <<'PY' || fail "the online project: $(cat "$tmp/info2.json")"
import json, sys
i = json.load(open(sys.argv[1]))
assert i["keyframes"]["count"] == i["capture"]["frames"] == i["path"]["frames"] >= 2, i
assert i["keyframes"]["method"] == "depth", i["keyframes"]
assert i["plan"]["occluder_segments"] >= 4, i["plan"]
PY
"$cli" export --project "$tmp/online.plenopath" --out "$tmp/online-tour" > /dev/null \
  || fail "export of the online project"
[[ -f "$tmp/online-tour/tour.json" ]] || fail "no tour.json in the online export"
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "0,0 1,0" --project "$tmp/e8.plenopath" --section-plan \
  --plan "$tmp/room.dxf" --out "$tmp/e8" 2> "$tmp/err" && fail "--section-plan with --plan accepted"
grep -q "choose one" "$tmp/err" || fail "section plan and plan error: $(cat "$tmp/err")"

# Again without a path: the render follows the project's own path, and the project is updated.
"$cli" render-scene --scene "$tmp/room.pov" --size 128x64 --no-depth --project "$tmp/room.plenopath" \
  --out "$tmp/proj-again" --quiet || fail "render-scene along the project's path exit $?"
[[ $(ls "$tmp/proj-again/frames" | wc -l) -eq 41 ]] || fail "the project's path was not followed"
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "0,0 1,0" --plan "$tmp/room.dxf" --out "$tmp/e7" \
  2> "$tmp/err" && fail "--plan without --project accepted"
grep -q -- "--project" "$tmp/err" || fail "plan without project error: $(cat "$tmp/err")"

# Errors: a missing scene, a broken one, no path, a size that is not 2:1, no povray.
"$cli" render-scene --scene "$tmp/missing.pov" --waypoints "0,0 1,0" --out "$tmp/e1" 2> "$tmp/err" && fail "missing scene accepted"
grep -q "missing.pov" "$tmp/err" || fail "missing scene error: $(cat "$tmp/err")"
echo 'sphere { 0, 1' > "$tmp/broken.pov"
"$cli" render-scene --scene "$tmp/broken.pov" --waypoints "0,0 1,0" --size 32x16 --out "$tmp/e2" 2> "$tmp/err" \
  && fail "broken scene accepted"
grep -q "POV-Ray failed on .*broken.pov" "$tmp/err" || fail "broken scene error: $(cat "$tmp/err")"
"$cli" render-scene --scene "$tmp/room.pov" --out "$tmp/e3" 2> "$tmp/err" && fail "no path accepted"
grep -q -- "--waypoints" "$tmp/err" || fail "no path error: $(cat "$tmp/err")"
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "0,0 1,0" --size 64x64 --out "$tmp/e4" 2> "$tmp/err" \
  && fail "square size accepted"
grep -q "2:1" "$tmp/err" || fail "size error: $(cat "$tmp/err")"
"$cli" render-scene --scene "$tmp/room.pov" --waypoints "0,0 1,0" --povray no-such-povray --out "$tmp/e5" 2> "$tmp/err" \
  && fail "missing povray accepted"
grep -q "apt-get install povray" "$tmp/err" || fail "no povray error: $(cat "$tmp/err")"
[[ ! -e "$tmp/e5" ]] || fail "output written although povray is missing"
echo "render-scene: ok"
