#!/usr/bin/env bash
# `plenopath --version` and `plenopath info`: exit codes 0 ok / 1 failed / 2 bad usage, errors name the file.
set -u
cli=$1; data=$2
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

out=$("$cli" --version) || fail "--version exit $?"
[[ "$out" == plenopath\ * ]] || fail "--version printed '$out'"

"$cli" info "$data/projects/minimal.plenopath" > "$tmp/out.txt" || fail "info exit $?"
grep -q "Minimal test project" "$tmp/out.txt" || fail "info text: $(cat "$tmp/out.txt")"
grep -q "4 segments" "$tmp/out.txt" || fail "segment count: $(cat "$tmp/out.txt")"

"$cli" info --json "$data/projects/minimal.plenopath" > "$tmp/out.json" || fail "info --json exit $?"
python3 - "$tmp/out.json" <<'PY' || fail "json content"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["plan"]["segments"] == 4, s
assert s["path"]["frames"] == 3, s
assert abs(s["path"]["length_m"] - 2.0) < 1e-9, s
assert s["plan"]["extents_m"]["max"] == [4.0, 3.0], s
PY

"$cli" info "$tmp/absent.plenopath" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "missing file: exit $code"
grep -q "absent.plenopath" "$tmp/err.txt" || fail "missing file message: $(cat "$tmp/err.txt")"

echo '{"format":"plenopath-project","version":7}' > "$tmp/new.plenopath"
"$cli" info "$tmp/new.plenopath" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "newer version: exit $code"
grep -q "newer" "$tmp/err.txt" || fail "newer version message: $(cat "$tmp/err.txt")"

"$cli" info --no-such-option 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "bad usage: exit $code"
"$cli" frobnicate 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "unknown subcommand: exit $code"
echo "ok"
