#!/usr/bin/env bash
# `plenopath track --plan` and `plenopath register` (issue 19): a walk rendered on the office sample, tracked
# with no alignment at all, placed on the plan by itself, scored against the renderer's ground truth; the
# JSON (transform, score, candidates, share of wall points on walls); clear errors for a plan without
# walls, a capture from another building, and a project without points.
set -u
cli=$1; data=$2
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$cli" make-sample --out "$tmp/s" --frames 70 > /dev/null || fail "make-sample exit $?"
"$cli" render --plan "$tmp/s/office.dxf" --path "$tmp/s/office_path.json" --size 512x256 --out "$tmp/r" --quiet \
  || fail "render exit $?"

# Absolute errors on the plan, no alignment: frame by frame against the render's truth.
check_on_truth() {
  python3 - "$1" "$tmp/r/groundtruth.json" <<'PY'
import json, math, sys
est = {f["index"]: f for f in json.load(open(sys.argv[1]))["frames"]}
truth = json.load(open(sys.argv[2]))["frames"]
p2 = h2 = 0.0
for t in truth:
    e = est[t["index"]]
    p2 += (e["x"] - t["x"]) ** 2 + (e["y"] - t["y"]) ** 2
    d = (e["heading_deg"] - t["heading_deg"] + 180) % 360 - 180
    h2 += d * d
n = len(truth)
pos, head = math.sqrt(p2 / n), math.sqrt(h2 / n)
print(f"position RMS {pos:.4f} m, heading RMS {head:.4f} deg over {n} frames")
assert pos <= 0.05 and head <= 0.2, (pos, head)
PY
}

# 1. track --plan: the path comes out in plan coordinates.
"$cli" track --capture "$tmp/r/frames" --camera-height 1.6 --plan "$tmp/s/office.dxf" --out "$tmp/placed.json" \
  --json > "$tmp/t.json" 2> "$tmp/t.err" || fail "track --plan exit $?: $(tail -5 "$tmp/t.err")"
grep -q "track: registration" "$tmp/t.err" || fail "no registration progress: $(tail -5 "$tmp/t.err")"
check_on_truth "$tmp/placed.json" || fail "track --plan: path not on the truth"
[[ -s "$tmp/placed.points.json" ]] || fail "no points beside the path"
python3 - "$tmp/t.json" <<'PY' || fail "track --plan json: $(cat "$tmp/t.json")"
import json, sys
s = json.load(open(sys.argv[1]))
r = s["registration"]["pieces"]
assert len(r) == 1 and r[0]["ok"], r
assert r[0]["wall_share"] > 0.5 and r[0]["free_share"] == 1.0, r[0]
assert len(r[0]["candidates"]) >= 1 and r[0]["candidates"][0]["score"] == r[0]["score"], r[0]
# Then refined on the walls: it may only keep a result that fits the walls at least as well.
f = s["registration"]["plan_refinement"]["pieces"]
assert len(f) == 1 and f[0]["refined"], f
assert not f[0]["kept"] or f[0]["wall_share_after"] >= f[0]["wall_share_before"] - 0.005, f
assert abs(f[0]["drift_scale"] - 1) < 0.05, f
PY
grep -q "track: refinement on the walls" "$tmp/t.err" || fail "no refinement progress: $(tail -5 "$tmp/t.err")"

# 2. register: a project holding the unplaced path (track without --plan) and its points beside it.
"$cli" track --capture "$tmp/r/frames" --camera-height 1.6 --out "$tmp/raw.json" --quiet > /dev/null \
  || fail "track exit $?"
python3 - "$tmp/s/office.plenopath" "$tmp/raw.json" "$tmp/s/raw.plenopath" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
p["path"] = json.load(open(sys.argv[2]))
json.dump(p, open(sys.argv[3], "w"))
PY
cp "$tmp/raw.points.json" "$tmp/s/raw.points.json"
"$cli" register --project "$tmp/s/raw.plenopath" --json > "$tmp/g.json" 2> "$tmp/g.err" \
  || fail "register exit $?: $(cat "$tmp/g.err")"
python3 - "$tmp/g.json" <<'PY' || fail "register json: $(cat "$tmp/g.json")"
import json, sys
s = json.load(open(sys.argv[1]))
p = s["pieces"][0]
assert p["ok"] and p["wall_points"] > 50, p
t = p["transform"]
assert set(t) == {"rotation_deg", "translation", "scale"} and abs(t["scale"] - 1) < 0.03, t
assert 0 < p["score"] <= 1 and p["wall_share"] > 0.5, p
scores = [c["score"] for c in p["candidates"]]
assert scores == sorted(scores, reverse=True), scores
assert s["out"].endswith("raw.plenopath"), s
PY
[[ -s "$tmp/s/raw.plenopath.bak" ]] || fail "no .bak kept"
python3 - "$tmp/s/raw.plenopath" "$tmp/s/placed_path.json" <<'PY'
import json, sys
json.dump(json.load(open(sys.argv[1]))["path"], open(sys.argv[2], "w"))
PY
check_on_truth "$tmp/s/placed_path.json" || fail "register: path not on the truth"
# Registered again, the placed path stays where it is (the points were moved with it).
"$cli" register --project "$tmp/s/raw.plenopath" --out "$tmp/s/again.plenopath" --no-refine --json --quiet \
  > "$tmp/g2.json" || fail "register again exit $?"
python3 - "$tmp/g2.json" "$tmp/g.json" <<'PY' || fail "--no-refine / refinement json"
import json, sys
assert "plan_refinement" not in json.load(open(sys.argv[1]))
assert json.load(open(sys.argv[2]))["plan_refinement"]["pieces"][0]["refined"]
PY
python3 - "$tmp/g2.json" <<'PY' || fail "second registration moved the path: $(cat "$tmp/g2.json")"
import json, sys
t = json.load(open(sys.argv[1]))["pieces"][0]["transform"]
assert abs(t["rotation_deg"]) < 0.05 and abs(t["translation"][0]) < 0.02 and abs(t["translation"][1]) < 0.02, t
PY

# 3. Bad input. A plan without sight-blocking layers:
python3 - "$tmp/s/raw.plenopath.bak" "$tmp/s/nowalls.plenopath" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
for l in p["plan"]["layers"]: l["occluder"] = False
for s in p["plan"]["segments"]: s["occluder"] = False
json.dump(p, open(sys.argv[2], "w"))
PY
cp "$tmp/raw.points.json" "$tmp/s/nowalls.points.json"
"$cli" register --project "$tmp/s/nowalls.plenopath" --quiet > /dev/null 2> "$tmp/e1.txt"; code=$?
[[ $code -eq 1 ]] || fail "no walls: exit $code"
grep -q "no sight-blocking segments" "$tmp/e1.txt" || fail "no walls message: $(cat "$tmp/e1.txt")"
# A capture from another building (a round hall of 24 straight walls):
python3 - "$tmp/s/raw.plenopath.bak" "$tmp/s/hall.plenopath" <<'PY'
import json, math, sys
p = json.load(open(sys.argv[1]))
pts = [[9 * math.cos(2 * math.pi * i / 24), 9 * math.sin(2 * math.pi * i / 24)] for i in range(25)]
p["plan"]["layers"] = [{"name": "WALLS", "occluder": True}]
p["plan"]["segments"] = [{"a": pts[i], "b": pts[i + 1], "layer": "WALLS", "occluder": True} for i in range(24)]
p["plan"]["outlines"] = []
p["plan"]["labels"] = []
json.dump(p, open(sys.argv[2], "w"))
PY
cp "$tmp/raw.points.json" "$tmp/s/hall.points.json"
"$cli" register --project "$tmp/s/hall.plenopath" --json --quiet > "$tmp/h.json" 2> "$tmp/e2.txt"; code=$?
[[ $code -eq 1 ]] || fail "other building: exit $code"
grep -q "no placement fits: best candidate has [0-9]* % of wall points on walls" "$tmp/e2.txt" \
  || fail "other building message: $(cat "$tmp/e2.txt")"
python3 - "$tmp/h.json" <<'PY' || fail "other building json: $(cat "$tmp/h.json")"
import json, sys
s = json.load(open(sys.argv[1]))
assert not s["pieces"][0]["ok"] and s["out"] is None, s
PY
[[ -e "$tmp/s/hall.plenopath.bak" ]] && fail "a failed registration wrote the project"
# A project without its points:
rm "$tmp/s/hall.points.json"
"$cli" register --project "$tmp/s/hall.plenopath" --quiet > /dev/null 2> "$tmp/e3.txt"; code=$?
[[ $code -eq 1 ]] || fail "no points: exit $code"
grep -q "hall.points.json: no points file" "$tmp/e3.txt" || fail "no points message: $(cat "$tmp/e3.txt")"
# track --plan without a camera height:
"$cli" track --capture "$tmp/r/frames" --plan "$tmp/s/office.dxf" --quiet > /dev/null 2> "$tmp/e4.txt"; code=$?
[[ $code -eq 1 ]] || fail "--plan without --camera-height: exit $code"
grep -q "\-\-plan needs --camera-height" "$tmp/e4.txt" || fail "camera height message: $(cat "$tmp/e4.txt")"
echo "register: ok"
