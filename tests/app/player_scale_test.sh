#!/usr/bin/env bash
# The web player at scale, in Debian's headless Chromium (tests/app/player_check.py): a tour of 4096x2048
# keyframes rendered by `plenopath render` and exported with --max-size 4096 plays with no page error; its
# frame time walking the path is printed (p50/p95); the gyroscope follows the screen orientation; the same
# tour with cube tiles (`export --multires`) changes tile level on zoom, its tiles in line with the panorama.
# Screenshots are left in player_scale/ of the build folder to look at. Skips (77) without chromium.
set -u
cli=$1; src=${3:-$(cd "$(dirname "$0")/../.." && pwd)}
fail() { echo "FAIL: $*"; exit 1; }
command -v chromium > /dev/null || { echo "skip: no chromium"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
shots=$PWD/player_scale; rm -rf "$shots"; mkdir -p "$shots"

"$cli" make-sample --out "$tmp/office" --frames 30 --size 4096x2048 > /dev/null || fail "make-sample exit $?"
"$cli" render --plan "$tmp/office/office.dxf" --path "$tmp/office/office_path.json" --size 4096x2048 --depth \
  --out "$tmp/office/capture" --quiet || fail "render exit $?"
"$cli" sample --project "$tmp/office/office.plenopath" --method uniform --count 6 --save > /dev/null \
  || fail "sample exit $?"
"$cli" export --project "$tmp/office/office.plenopath" --out "$tmp/tour" --max-size 4096 --preview-size 512 \
  > /dev/null || fail "export exit $?"
/usr/bin/python3 - "$tmp/tour" <<'PY' || fail "the exported keyframes are not 4096x2048"
import json, subprocess, sys
tour = json.load(open(sys.argv[1] + "/tour.json"))
for k in tour["keyframes"]:
    size = subprocess.run(["identify", "-format", "%w %h", sys.argv[1] + "/" + k["full"]], capture_output=True, text=True).stdout
    assert size == "4096 2048", (k["full"], size)
PY

/usr/bin/python3 "$src/tests/app/player_check.py" "$tmp/tour" "$shots/tour" --no-hotspots --gyro --frame-times \
  || fail "the 4096x2048 tour"

"$cli" export --project "$tmp/office/office.plenopath" --out "$tmp/tiled" --max-size 4096 --preview-size 512 \
  --multires --tile-size 256 > /dev/null || fail "export --multires exit $?"
/usr/bin/python3 "$src/tests/app/player_check.py" "$tmp/tiled" "$shots/tiled" --no-hotspots --multires \
  || fail "the tour with cube tiles"
echo ok
