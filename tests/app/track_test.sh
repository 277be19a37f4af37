#!/usr/bin/env bash
# `plenopath track` and `plenopath eval-path`: exit codes, progress on stderr, JSON output, a mirrored path
# scored as wrong, errors naming the file.
set -u
cli=$1; data=$2
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# eval-path on hand-made paths: an L-shaped truth, the same path scaled/rotated/moved, and its mirror image.
python3 - "$tmp" <<'PY'
import json, math, sys
d = sys.argv[1]
truth, est, mirror = [], [], []
for i in range(30):
    x, y, h = (0.1 * i, 0.0, 0.0) if i < 15 else (1.4, 0.1 * (i - 14), math.pi / 2)
    truth.append({"index": i, "x": x, "y": y, "heading_deg": math.degrees(h)})
    a = 0.5
    est.append({"index": i, "x": 2 * (math.cos(a) * x - math.sin(a) * y) + 3, "y": 2 * (math.sin(a) * x + math.cos(a) * y),
                "heading_deg": math.degrees(h + a)})
    mirror.append({"index": i, "x": x, "y": -y, "heading_deg": -math.degrees(h)})
for name, frames in (("truth", truth), ("est", est), ("mirror", mirror)):
    json.dump({"units": "m", "frames": frames}, open(f"{d}/{name}.json", "w"))
PY
"$cli" eval-path --estimate "$tmp/est.json" --truth "$tmp/truth.json" --json > "$tmp/e.json" || fail "eval-path exit $?"
python3 - "$tmp/e.json" <<'PY' || fail "eval-path json: $(cat "$tmp/e.json")"
import json, sys
e = json.load(open(sys.argv[1]))
assert e["frames_matched"] == 30, e
assert e["ate_rms_m"] < 1e-9 and e["rot_rms_deg"] < 1e-9, e
PY
"$cli" eval-path --estimate "$tmp/mirror.json" --truth "$tmp/truth.json" --json > "$tmp/m.json" || fail "mirror exit $?"
python3 - "$tmp/m.json" <<'PY' || fail "mirrored path scored well: $(cat "$tmp/m.json")"
import json, sys
e = json.load(open(sys.argv[1]))
assert e["ate_pct"] > 5 and e["rot_rms_deg"] > 20, e
PY
# An estimate in two pieces, each in a gauge of its own (the second rotated, scaled and moved by hand): the
# whole path scores badly, each piece on its own exactly.
python3 - "$tmp" <<'PY'
import json, math, sys
d = sys.argv[1]
truth = json.load(open(f"{d}/truth.json"))["frames"]
frames = []
for f in truth:
    piece = 0 if f["index"] < 15 else 1
    x, y, h = f["x"], f["y"], math.radians(f["heading_deg"])
    if piece == 1:
        a, s = 2.0, 0.5
        x, y, h = s * (math.cos(a) * x - math.sin(a) * y) - 7, s * (math.sin(a) * x + math.cos(a) * y) + 4, h + a
    frames.append({"index": f["index"], "x": x, "y": y, "heading_deg": math.degrees(h), "piece": piece})
pieces = [{"first_index": 0, "last_index": 14, "placed": True},
          {"first_index": 15, "last_index": 29, "placed": False, "break_reason": "by hand"}]
json.dump({"units": "m", "frames": frames, "pieces": pieces}, open(f"{d}/pieces.json", "w"))
PY
"$cli" eval-path --estimate "$tmp/pieces.json" --truth "$tmp/truth.json" --json > "$tmp/p.json" || fail "pieces exit $?"
python3 - "$tmp/p.json" <<'PY' || fail "eval-path pieces: $(cat "$tmp/p.json")"
import json, sys
e = json.load(open(sys.argv[1]))
assert e["ate_pct"] > 5, e
assert [p["piece"] for p in e["pieces"]] == [0, 1], e
assert [(p["first_index"], p["last_index"]) for p in e["pieces"]] == [(0, 14), (15, 29)], e
for p in e["pieces"]:
    assert p["frames_matched"] == 15 and p["ate_rms_m"] < 1e-9 and p["rot_rms_deg"] < 1e-9, p
assert abs(e["pieces"][1]["scale_error_pct"] - 50.0) < 1e-6, e  # the second piece's metres are half
PY
"$cli" eval-path --estimate "$tmp/absent.json" --truth "$tmp/truth.json" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "missing estimate: exit $code"
grep -q "absent.json" "$tmp/err.txt" || fail "missing estimate message: $(cat "$tmp/err.txt")"
# --match file: an estimate of every third frame, numbered 0, 1, ... among those kept (as `track --stride 3`
# numbers them), with the truth's image files: matched by name it scores exactly; by index, badly.
python3 - "$tmp" <<'PY'
import json, sys
d = sys.argv[1]
truth = json.load(open(f"{d}/truth.json"))["frames"]
for f in truth:
    f["file"] = "frames/%06d.png" % f["index"]
json.dump({"units": "m", "frames": truth}, open(f"{d}/truth_files.json", "w"))
kept = [dict(f, index=k, file="%06d.png" % f["index"]) for k, f in enumerate(truth[::3])]
kept.append({"index": len(kept), "file": "not_in_truth.png", "x": 50.0, "y": 0.0, "heading_deg": 0.0})
json.dump({"units": "m", "frames": kept}, open(f"{d}/strided.json", "w"))
nameless = [{k: v for k, v in f.items() if k != "file"} for f in kept]
json.dump({"units": "m", "frames": nameless}, open(f"{d}/nameless.json", "w"))
PY
"$cli" eval-path --estimate "$tmp/strided.json" --truth "$tmp/truth_files.json" --match file --json > "$tmp/s.json" \
  || fail "match file exit $?"
"$cli" eval-path --estimate "$tmp/strided.json" --truth "$tmp/truth_files.json" --json > "$tmp/si.json" \
  || fail "match index exit $?"
python3 - "$tmp/s.json" "$tmp/si.json" <<'PY' || fail "eval-path --match file: $(cat "$tmp/s.json" "$tmp/si.json")"
import json, sys
by_file, by_index = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert by_file["frames_matched"] == 10, by_file  # the frame whose file the truth lacks is left out
assert by_file["ate_rms_m"] < 1e-9 and by_file["rot_rms_deg"] < 1e-9, by_file
assert by_index["ate_pct"] > 5, by_index
PY
"$cli" eval-path --estimate "$tmp/nameless.json" --truth "$tmp/truth_files.json" --match file 2> "$tmp/err.txt"
code=$?
[[ $code -eq 1 ]] || fail "nameless estimate: exit $code"
grep -q "nameless.json.*no file name" "$tmp/err.txt" || fail "nameless message: $(cat "$tmp/err.txt")"
"$cli" eval-path --estimate "$tmp/strided.json" --truth "$tmp/truth_files.json" --match name 2> "$tmp/err.txt"
[[ $? -eq 2 ]] || fail "--match name: not refused"

# track on a tiny capture (three panoramas of the convention fixture, any names, natural order).
mkdir -p "$tmp/cap"
cp "$data/convention/pano_heading0.png" "$tmp/cap/f9.png"
cp "$data/convention/pano_heading30.png" "$tmp/cap/f10.png"
cp "$data/convention/pano_heading90.png" "$tmp/cap/f11.png"
"$cli" track --capture "$tmp/cap" --camera-height 1.6 --out "$tmp/path.json" --json > "$tmp/t.json" 2> "$tmp/progress.txt" \
  || fail "track exit $?: $(cat "$tmp/progress.txt")"
grep -q "track: frames" "$tmp/progress.txt" || fail "no progress on stderr: $(cat "$tmp/progress.txt")"
python3 - "$tmp/t.json" "$tmp/path.json" <<'PY' || fail "track output: $(cat "$tmp/t.json")"
import json, sys
s = json.load(open(sys.argv[1]))
p = json.load(open(sys.argv[2]))
assert s["frames"] == 3, s
assert s["loop_closures"] == 0 and s["loop_frames"] == [], s  # three frames: nowhere to come back to
assert 0 <= s["tilt_prior_deg"] <= 2.0, s  # the tilt prior the last global pass used, within its bounds
assert 0 <= s["floor_prior_pct"] <= 1.0, s  # the floor prior's spread the last pass used (0: no floor points)
assert 0 <= s["steps_on_floor"] < s["keyframes"] and 0 <= s["steps_from_points"] < s["keyframes"], s
# Flag counts as the path file's flags say (16 = bridged, 8 = moving objects); a warning past 20 % bridged.
assert s["flag_counts"]["bridged"] == sum(1 for f in p["frames"] if f.get("flags", 0) & 16), (s, p)
assert s["flag_counts"]["moving_objects"] == sum(1 for f in p["frames"] if f.get("flags", 0) & 8), (s, p)
assert s["reliable"] == (s["flag_counts"]["bridged"] <= 0.2 * s["frames"]) and ("warning" in s) != s["reliable"], s
assert [f["file"] for f in p["frames"]] == ["f9.png", "f10.png", "f11.png"], p
assert p["frames"][0]["x"] == 0 and p["frames"][0]["y"] == 0, p
assert len(s["pieces"]) == 1 and s["pieces"][0]["placed"] and s["pieces"][0]["frames"] == 3, s
assert "pieces" not in p and all("piece" not in f for f in p["frames"]), p  # one piece: nothing to say
PY
"$cli" track --capture "$tmp/cap" --no-loop-closure --out "$tmp/noloop.json" --quiet > /dev/null 2> "$tmp/err.txt" \
  || fail "track --no-loop-closure exit $?: $(cat "$tmp/err.txt")"
# A range and a stride: the Capture numbers the frames kept 0, 1, ... (model/capture.h, as the studio does).
"$cli" track --capture "$tmp/cap" --first 1 --last 2 --out "$tmp/range.json" --quiet > /dev/null 2> "$tmp/err.txt" \
  || fail "track --first 1 --last 2 exit $?: $(cat "$tmp/err.txt")"
"$cli" track --capture "$tmp/cap" --stride 2 --out "$tmp/stride.json" --quiet > /dev/null 2> "$tmp/err.txt" \
  || fail "track --stride 2 exit $?: $(cat "$tmp/err.txt")"
# An author's mask (a PGM: the left quarter black), --level, and masks that cannot be used.
/usr/bin/python3 - "$tmp/mask.pgm" 64 32 <<'PY'
import sys
w, h = int(sys.argv[2]), int(sys.argv[3])
rows = bytes(0 if x < w // 4 else 255 for x in range(w)) * h
open(sys.argv[1], "wb").write(b"P5 %d %d 255\n" % (w, h) + rows)
PY
"$cli" track --capture "$tmp/cap" --mask "$tmp/mask.pgm" --level --no-static-mask --out "$tmp/masked.json" \
  --mask-out "$tmp/used.pgm" --tilt-prior 0 --json > "$tmp/masked-summary.json" 2> "$tmp/err.txt" \
  || fail "track --mask exit $?: $(cat "$tmp/err.txt")"
[[ -s "$tmp/masked.json" ]] || fail "track --mask wrote no path"
# The mask written back is the author's at the working size: the left quarter unused, the rest used.
/usr/bin/python3 - "$tmp/used.pgm" "$tmp/masked-summary.json" <<'PY' || fail "--mask-out: $(cat "$tmp/masked-summary.json")"
import json, sys
data = open(sys.argv[1], "rb").read()
fields = data.split(maxsplit=4)
assert fields[0] == b"P5", fields[:4]
w, h = int(fields[1]), int(fields[2])
pixels = fields[4][-w * h:]
assert w == 2 * h and w >= 64, (w, h)
for y in (0, h // 2, h - 1):
    row = pixels[y * w:(y + 1) * w]
    assert all(v == 0 for v in row[: w // 4 - 1]) and all(v == 255 for v in row[w // 4 + 1:]), (y, row)
s = json.load(open(sys.argv[2]))
assert abs(s["masked_pct"] - 25.0) < 1.0, s["masked_pct"]
PY
"$cli" track --capture "$tmp/cap" --tilt-prior 30 --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 2 ]] || fail "--tilt-prior 30: exit $code"
grep -q -- "--tilt-prior" "$tmp/err.txt" || fail "--tilt-prior message: $(cat "$tmp/err.txt")"
"$cli" track --capture "$tmp/cap" --floor-prior -1 --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 2 ]] || fail "--floor-prior -1: exit $code"
grep -q -- "--floor-prior" "$tmp/err.txt" || fail "--floor-prior message: $(cat "$tmp/err.txt")"
"$cli" track --capture "$tmp/cap" --step-check -1 --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 2 ]] || fail "--step-check -1: exit $code"
grep -q -- "--step-check" "$tmp/err.txt" || fail "--step-check message: $(cat "$tmp/err.txt")"
"$cli" track --capture "$tmp/cap" --step-check 0.5 --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -ne 0 ]] || fail "--step-check 0.5 accepted"
grep -q "step_map_check_factor" "$tmp/err.txt" || fail "--step-check 0.5 message: $(cat "$tmp/err.txt")"
"$cli" track --capture "$tmp/cap" --mask "$tmp/no-such-mask.png" --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "missing mask: exit $code"
grep -q "no-such-mask.png" "$tmp/err.txt" || fail "missing mask message: $(cat "$tmp/err.txt")"
/usr/bin/python3 -c "open('$tmp/black.pgm','wb').write(b'P5 8 4 255\n' + bytes(32))"
"$cli" track --capture "$tmp/cap" --mask "$tmp/black.pgm" --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "all-black mask: exit $code"
grep -q "black.pgm" "$tmp/err.txt" || fail "all-black mask message: $(cat "$tmp/err.txt")"
python3 - "$tmp/range.json" "$tmp/stride.json" <<'PY' || fail "range/stride output: $(cat "$tmp/range.json" "$tmp/stride.json")"
import json, sys
r = json.load(open(sys.argv[1]))
s = json.load(open(sys.argv[2]))
assert [(f["index"], f["file"]) for f in r["frames"]] == [(0, "f10.png"), (1, "f11.png")], r
assert [(f["index"], f["file"]) for f in s["frames"]] == [(0, "f9.png"), (1, "f11.png")], s
PY
"$cli" track --capture "$tmp/cap" --first 2 --last 1 --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "--last before --first: exit $code"
grep -q -- "--last" "$tmp/err.txt" || fail "--last before --first message: $(cat "$tmp/err.txt")"
"$cli" track --capture "$tmp/cap" --first 7 --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "--first beyond the capture: exit $code"
grep -q "cap" "$tmp/err.txt" || fail "--first beyond the capture message: $(cat "$tmp/err.txt")"
"$cli" track --capture "$tmp/cap" --stride 2 --known-distance 0 2 2 --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "--known-distance on an untracked frame: exit $code"
grep -q "not among the tracked frames" "$tmp/err.txt" || fail "untracked frame message: $(cat "$tmp/err.txt")"
"$cli" track --capture "$tmp/nothing-here" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "missing capture: exit $code"
grep -q "nothing-here" "$tmp/err.txt" || fail "missing capture message: $(cat "$tmp/err.txt")"
"$cli" track --capture "$tmp/cap" --known-distance 0 0 2 --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "bad --known-distance: exit $code"
grep -q "known-distance" "$tmp/err.txt" || fail "bad --known-distance message: $(cat "$tmp/err.txt")"
"$cli" track 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "track without --capture: exit $code"
# track --anchors: a rendered 40-frame walk through the office sample, anchored at three of its ground-truth
# positions. Tracked alone the path starts at the origin; with the anchors it lies on the plan: every frame
# within 5 cm of the truth, the anchored ones within 5 cm of their anchors. Bad anchors fail before tracking.
"$cli" render --plan office-sample --auto-path --frames 40 --size 512x256 --out "$tmp/walk" --quiet || fail "render exit $?"
python3 - "$tmp/walk/groundtruth.json" "$tmp/anchors.json" <<'PY'
import json, sys
f = json.load(open(sys.argv[1]))["frames"]
json.dump([{"index": f[i]["index"], "x": f[i]["x"], "y": f[i]["y"]} for i in (0, 20, 39)], open(sys.argv[2], "w"))
PY
"$cli" track --capture "$tmp/walk/frames" --camera-height 1.6 --out "$tmp/free.json" --quiet > /dev/null || fail "track exit $?"
"$cli" track --capture "$tmp/walk/frames" --camera-height 1.6 --anchors "$tmp/anchors.json" --out "$tmp/anchored.json" \
  > "$tmp/anchored.txt" 2> "$tmp/anchored_err.txt" || fail "track --anchors exit $?: $(cat "$tmp/anchored_err.txt")"
grep -q "refined with 3 anchors" "$tmp/anchored.txt" || fail "track --anchors output: $(cat "$tmp/anchored.txt")"
grep -q "refining with 3 anchors" "$tmp/anchored_err.txt" || fail "track --anchors progress: $(cat "$tmp/anchored_err.txt")"
python3 - "$tmp/walk/groundtruth.json" "$tmp/free.json" "$tmp/anchored.json" "$tmp/anchors.json" <<'PY' || fail "anchored path not on the plan"
import json, math, sys
truth, free, anchored = ({f["index"]: f for f in json.load(open(p))["frames"]} for p in sys.argv[1:4])
anchors = json.load(open(sys.argv[4]))
def worst(path):
    return max(math.hypot(path[i]["x"] - t["x"], path[i]["y"] - t["y"]) for i, t in truth.items())
print("track --anchors: largest distance to the truth %.3f m without anchors, %.3f m with" % (worst(free), worst(anchored)))
assert worst(free) > 1.0, worst(free)
assert worst(anchored) < 0.05, worst(anchored)
for a in anchors:
    f = anchored[a["index"]]
    assert math.hypot(f["x"] - a["x"], f["y"] - a["y"]) < 0.05, (a, f)
PY
"$cli" track --capture "$tmp/walk/frames" --camera-height 1.6 --anchors "$tmp/anchors.json" --json --quiet > "$tmp/a.json" \
  || fail "track --anchors --json exit $?"
python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); assert s["anchors"]==3 and len(s["anchor_residuals"])==3 and s["scale_source"]=="anchors", s' \
  "$tmp/a.json" || fail "track --anchors json: $(cat "$tmp/a.json")"
echo '[{"index":0,"x":1,"y":1},{"index":400,"x":2,"y":2}]' > "$tmp/off.json"
"$cli" track --capture "$tmp/walk/frames" --anchors "$tmp/off.json" --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "anchor off the capture: exit $code"
grep -q "off.json: anchor on frame 400" "$tmp/err.txt" || fail "anchor off the capture message: $(cat "$tmp/err.txt")"
echo '[{"index":0,"y":1}]' > "$tmp/bad.json"
"$cli" track --capture "$tmp/walk/frames" --anchors "$tmp/bad.json" --quiet 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "bad anchors file: exit $code"
grep -q "bad.json" "$tmp/err.txt" || fail "bad anchors file message: $(cat "$tmp/err.txt")"
echo "ok"
