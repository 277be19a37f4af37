#!/usr/bin/env bash
# `plenopath track` on tripod stills (issue 20): six rendered stills 1.6-3.4 m apart at random headings are
# recognised as stills by themselves, solved within 1 cm / 0.2 deg of the truth at metric scale from the
# camera height (eval-path), `--stills` forces the same, and bad use gets a clear error.
set -u
cli=$1
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

python3 - "$tmp" <<'PY'
import json, random, sys
random.seed(3)
pos = [(2.6, 9.4), (4.6, 9.6), (5.5, 11.2), (3.0, 12.6), (5.2, 12.9), (2.5, 11.0)]
frames = [{"index": i, "x": x, "y": y, "heading_deg": random.uniform(-180, 180)} for i, (x, y) in enumerate(pos)]
json.dump({"units": "m", "frames": frames}, open(sys.argv[1] + "/path.json", "w"))
PY
# 16 m texture tiles: the default 4 m tiles repeat within the room, which aliases wide-baseline matching.
"$cli" render --plan office-sample --path "$tmp/path.json" --size 1024x512 --texture-size 2048 \
  --texels-per-metre 128 --out "$tmp/r" --quiet || fail "render exit $?"

"$cli" track --capture "$tmp/r/frames" --camera-height 1.6 --work-width 1024 --out "$tmp/est.json" --json \
  > "$tmp/t.json" 2> "$tmp/t.err" || fail "track exit $?: $(tail -c 600 "$tmp/t.err")"
grep -aq "looks like still panoramas" "$tmp/t.err" || fail "no word of the switch to stills: $(tail -c 600 "$tmp/t.err")"
python3 - "$tmp/t.json" <<'PY' || fail "track json: $(cat "$tmp/t.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["mode"] == "stills", j["mode"]
s = j["stills"]
assert s["connected"] == 6 and s["unconnected"] == [], s
assert s["detection"]["followed_fraction"] < 0.35, s
assert j["scale_source"] == "camera_height", j
assert j["frames"] == 6 and j["keyframes"] == 6, j
PY
"$cli" eval-path --estimate "$tmp/est.json" --truth "$tmp/r/groundtruth.json" --json > "$tmp/e.json" ||
  fail "eval-path exit $?"
python3 - "$tmp/e.json" <<'PY' || fail "stills off the truth: $(cat "$tmp/e.json")"
import json, sys
e = json.load(open(sys.argv[1]))
assert e["frames_matched"] == 6, e
assert e["ate_max_m"] < 0.01 and e["rot_max_deg"] < 0.2, e
assert abs(e["scale_error_pct"]) < 2, e
PY
[[ -s "$tmp/est.points.json" ]] || fail "no points file beside the path"

# --stills forces the pipeline (no detection in the summary), without a height it says what it assumed.
"$cli" track --stills "$tmp/r/frames" --work-width 1024 --json > "$tmp/f.json" 2> "$tmp/f.err" ||
  fail "--stills exit $?: $(tail -c 600 "$tmp/f.err")"
grep -aq "no --camera-height given" "$tmp/f.err" || fail "no word of the assumed height"
python3 - "$tmp/f.json" <<'PY' || fail "--stills json: $(cat "$tmp/f.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["mode"] == "stills" and "detection" not in j["stills"], j
assert j["stills"]["camera_height_given"] is False, j
PY

# Stills come in the order they were shot: JPEGs named in reverse, EXIF times (ExifTool) in the true order.
mkdir -p "$tmp/shot"
k=0
for f in $(ls "$tmp/r/frames" | sort); do
  name=$(printf "IMG_%02d.jpg" $((5 - k)))
  convert "$tmp/r/frames/$f" -quality 95 "$tmp/shot/$name" || fail "convert $f"
  exiftool -q -q -overwrite_original "-DateTimeOriginal=2026:11:30 10:0$k:00" "$tmp/shot/$name" ||
    fail "exiftool $name"
  k=$((k + 1))
done
"$cli" track --stills "$tmp/shot" --camera-height 1.6 --work-width 1024 --out "$tmp/shot.json" --json \
  > "$tmp/s.json" 2> "$tmp/s.err" || fail "--stills on JPEGs exit $?: $(tail -c 600 "$tmp/s.err")"
grep -aq "stills ordered by EXIF DateTimeOriginal" "$tmp/s.err" || fail "no word of the order: $(cat "$tmp/s.err")"
python3 - "$tmp/s.json" "$tmp/shot.json" <<'PY' || fail "stills by time: $(cat "$tmp/s.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["stills"]["capture_order"]["order"] == "by EXIF DateTimeOriginal", j["stills"]
assert j["stills"]["connected"] == 6, j["stills"]
names = [f["file"] for f in json.load(open(sys.argv[2]))["frames"]]
assert names == ["IMG_%02d.jpg" % (5 - k) for k in range(6)], names
PY
"$cli" eval-path --estimate "$tmp/shot.json" --truth "$tmp/r/groundtruth.json" --json > "$tmp/se.json" ||
  fail "eval-path (by time) exit $?"
python3 - "$tmp/se.json" <<'PY' || fail "stills by time off the truth: $(cat "$tmp/se.json")"
import json, sys
e = json.load(open(sys.argv[1]))
assert e["frames_matched"] == 6 and e["ate_max_m"] < 0.02 and e["rot_max_deg"] < 0.3, e
PY

# On the plan, with a seventh still that shows nothing (a lens cap): the six are placed, the seventh is
# listed as unplaced with why.
"$cli" make-sample --out "$tmp/sample" --frames 10 > /dev/null || fail "make-sample exit $?"
mkdir -p "$tmp/capped"
cp "$tmp"/r/frames/* "$tmp/capped/"
convert -size 1024x512 xc:gray40 "$tmp/capped/zz_cap.png" || fail "convert cap"
"$cli" track --stills "$tmp/capped" --camera-height 1.6 --work-width 1024 --plan "$tmp/sample/office.dxf" \
  --out "$tmp/capped.json" --json > "$tmp/c.json" 2> "$tmp/c.err" ||
  fail "--stills --plan exit $?: $(tail -c 600 "$tmp/c.err")"
python3 - "$tmp/c.json" <<'PY' || fail "unplaced still not explained: $(cat "$tmp/c.json")"
import json, sys
r = json.load(open(sys.argv[1]))["registration"]
assert r["unplaced_stills"] == ["zz_cap.png"], r["unplaced_stills"]
assert len(r["unplaced_why"]) == 1 and r["unplaced_why"][0]["still"] == 6 and r["unplaced_why"][0]["why"], r
PY

# Bad use.
out=$("$cli" track 2>&1) && fail "track without input succeeded"
[[ $out == *"--capture"*"--stills"* ]] || fail "unclear message: $out"
out=$("$cli" track --stills "$tmp/nowhere" 2>&1) && fail "--stills on a missing folder succeeded"
[[ $out == *nowhere* ]] || fail "message does not name the folder: $out"
echo "stills: ok"
