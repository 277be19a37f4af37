#!/usr/bin/env bash
# `plenopath export`: usage and failure paths of the command line, and a zip package read back by python's
# zipfile and by unzip (the package itself is tested in tests/processing/export/).
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
# A rendered, sampled sample project exported as a zip: python's zipfile reads every entry back (CRCs), text is
# deflated and images stored, each keyframe has one full JPEG and one preview script, and --json's ratio is
# the zip's size over the full JPEGs' as zipfile lists them.
"$cli" make-sample --out "$tmp/s" --frames 24 --size 256x128 > /dev/null || fail "make-sample exit $?"
"$cli" render --plan "$tmp/s/office.dxf" --path "$tmp/s/office_path.json" --size 256x128 --depth --quiet \
  --out "$tmp/s/capture" > /dev/null || fail "render exit $?"
"$cli" sample --project "$tmp/s/office.plenopath" --method uniform --count 6 --save > /dev/null \
  || fail "sample exit $?"
"$cli" export --project "$tmp/s/office.plenopath" --out "$tmp/tour.zip" --json > "$tmp/export.json" \
  2> "$tmp/err.txt" || fail "export zip exit $?: $(cat "$tmp/err.txt")"
python3 - "$tmp/tour.zip" "$tmp/export.json" <<'PY' || fail "zip package: $(cat "$tmp/export.json")"
import json, os, sys, zipfile
z = zipfile.ZipFile(sys.argv[1]); report = json.load(open(sys.argv[2]))
assert z.testzip() is None
info = {e.filename: e for e in z.infolist()}
assert len(info) == report["files"], (len(info), report["files"])
for name, e in info.items():
    text = name.rsplit(".", 1)[-1] in ("json", "js", "html", "css", "svg")
    assert e.compress_type == (zipfile.ZIP_DEFLATED if text else zipfile.ZIP_STORED), (name, e.compress_type)
full = [n for n in info if n.endswith("_full.jpg")]
previews = [n for n in info if n.endswith("_preview.js")]
assert len(full) == len(previews) == report["keyframes"] == 6, (full, previews)
assert not [n for n in info if n.endswith("_full.js") or n.endswith("_preview.jpg")]
full_bytes = sum(info[n].file_size for n in full)
assert report["full_image_bytes"] == full_bytes, (report["full_image_bytes"], full_bytes)
assert report["package_bytes"] == os.path.getsize(sys.argv[1])
assert abs(report["package_ratio"] - report["package_bytes"] / full_bytes) < 1e-9, report["package_ratio"]
print("zip: %d entries, ratio %.3f" % (len(info), report["package_ratio"]))
PY
unzip -tq "$tmp/tour.zip" > /dev/null || fail "unzip -t refuses the package"
echo ok
