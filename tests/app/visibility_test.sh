#!/usr/bin/env bash
# `plenopath plan-info` and `plenopath visibility`: JSON content, exit codes, errors naming the file.
set -u
cli=$1; data=$2
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$cli" plan-info --json "$data/dxf/lines_mm.dxf" > "$tmp/info.json" || fail "plan-info exit $?"
python3 - "$tmp/info.json" <<'PY' || fail "plan-info json: $(cat "$tmp/info.json")"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["units"] == "mm", s
assert s["extents_m"]["max"] == [10.0, 10.0], s
assert s["occluder_segments"] == 4, s
walls = [l for l in s["layers"] if l["name"] == "WALLS"][0]
assert walls["occluder"] and walls["entities"] == 6, walls
assert s["cleaned"]["duplicates_dropped"] == 1 and s["cleaned"]["zero_length_dropped"] == 1, s
PY
"$cli" plan-info --json --units cm --layers FURNITURE "$data/dxf/lines_mm.dxf" > "$tmp/info2.json" || fail "plan-info options"
python3 -c "import json,sys; s=json.load(open(sys.argv[1])); assert s['units']=='cm' and s['segments']==1, s" "$tmp/info2.json" \
  || fail "plan-info --units/--layers"

# A file cut in half imports what it holds and says so; noise after a binary sentinel is refused by name.
"$cli" plan-info "$data/dxf/truncated.dxf" > "$tmp/out.txt" 2> "$tmp/err.txt" || fail "truncated: exit $?"
grep -q "cut short" "$tmp/out.txt" || fail "truncated warning: $(cat "$tmp/out.txt")"
"$cli" plan-info "$data/dxf/binary.dxf" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "binary noise: exit $code"
grep -q "binary.dxf" "$tmp/err.txt" || fail "binary noise message: $(cat "$tmp/err.txt")"

# The 10 m x 10 m room seen from anywhere inside: 100 m^2.
"$cli" visibility --plan "$data/dxf/lines_mm.dxf" --point 3,4 --samples 4 --json > "$tmp/point.json" || fail "point exit $?"
python3 - "$tmp/point.json" <<'PY' || fail "point json: $(cat "$tmp/point.json")"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["status"] == "ok", s
assert abs(s["area_m2"] - 100.0) < 1e-9, s
assert len(s["polygon"]) == 4, s
assert [round(r, 9) for r in s["radial_m"]] == [7.0, 6.0, 3.0, 4.0], s
PY
"$cli" visibility --plan "$data/dxf/lines_mm.dxf" --point 20,4 --json | grep -q '"outside"' || fail "outside point"

# A path crossing the room: no wall, no vertex hidden -> one cell.
cat > "$tmp/path.json" <<'JSON'
{"units":"m","frames":[{"index":0,"x":1,"y":1,"heading_deg":0},{"index":1,"x":5,"y":1,"heading_deg":0},
{"index":2,"x":9,"y":5,"heading_deg":0}]}
JSON
"$cli" visibility --plan "$data/dxf/lines_mm.dxf" --path "$tmp/path.json" --json > "$tmp/path_out.json" || fail "path exit $?"
python3 - "$tmp/path_out.json" <<'PY' || fail "path json: $(cat "$tmp/path_out.json")"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["frames"] == 3 and s["events"] == [], s
assert len(s["cells"]) == 1 and s["cells"][0]["first_frame"] == 0 and s["cells"][0]["last_frame"] == 2, s
assert abs(s["cells"][0]["area_mid_m2"] - 100.0) < 1e-9, s
PY

"$cli" visibility --plan "$data/dxf/lines_mm.dxf" 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "no --point/--path: exit $code"
"$cli" visibility --plan "$tmp/absent.dxf" --point 1,1 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "absent plan: exit $code"
grep -q "absent.dxf" "$tmp/err.txt" || fail "absent plan message"
echo "ok"
