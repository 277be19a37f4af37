#!/usr/bin/env bash
# `plenopath render`, `stitch` and `sample`: outputs and ground truth, bit-for-bit re-rendering from
# groundtruth.json, depth PNGs, per-head rig images stitched back, and clear errors for bad input.
set -u
cli=$1; data=$2
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$cli" make-sample --out "$tmp/sample" --frames 20 > "$tmp/sample.txt" || fail "sample exit $?"
for f in office.dxf office_path.json office.plenopath; do [[ -s "$tmp/sample/$f" ]] || fail "sample did not write $f"; done
grep -q '^\$INSUNITS' "$tmp/sample/office.dxf" || grep -q 'INSUNITS' "$tmp/sample/office.dxf" || fail "no \$INSUNITS"
for layer in WALLS COLUMNS DOORS FURNITURE TEXT; do grep -qx "$layer" "$tmp/sample/office.dxf" || fail "layer $layer missing"; done
grep -qx "INSERT" "$tmp/sample/office.dxf" || fail "no block inserts"
grep -qx "ARC" "$tmp/sample/office.dxf" || fail "no door arcs"

# Render with realism switches on, from the DXF, then again from the ground truth it wrote.
args=(--plan "$tmp/sample/office.dxf" --size 128x64 --depth --people 2 --noise 1.5 --exposure-drift 0.1 --quiet)
"$cli" render "${args[@]}" --path "$tmp/sample/office_path.json" --frames 6 --out "$tmp/a" || fail "render exit $?"
[[ $(ls "$tmp/a/frames" | wc -l) -eq 6 ]] || fail "expected 6 frames, got $(ls "$tmp/a/frames")"
[[ $(ls "$tmp/a/depth" | wc -l) -eq 6 ]] || fail "expected 6 depth maps"
python3 - "$tmp/a/groundtruth.json" <<'PY' || fail "groundtruth content"
import json, sys
g = json.load(open(sys.argv[1]))
assert g["units"] == "m", g
fr = g["frames"]
assert len(fr) == 6, len(fr)
for i, f in enumerate(fr):
    assert f["index"] == i and f["file"] == "frames/%06d.jpg" % i, f
    assert -180 <= f["heading_deg"] <= 180
PY
"$cli" render "${args[@]}" --path "$tmp/a/groundtruth.json" --out "$tmp/b" || fail "re-render exit $?"
for f in "$tmp"/a/frames/* "$tmp"/a/depth/*; do
  cmp -s "$f" "$tmp/b/${f#$tmp/a/}" || fail "re-render differs: ${f#$tmp/a/}"
done
python3 - "$tmp/a/depth/000003.png" <<'PY' || fail "depth png"
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n"
w, h, depth, colour = struct.unpack(">IIBB", data[16:26])
assert (w, h, depth, colour) == (128, 64, 16, 0), (w, h, depth, colour)
PY

# The capture nuisances, and the JPEG quality honoured: the same frames at quality 30 are much smaller than
# at 95 (and differ), frame by frame.
nuis=(--plan office-sample --path "$tmp/a/groundtruth.json" --frames 3 --size 256x128 --trolley --operator
      --tilt-wobble 1.0 --bumps 1.5 --exposure-jump 0.3 --plain-walls --quiet)
"$cli" render "${nuis[@]}" --jpeg-quality 95 --out "$tmp/q95" || fail "nuisance render exit $?"
"$cli" render "${nuis[@]}" --jpeg-quality 30 --out "$tmp/q30" || fail "nuisance render (q30) exit $?"
for f in "$tmp"/q95/frames/*; do
  hi=$(stat -c %s "$f"); lo=$(stat -c %s "$tmp/q30/frames/$(basename "$f")")
  (( lo * 3 < hi * 2 )) || fail "jpeg quality not honoured: $(basename "$f") q30 $lo bytes vs q95 $hi bytes"
done
"$cli" render --plan office-sample --tilt-wobble -1 --out "$tmp/f" --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "bad tilt: exit $code"
grep -q "tilt_wobble_deg" "$tmp/err.txt" || fail "bad tilt message: $(cat "$tmp/err.txt")"

# Auto path with a step, and the built-in sample plan.
"$cli" render --plan office-sample --auto-path --step 0.2 --frames 3 --size 64x32 --out "$tmp/c" --quiet || fail "auto path exit $?"
[[ $(ls "$tmp/c/frames" | wc -l) -eq 3 ]] || fail "auto path frames"

# A small rig: per-head images, stitched back.
python3 - "$tmp/rig.json" <<'PY'
import json, math, sys
heads = []
for i in range(4):
    heads.append({"name": "h%d" % i, "width": 40, "height": 60, "fx": 20 / math.tan(math.radians(50)),
                  "fy": 30 / math.tan(math.radians(60)), "yaw_deg": 90 * i})
for name, pitch in (("up", 90), ("down", -90)):
    heads.append({"name": name, "width": 40, "height": 40, "fx": 20 / math.tan(math.radians(55)),
                  "fy": 20 / math.tan(math.radians(55)), "pitch_deg": pitch})
json.dump({"format": "plenopath-rig", "version": 1, "heads": heads}, open(sys.argv[1], "w"))
PY
"$cli" render --plan office-sample --path "$tmp/a/groundtruth.json" --frames 2 --rig "$tmp/rig.json" --out "$tmp/d" --quiet \
  || fail "rig render exit $?"
[[ -f "$tmp/d/heads/h2/000001.jpg" && -f "$tmp/d/heads/down/000000.jpg" ]] || fail "per-head images missing"
"$cli" stitch --rig "$tmp/rig.json" --in "$tmp/d" --out "$tmp/e" --size 128x64 --quiet || fail "stitch exit $?"
[[ -f "$tmp/e/frames/000001.jpg" && -f "$tmp/e/groundtruth.json" ]] || fail "stitch outputs missing"

# Errors: exit 1 with the file named; usage errors exit 2.
"$cli" render --plan "$tmp/absent.dxf" --out "$tmp/f" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "missing plan: exit $code"
grep -q "absent.dxf" "$tmp/err.txt" || fail "missing plan message: $(cat "$tmp/err.txt")"
echo '{"units":"m","frames":[{"index":0,"x":"a","y":0,"heading_deg":0}]}' > "$tmp/bad_path.json"
"$cli" render --plan office-sample --path "$tmp/bad_path.json" --out "$tmp/f" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "bad path: exit $code"
grep -q "bad_path.json" "$tmp/err.txt" || fail "bad path message: $(cat "$tmp/err.txt")"
"$cli" render --plan office-sample --size 12 --out "$tmp/f" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "bad size: exit $code"
grep -q "WIDTHxHEIGHT" "$tmp/err.txt" || fail "bad size message: $(cat "$tmp/err.txt")"
"$cli" render --plan office-sample --path "$tmp/a/groundtruth.json" --auto-path --out "$tmp/f" 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "--path with --auto-path: exit $code"
echo '{"heads":[{"name":"x","width":10}]}' > "$tmp/bad_rig.json"
"$cli" stitch --rig "$tmp/bad_rig.json" --in "$tmp/d" --out "$tmp/g" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "bad rig: exit $code"
grep -q "bad_rig.json" "$tmp/err.txt" || fail "bad rig message: $(cat "$tmp/err.txt")"
"$cli" stitch --rig "$tmp/rig.json" --in "$tmp/nothing" --out "$tmp/g" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "missing heads: exit $code"
echo "ok"
