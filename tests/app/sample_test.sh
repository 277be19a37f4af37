#!/usr/bin/env bash
# `plenopath sample`: keyframes in progressive order, exact budgets, pinned frames, loss measures, the
# project round trip (--save), and clear errors naming the file.
set -u
cli=$1
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$cli" make-sample --out "$tmp/s" --frames 120 --size 128x64 > /dev/null || fail "make-sample exit $?"
"$cli" render --plan "$tmp/s/office.dxf" --path "$tmp/s/office_path.json" --size 128x64 --depth --quiet \
  --out "$tmp/s/capture" > /dev/null || fail "render exit $?"
plan="$tmp/s/office.dxf"; path="$tmp/s/office_path.json"

check() {  # check FILE METHOD BUDGET [PINNED...]: progressive order, ends first, exact budget, pins kept
  python3 - "$@" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); method = sys.argv[2]; budget = int(sys.argv[3]); pins = [int(p) for p in sys.argv[4:]]
k = s["keyframes"]
assert s["method"] == method, s["method"]
assert len(k) == budget == s["budget"], (len(k), budget)
assert len(set(k)) == len(k), k
assert k[0] == 0 and k[1] == s["frames"] - 1, k[:2]        # coarse to fine: the ends first
assert all(p in k for p in pins), (pins, k)
assert abs(s["reduction_ratio"] - s["frames"] / budget) < 1e-9, s["reduction_ratio"]
assert s["largest_gap_m"] > 0
PY
}

"$cli" sample --plan "$plan" --path "$path" --method uniform --count 12 --json > "$tmp/u.json" || fail "uniform exit $?"
check "$tmp/u.json" uniform 12 || fail "uniform: $(cat "$tmp/u.json")"
python3 -c "
import json,sys; s=json.load(open(sys.argv[1])); g=s['geometric_loss']
assert 0 <= g['mean'] <= g['p95'] <= g['max'] <= 1 and g['evaluated'] == 108, g
assert s['photometric_loss'] is None, s" "$tmp/u.json" || fail "uniform loss: $(cat "$tmp/u.json")"

"$cli" sample --plan "$plan" --path "$path" --method visibility --ratio 10 --pin 7,50 --json > "$tmp/v.json" \
  || fail "visibility exit $?"
check "$tmp/v.json" visibility 12 7 50 || fail "visibility: $(cat "$tmp/v.json")"
"$cli" sample --plan "$plan" --path "$path" --method visibility --rule cell_rule --exponent 2 --boost 0.5 \
  --count 9 --json > "$tmp/c.json" || fail "cell rule exit $?"
check "$tmp/c.json" visibility 9 || fail "cell rule: $(cat "$tmp/c.json")"
python3 -c "import json,sys; s=json.load(open(sys.argv[1])); assert s['rule']=='cell_rule' and s['exponent']==2 and s['boost']==0.5, s" \
  "$tmp/c.json" || fail "cell rule parameters"

# Depth sampling from the rendered depth maps; the capture's frames give the photometric loss.
"$cli" sample --path "$path" --capture "$tmp/s/capture" --method depth --count 10 --photometric-frames 5 --json \
  > "$tmp/d.json" || fail "depth exit $?"
check "$tmp/d.json" depth 10 || fail "depth: $(cat "$tmp/d.json")"
python3 -c "
import json,sys; s=json.load(open(sys.argv[1])); p=s['photometric_loss']
assert s['geometric_loss'] is None, s
assert p['frames'] == 5 and 5 < p['psnr_min_db'] <= p['psnr_mean_db'] <= 100 and 0 < p['ssim_min'] <= p['ssim_mean'] <= 1, p
" "$tmp/d.json" || fail "depth photometric: $(cat "$tmp/d.json")"

# The project: plan, path and capture from it; --save writes the keyframes back.
"$cli" sample --project "$tmp/s/office.plenopath" --method visibility --count 8 --save --json > "$tmp/p.json" \
  || fail "project exit $?"
python3 - "$tmp/p.json" "$tmp/s/office.plenopath" <<'PY' || fail "project save: $(cat "$tmp/p.json")"
import json, sys
s = json.load(open(sys.argv[1])); p = json.load(open(sys.argv[2]))
k = p["keyframes"]
assert sorted(s["keyframes"]) == k["indices"], (s["keyframes"], k)
assert k["parameters"]["method"] == "visibility" and len(k["rank"]) == 8, k
assert s["photometric_loss"]["frames"] > 0, s
PY
"$cli" sample --project "$tmp/s/office.plenopath" --method uniform --ratio 40 > "$tmp/text.txt" || fail "text exit"
grep -q "Kept       3 of 120" "$tmp/text.txt" || fail "text output: $(cat "$tmp/text.txt")"

# Errors: exit 1 naming the file or the problem, exit 2 for usage.
"$cli" sample --path "$path" --method visibility --count 5 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "visibility without plan: exit $code"
grep -q "plan" "$tmp/err.txt" || fail "no-plan message: $(cat "$tmp/err.txt")"
"$cli" sample --plan "$plan" --path "$tmp/absent.json" --method uniform --count 5 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "absent path: exit $code"
grep -q "absent.json" "$tmp/err.txt" || fail "absent path message: $(cat "$tmp/err.txt")"
"$cli" sample --plan "$plan" --path "$path" --method uniform --count 5 --pin 999 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "bad pin: exit $code"
grep -q "999" "$tmp/err.txt" || fail "bad pin message: $(cat "$tmp/err.txt")"
"$cli" sample --path "$path" --method depth --count 5 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "depth without capture: exit $code"
grep -q "depth" "$tmp/err.txt" || fail "depth message: $(cat "$tmp/err.txt")"
"$cli" sample --plan "$plan" --path "$path" --method uniform 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "no budget: exit $code"
"$cli" sample --plan "$plan" --path "$path" --method fancy --count 3 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "bad method: exit $code"
echo "ok"
