#!/usr/bin/env bash
# `plenopath export`: usage and failure paths of the command line (the package itself is tested in
# tests/processing/export/).
set -u
cli=$1; data=$2
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$cli" export --project "$data/projects/minimal.plenopath" --out "$tmp/tour" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "project without keyframes: exit $code"
grep -q "no keyframes" "$tmp/err.txt" || fail "message: $(cat "$tmp/err.txt")"
[[ ! -e "$tmp/tour" ]] || fail "a failed export left a package behind"

"$cli" export --project "$tmp/absent.plenopath" --out "$tmp/tour" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "missing project: exit $code"
grep -q "absent.plenopath" "$tmp/err.txt" || fail "missing project message: $(cat "$tmp/err.txt")"

# A nadir image that is not there: the error names it, before any work.
"$cli" export --project "$data/projects/minimal.plenopath" --out "$tmp/tour" --clean-plates \
  --nadir "$tmp/no-logo.png" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "missing nadir image: exit $code"
grep -q "no-logo.png" "$tmp/err.txt" || fail "nadir image message: $(cat "$tmp/err.txt")"

# --kml-gpx insists on the map files, --no-kml-gpx leaves them out: both at once is a usage error.
"$cli" export --project x --out y --kml-gpx --no-kml-gpx 2> "$tmp/err.txt"; code=$?
[[ $code -eq 2 ]] || fail "--kml-gpx with --no-kml-gpx: exit $code"
grep -q "excludes" "$tmp/err.txt" || fail "--kml-gpx/--no-kml-gpx message: $(cat "$tmp/err.txt")"
"$cli" export --help | grep -q -- "--opensfm" || fail "export --help does not list --opensfm"

"$cli" export --out "$tmp/tour" 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "missing --project: exit $code"
"$cli" export --project x --out y --quality abc 2>/dev/null; code=$?
[[ $code -eq 2 ]] || fail "bad --quality: exit $code"
echo ok
