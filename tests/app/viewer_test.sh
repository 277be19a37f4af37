#!/usr/bin/env bash
# `plenopath export --multires --pannellum --marzipano --psv` read by the real viewers: Pannellum, Marzipano
# and Photo Sphere Viewer (virtual-tour and map plugins), installed from npm at test time into
# ${XDG_CACHE_HOME:-$HOME/.cache}/plenopath-npm (once, then reused), each in headless Chromium over a local
# http server (tests/app/viewer_check.py). The capture: three panoramas with coloured marks at known
# directions (tests/app/viewer_marks.py). Skips (exit 77) without chromium, npm or the registry.
# PLENOPATH_KEEP_TEST_OUTPUT=1 keeps the package and the screenshots.
set -u
cli=$1; src=${3:-$(cd "$(dirname "$0")/../.." && pwd)}
fail() { echo "FAIL: $*"; exit 1; }
skip() { echo "SKIP: $*"; exit 77; }
command -v chromium > /dev/null || skip "chromium is not installed"
command -v npm > /dev/null || skip "npm is not installed"

# The viewers, pinned: the versions this test was written against (PSV's plugins must match its core,
# and its core wants three 0.185).
npm_dir=${XDG_CACHE_HOME:-$HOME/.cache}/plenopath-npm
packages="pannellum@2.5.7 marzipano@0.10.2 @photo-sphere-viewer/core@5.15.1
  @photo-sphere-viewer/virtual-tour-plugin@5.15.1 @photo-sphere-viewer/map-plugin@5.15.1
  @photo-sphere-viewer/markers-plugin@5.15.1 three@0.185.1"
stamp="$npm_dir/.installed"
if [[ "$(cat "$stamp" 2> /dev/null)" != "$(echo $packages)" ]]; then
  mkdir -p "$npm_dir" || fail "cannot create $npm_dir"
  # shellcheck disable=SC2086
  log=$(mktemp)
  if ! timeout 300 npm install --prefix "$npm_dir" --no-audit --no-fund --no-save --fetch-retries=1 \
      $packages > "$log" 2>&1; then
    reason=$(grep -m1 -E "code E|errno|network" "$log")
    rm -f "$log"
    skip "npm cannot install the viewers from $(npm config get registry) (${reason:-no reason given})"
  fi
  rm -f "$log"
  echo $packages > "$stamp"
fi

if [[ -n "${PLENOPATH_KEEP_TEST_OUTPUT:-}" ]]; then
  tmp=$(mktemp -d); echo "output kept in $tmp"
else
  tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fi

# Three frames in a 4 m x 3 m room: k0 at (1, 1.5) facing east, k1 at (2, 1.5) facing north, k2 at
# (3, 1.5) facing east. 2048 px wide with tiles of at most 256 px: faces of 512 px, levels 128 (fallback),
# 256 (one tile a face), 512 (four tiles a face).
python3 - "$tmp" "$src/tests/app" <<'PY' || fail "making the capture"
import json, os, sys
sys.path.insert(0, sys.argv[2])
import viewer_marks as vm
out = sys.argv[1]
os.makedirs(out + '/frames')
frames = [(0, 1.0, 1.5, 0.0), (1, 2.0, 1.5, 90.0), (2, 3.0, 1.5, 0.0)]
for i, x, y, h in frames:
    vm.write_png('%s/frames/%06d.png' % (out, i), vm.draw(2048, vm.marks_of_frame(h, i == 0)))
project = {
  "format": "plenopath-project", "version": 1,
  "plan": {"units": "m", "layers": [{"name": "WALLS", "occluder": True}],
           "segments": [{"a": a, "b": b, "layer": "WALLS", "occluder": True}
                        for a, b in [([0, 0], [4, 0]), ([4, 0], [4, 3]), ([4, 3], [0, 3]), ([0, 3], [0, 0])]]},
  "path": {"units": "m", "frames": [{"index": i, "x": x, "y": y, "heading_deg": h} for i, x, y, h in frames]},
  "capture": {"kind": "image_folder", "source": "frames", "frame_count": 3, "width": 2048, "height": 1024,
              "frame_names": ["%06d.png" % i for i, _, _, _ in frames], "camera_height_m": 1.6},
  "keyframes": {"indices": [0, 1, 2], "rank": [0, 2, 1], "pinned": []},
  # A note on the north wall seen from every keyframe (never on a mark), with a link out.
  "hotspots": [{"id": "note", "kind": "event", "title": "North <b>wall</b>", "media": "", "frame": 0,
                "image_corners_deg": [[-113, 5], [-103, 5], [-103, -5], [-113, -5]],
                "world_corners": [[0.3, 3.0, 1.7], [0.7, 3.0, 1.7], [0.7, 3.0, 1.5], [0.3, 3.0, 1.5]],
                "trigger": "click", "trigger_distance_m": 0, "action": "open_url",
                "action_target": "https://example.org/"}],
  "tour": {"title": "Viewer check"}}
json.dump(project, open(out + '/tour.plenopath', 'w'), indent=1)
PY

"$cli" export --project "$tmp/tour.plenopath" --out "$tmp/tour" --max-size 2048 --preview-size 512 \
  --tile-size 256 --multires --pannellum --marzipano --psv --http-only > "$tmp/export.txt" 2>&1 \
  || fail "export: $(cat "$tmp/export.txt")"
for f in tiles/k000000/0/f/0_0.jpg tiles/k000000/1/u/0_0.jpg tiles/k000002/2/d/1_1.jpg pannellum.json \
         marzipano.html marzipano-app.js marzipano-data.js psv.json; do
  [[ -f "$tmp/tour/$f" ]] || fail "missing $f"
done
[[ ! -e "$tmp/tour/tiles/k000000/2/f/2_0.jpg" ]] || fail "level 2 has more than 2x2 tiles a face"

shots=${PLENOPATH_VIEWER_SHOTS:-$tmp/shots}
mkdir -p "$shots"
python3 "$src/tests/app/viewer_check.py" "$tmp/tour" "$npm_dir/node_modules" "$shots" || fail "viewer check"
echo ok
