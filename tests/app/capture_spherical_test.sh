#!/usr/bin/env bash
# `plenopath capture-info` on 360 video: Spherical Video V2 metadata (projection, stereo, initial view) shown
# in text and JSON, a plain video said to have none, damaged metadata reported without failing; a variable
# frame rate video flagged. Needs ffmpeg and python3 (cmake/install-deps.sh): fails, never skips, without.
set -u
cli=$1
src=$3
fail() { echo "FAIL: $*"; exit 1; }
command -v ffmpeg > /dev/null || fail "ffmpeg is needed (cmake/install-deps.sh installs it)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
writer="$src/tests/processing/capture/spherical_mp4_writer.py"

ffmpeg -v error -f lavfi -i testsrc=size=256x128:rate=25 -frames:v 12 -c:v libx264 -pix_fmt yuv420p \
  "$tmp/plain.mp4" || fail "ffmpeg cannot make a test video"
python3 "$writer" "$tmp/plain.mp4" "$tmp/360.mp4" --v2 --yaw 90 --pitch -10 --roll 2.5 --stereo 0 \
  || fail "cannot add spherical metadata"

"$cli" capture-info "$tmp/360.mp4" --json > "$tmp/360.json" 2> "$tmp/err.txt" \
  || fail "capture-info exit $?: $(cat "$tmp/err.txt")"
python3 - "$tmp/360.json" <<'PY' || fail "360 json: $(cat "$tmp/360.json")"
import json, sys
s = json.load(open(sys.argv[1]))
v = s["spherical"]
assert s["frames"] == 12 and s["variable_frame_rate"] is False, s
assert v["metadata"] == "Spherical Video V2" and v["projection"] == "equirectangular", v
assert v["equirectangular"] is True and v["stereo"] == "mono", v
assert (v["yaw_deg"], v["pitch_deg"], v["roll_deg"]) == (90, -10, 2.5), v
PY
"$cli" capture-info "$tmp/360.mp4" > "$tmp/360.txt" || fail "capture-info text exit $?"
grep -q "^360       equirectangular, mono (Spherical Video V2); initial view yaw 90.000°, pitch -10.000°, roll 2.500°" \
  "$tmp/360.txt" || fail "360 text: $(cat "$tmp/360.txt")"

"$cli" capture-info "$tmp/plain.mp4" > "$tmp/plain.txt" || fail "plain exit $?"
grep -q "^360       no spherical metadata" "$tmp/plain.txt" || fail "plain text: $(cat "$tmp/plain.txt")"

# A damaged sv3d box: the frames are still fine, so the command succeeds and says what is wrong.
python3 - "$tmp/360.mp4" "$tmp/damaged.mp4" <<'PY' || fail "cannot damage the file"
import sys
data = bytearray(open(sys.argv[1], "rb").read())
at = data.find(b"sv3d")
data[at - 4] = 0x7f
open(sys.argv[2], "wb").write(data)
PY
"$cli" capture-info "$tmp/damaged.mp4" --json > "$tmp/damaged.json" || fail "damaged exit $?"
python3 -c "import json,sys; v=json.load(open(sys.argv[1]))['spherical']; assert 'damaged.mp4' in v['error'] and \"'sv3d'\" in v['error'], v" \
  "$tmp/damaged.json" || fail "damaged json: $(cat "$tmp/damaged.json")"

# Variable frame rate: 10 frames at 25 fps, then 10 at 5 fps.
ffmpeg -v error -f lavfi -i testsrc=size=256x128:rate=25 -frames:v 20 \
  -vf "settb=1/1000,setpts='if(lt(N\,10)\,N/25\,0.4+(N-10)/5)/TB'" -fps_mode passthrough -enc_time_base 1/1000 \
  -c:v libx264 -pix_fmt yuv420p "$tmp/vfr.mp4" || fail "ffmpeg cannot make a variable-rate video"
"$cli" capture-info "$tmp/vfr.mp4" --json > "$tmp/vfr.json" || fail "vfr exit $?"
python3 -c "import json,sys; s=json.load(open(sys.argv[1])); assert s['variable_frame_rate'] is True and abs(s['duration_s'] - 2.2) < 1e-3, s" \
  "$tmp/vfr.json" || fail "vfr json: $(cat "$tmp/vfr.json")"
echo "ok"
