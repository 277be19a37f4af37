#!/usr/bin/env bash
# `plenopath capture-info`: frame count, size, skipped frames with reasons, depth and GPS matches, errors.
set -u
cli=$1
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# A folder of 2:1 PNG frames f1..f12 (natural order), f5 missing, f7 garbage; depth for f1 and f2; a GPX.
mkdir -p "$tmp/frames" "$tmp/depth"
python3 - "$tmp" <<'PY' || fail "cannot write test frames"
import struct, sys, zlib
root = sys.argv[1]
def png(path, w, h, bit_depth=8, colour_type=2):
    channels = 3 if colour_type == 2 else 1
    row = b"\x00" + b"\x40" * (w * channels * bit_depth // 8)
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, bit_depth, colour_type, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(row * h)) + chunk(b"IEND", b"")
    open(path, "wb").write(data)
for k in range(1, 13):
    if k == 5: continue
    png(f"{root}/frames/f{k}.png", 64, 32)
open(f"{root}/frames/f7.png", "wb").write(b"garbage, not a PNG")
png(f"{root}/depth/f1.png", 64, 32, 16, 0)
png(f"{root}/depth/f2.png", 64, 32, 16, 0)
pts = "".join(f'<trkpt lat="47.0000{k}" lon="8.5"><time>2024-05-01T10:00:0{k}Z</time></trkpt>' for k in range(3))
open(f"{root}/track.gpx", "w").write(f'<?xml version="1.0"?><gpx version="1.1"><trk><trkseg>{pts}</trkseg></trk></gpx>')
PY

"$cli" capture-info "$tmp/frames" --depth "$tmp/depth" --gpx "$tmp/track.gpx" --rate 2 --json > "$tmp/out.json" \
  || fail "capture-info exit $?"
python3 - "$tmp/out.json" <<'PY' || fail "json content: $(cat "$tmp/out.json")"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["kind"] == "image_folder", s
assert s["frames"] == 10, s            # 12 numbers, one missing, one corrupt
assert s["size"] == [64, 32], s
assert s["first_name"] == "f1.png" and s["last_name"] == "f12.png", s
reasons = {k["name"]: k["reason"] for k in s["skipped"]}
assert "missing" in reasons["f5.png"], reasons
assert "not a JPEG, PNG" in reasons["f7.png"], reasons
assert s["depth"]["matched"] == 2 and s["depth"]["unmatched"] == 8, s
# 2 fps from f1 at t=0; GPS covers 0..2 s (+0.5 s tolerance): frames f1..f6 (f5 missing) -> f1,f2,f3,f4,f6.
assert s["gps"]["samples"] == 3, s
assert s["gps"]["frames_matched"] == 5, s
PY

"$cli" capture-info "$tmp/frames" --first 2 --stride 2 > "$tmp/out.txt" || fail "text exit $?"
grep -q "Frames" "$tmp/out.txt" || fail "text output: $(cat "$tmp/out.txt")"

# Wrong aspect: a clear message naming the folder; exit 1. --any-aspect accepts it.
mkdir -p "$tmp/wide"
python3 -c "
import struct, zlib, sys
w, h = 160, 90
row = b'\x00' + b'\x10' * (w * 3)
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
open(sys.argv[1], 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0)) + chunk(b'IDAT', zlib.compress(row * h)) + chunk(b'IEND', b''))
" "$tmp/wide/a.png"
"$cli" capture-info "$tmp/wide" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "wrong aspect: exit $code"
grep -q "not 2:1" "$tmp/err.txt" || fail "aspect message: $(cat "$tmp/err.txt")"
grep -q "$tmp/wide" "$tmp/err.txt" || fail "aspect message names the folder: $(cat "$tmp/err.txt")"
"$cli" capture-info "$tmp/wide" --any-aspect --json > /dev/null || fail "--any-aspect exit $?"

"$cli" capture-info "$tmp/absent" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "missing source: exit $code"
grep -q "absent" "$tmp/err.txt" || fail "missing source message: $(cat "$tmp/err.txt")"
"$cli" capture-info "$tmp/frames" --stride 0 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "bad stride: exit $code"
echo "ok"
