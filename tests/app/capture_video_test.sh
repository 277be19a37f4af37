#!/usr/bin/env bash
# A rendered walk encoded as H.264 MP4 by `plenopath encode-video`, inspected by `capture-info` (count, size,
# rate, depth matched by frame number) and accepted by `plenopath track --capture VIDEO`.
set -u
cli=$1
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$cli" make-sample --out "$tmp/sample" --frames 10 > /dev/null || fail "sample exit $?"
"$cli" render --plan "$tmp/sample/office.dxf" --path "$tmp/sample/office_path.json" --frames 10 --size 256x128 \
  --depth --quiet --out "$tmp/r" > /dev/null || fail "render exit $?"
[[ $(ls "$tmp/r/frames" | wc -l) -eq 10 ]] || fail "render wrote $(ls "$tmp/r/frames" | wc -l) frames"

"$cli" encode-video "$tmp/r/frames" --out "$tmp/walk.mp4" --fps 25 --json > "$tmp/enc.json" 2> "$tmp/enc.err" \
  || fail "encode-video exit $?: $(cat "$tmp/enc.err")"
python3 - "$tmp/enc.json" <<'PY' || fail "encode-video json: $(cat "$tmp/enc.json")"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["frames_written"] == 10 and s["frames_failed"] == 0 and s["fourcc"] == "avc1", s
PY

"$cli" capture-info "$tmp/walk.mp4" --depth "$tmp/r/depth" --json > "$tmp/info.json" 2> "$tmp/info.err" \
  || fail "capture-info exit $?: $(cat "$tmp/info.err")"
python3 - "$tmp/info.json" <<'PY' || fail "capture-info json: $(cat "$tmp/info.json")"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["kind"] == "video", s
assert s["frames"] == 10 and s["size"] == [256, 128], s
assert abs(s["frame_rate"] - 25) < 1e-6, s
assert abs(s["duration_s"] - 9 / 25) < 1e-9, s
assert s["skipped"] == [], s
assert s["depth"]["matched"] == 10, s
PY

"$cli" capture-info "$tmp/walk.mp4" --first 2 --last 8 --stride 3 --json > "$tmp/range.json" || fail "range exit $?"
python3 -c "import json,sys; s=json.load(open(sys.argv[1])); assert s['frames'] == 3 and s['first_name'] == 'frame 2' and s['last_name'] == 'frame 8', s" \
  "$tmp/range.json" || fail "range: $(cat "$tmp/range.json")"

"$cli" track --capture "$tmp/walk.mp4" --quiet --work-width 256 --json > "$tmp/track.json" 2> "$tmp/track.err" \
  || fail "track on the video exit $?: $(cat "$tmp/track.err")"
python3 -c "import json,sys; s=json.load(open(sys.argv[1])); assert s['frames'] == 10, s" "$tmp/track.json" \
  || fail "track on the video: $(cat "$tmp/track.json")"

"$cli" encode-video "$tmp/r/frames" --out "$tmp/walk.mp4" --codec vp9 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "unknown codec: exit $code"
"$cli" encode-video "$tmp/r/frames" --out "$tmp/no-such-dir/walk.mp4" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "unwritable output: exit $code"
grep -q "no-such-dir/walk.mp4" "$tmp/err.txt" || fail "unwritable output message: $(cat "$tmp/err.txt")"
echo "ok"
