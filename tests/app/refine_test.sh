#!/usr/bin/env bash
# `plenopath refine`: the minimal project's straight 2 m path (x 1..3 at y 1.5) anchored so that it runs
# north along x = 2 from y = 1 to y = 3: the middle frame must land at (2, 2) (hand-computed).
set -u
cli=$1; data=$2
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cp "$data/projects/minimal.plenopath" "$tmp/p.plenopath"
echo '[{"index":0,"x":2,"y":1},{"index":2,"x":2,"y":3}]' > "$tmp/anchors.json"

"$cli" refine --project "$tmp/p.plenopath" --anchors "$tmp/anchors.json" --json > "$tmp/out.json" 2>/dev/null \
  || fail "refine exit $?"
[[ -f "$tmp/p.plenopath.bak" ]] || fail "no .bak kept"
/usr/bin/python3 - "$tmp/p.plenopath" "$tmp/out.json" <<'PY' || fail "refined positions"
import json, sys
p = json.load(open(sys.argv[1]))
frames = {f["index"]: f for f in p["path"]["frames"]}
assert abs(frames[1]["x"] - 2) < 0.01 and abs(frames[1]["y"] - 2) < 0.01, frames[1]
assert abs(frames[1]["heading_deg"] - 90) < 1, frames[1]
assert len(p["anchors"]) == 2, p["anchors"]
r = json.load(open(sys.argv[2]))
assert all(x["distance_m"] < 0.01 for x in r["residuals"]), r
PY

"$cli" refine --project "$tmp/p.plenopath" --anchors "$tmp/anchors.json" --preview --out "$tmp/q.plenopath" \
  > /dev/null || fail "preview exit $?"

cp "$data/projects/minimal.plenopath" "$tmp/none.plenopath"
"$cli" refine --project "$tmp/none.plenopath" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "no anchors: exit $code"
grep -q "no anchors" "$tmp/err.txt" || fail "no anchors message: $(cat "$tmp/err.txt")"

echo '[{"index":7,"x":0,"y":0}]' > "$tmp/bad.json"
"$cli" refine --project "$tmp/none.plenopath" --anchors "$tmp/bad.json" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "anchor off the path: exit $code"
grep -q "frame 7" "$tmp/err.txt" || fail "anchor message: $(cat "$tmp/err.txt")"
echo '[{"index":0,"x":"here"}]' > "$tmp/bad.json"
"$cli" refine --project "$tmp/none.plenopath" --anchors "$tmp/bad.json" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "bad anchors file: exit $code"
grep -q "bad.json: /0/x" "$tmp/err.txt" || fail "bad anchors file message: $(cat "$tmp/err.txt")"
# GPS only: the capture's track (two fixes, 1/15 s apart, on the plan line x = 2 from y = 1 to y = 3 through a
# geo-anchor at 48 N 2 E; 1 m north = 1/111190.3 deg, 1 m east = 1/74625.2 deg there) and no anchors.
/usr/bin/python3 - "$data/projects/minimal.plenopath" "$tmp/gps.plenopath" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
n, e = 1 / 111190.3, 1 / 74625.2
p["capture"] = {"kind": "none", "frame_rate": 30.0, "gps_track": [
    {"t": 0.0, "lat": 48 + 1 * n, "lon": 2 + 2 * e, "alt": 0},
    {"t": 2 / 30, "lat": 48 + 3 * n, "lon": 2 + 2 * e, "alt": 0}]}
p["geo_anchor"] = {"valid": True, "latitude_deg": 48.0, "longitude_deg": 2.0, "altitude_m": 0,
                   "plan_rotation_deg": 0, "scale": 1, "plan_origin": [0, 0]}
json.dump(p, open(sys.argv[2], "w"))
PY
"$cli" refine --project "$tmp/gps.plenopath" --json > "$tmp/gps.json" 2>/dev/null || fail "GPS refine exit $?"
/usr/bin/python3 - "$tmp/gps.plenopath" "$tmp/gps.json" <<'PY' || fail "GPS-refined positions"
import json, sys
p = json.load(open(sys.argv[1]))
f = {x["index"]: x for x in p["path"]["frames"]}
for i, y in ((0, 1), (1, 2), (2, 3)):
    assert abs(f[i]["x"] - 2) < 0.05 and abs(f[i]["y"] - y) < 0.05, f[i]
assert json.load(open(sys.argv[2]))["gps_fixes"] == 3
assert p["path"]["scale_source"] == "gps"
PY
echo ok
