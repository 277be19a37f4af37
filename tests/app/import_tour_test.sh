#!/usr/bin/env bash
# `plenopath import-tour`: a published tour (folder, tour.json, .zip, a zip made by hand with a top folder)
# becomes a project again, and exporting that project gives the same tour.json; its images and hotspot media
# are the package's. Partial packages import what is there and say what was skipped; bad input is an error
# naming the file; nothing already on disk is overwritten.
set -u
cli=$1
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$cli" make-sample --out "$tmp/s" --frames 60 --size 128x64 > /dev/null || fail "make-sample exit $?"
"$cli" render --plan "$tmp/s/office.dxf" --path "$tmp/s/office_path.json" --size 128x64 --depth --quiet \
  --out "$tmp/s/capture" > /dev/null || fail "render exit $?"
# Two hotspots: a movie texture whose media is an image of the capture, and a link.
python3 - "$tmp/s/office.plenopath" "$tmp/s/capture/frames" <<'PY' || fail "adding hotspots"
import json, os, sys
p = json.load(open(sys.argv[1]))
frames = sorted(os.listdir(sys.argv[2]))
p["hotspots"] = [
  {"id": "poster", "kind": "movie_texture", "title": "Poster", "media": "capture/frames/" + frames[3],
   "frame": p["keyframes"]["indices"][1], "image_corners_deg": [[-10, 10], [10, 10], [10, -10], [-10, -10]]},
  {"id": "site", "kind": "event", "title": "Site", "frame": 0, "action": "open_url",
   "action_target": "https://example.org/", "image_corners_deg": [[-5, 5], [5, 5], [5, -5]]},
]
p["tour"]["title"] = "Tour to re-import"
json.dump(p, open(sys.argv[1], "w"))
PY
"$cli" export --project "$tmp/s/office.plenopath" --out "$tmp/one" > /dev/null || fail "export exit $?"
"$cli" export --project "$tmp/s/office.plenopath" --out "$tmp/one.zip" > /dev/null || fail "export zip exit $?"

same_tour() {  # same_tour A B: the two packages' tour.json are equal, and their images have equal sizes
  python3 - "$1" "$2" <<'PY'
import json, struct, sys
a = json.load(open(sys.argv[1] + "/tour.json")); b = json.load(open(sys.argv[2] + "/tour.json"))
if a != b:
    for k in a:
        if a.get(k) != b.get(k): print("differs:", k, str(a.get(k))[:300], "|", str(b.get(k))[:300])
    sys.exit(1)
def jpeg_size(f):
    d = open(f, "rb").read(); i = 2
    while i < len(d):
        m = d[i + 1]; n = struct.unpack(">H", d[i + 2:i + 4])[0]
        if m in (0xC0, 0xC1, 0xC2): return struct.unpack(">HH", d[i + 5:i + 9])
        i += 2 + n
for k in a["keyframes"]:
    assert jpeg_size(sys.argv[1] + "/" + k["full"]) == jpeg_size(sys.argv[2] + "/" + k["full"]), k
PY
}

# From the zip: a project whose export is the same tour.
"$cli" import-tour --package "$tmp/one.zip" --project "$tmp/p/back.plenopath" --json > "$tmp/import.json" 2> "$tmp/err.txt" \
  || fail "import exit $?: $(cat "$tmp/err.txt")"
python3 - "$tmp/import.json" "$tmp/one/tour.json" "$tmp/p" <<'PY' || fail "import report: $(cat "$tmp/import.json")"
import json, os, sys
r = json.load(open(sys.argv[1])); t = json.load(open(sys.argv[2]))
assert r["keyframes"] == len(t["keyframes"]) >= 2, r
assert r["path_frames"] == len(t["path"]["frames"]) == 60, r
assert r["hotspots"] == 2 and r["media_files"] == 1 and r["warnings"] == [], r
assert os.path.isdir(os.path.join(sys.argv[3], "back_tour", "images")), os.listdir(sys.argv[3])
PY
cmp "$tmp/p/back_tour/media/poster.jpg" "$tmp/one/media/poster.jpg" || fail "hotspot media differs from the package's"
"$cli" export --project "$tmp/p/back.plenopath" --out "$tmp/two" > /dev/null || fail "export of the import exit $?"
same_tour "$tmp/one" "$tmp/two" || fail "export -> import -> export changed tour.json"
cmp "$tmp/one/media/poster.jpg" "$tmp/two/media/poster.jpg" || fail "hotspot media changed on the way"

# From the folder and from its tour.json, and from a zip made by hand with everything under one folder.
"$cli" import-tour --package "$tmp/one" --project "$tmp/q/a.plenopath" > /dev/null || fail "folder import exit $?"
"$cli" import-tour --package "$tmp/one/tour.json" --project "$tmp/q/b.plenopath" > /dev/null \
  || fail "tour.json import exit $?"
(cd "$tmp" && python3 -c "
import os, zipfile
with zipfile.ZipFile('hand.zip', 'w', zipfile.ZIP_DEFLATED) as z:
    for root, _, files in os.walk('one'):
        for f in files: z.write(os.path.join(root, f))") || fail "making hand.zip"
"$cli" import-tour --package "$tmp/hand.zip" --project "$tmp/q/c.plenopath" > /dev/null || fail "hand zip import exit $?"
for n in a b c; do
  "$cli" export --project "$tmp/q/$n.plenopath" --out "$tmp/q/$n-tour" > /dev/null || fail "export $n exit $?"
  same_tour "$tmp/one" "$tmp/q/$n-tour" || fail "round trip through $n"
done

# A keyframe image missing: imported without it, and said so; a missing hotspot medium too.
cp -r "$tmp/one" "$tmp/partial"
first=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['keyframes'][-1]['full'])" "$tmp/one/tour.json")
rm "$tmp/partial/$first" "$tmp/partial/media/poster.jpg"
"$cli" import-tour --package "$tmp/partial" --project "$tmp/r/p.plenopath" --json > "$tmp/r.json" 2> "$tmp/err.txt" \
  || fail "partial import exit $?"
grep -q "keyframe .*not in the package; keyframe dropped" "$tmp/err.txt" || fail "partial message: $(cat "$tmp/err.txt")"
grep -q "hotspot poster: its media media/poster.jpg is not in the package" "$tmp/err.txt" \
  || fail "media message: $(cat "$tmp/err.txt")"
python3 -c "
import json,sys; r=json.load(open(sys.argv[1])); t=json.load(open(sys.argv[2]))
assert r['keyframes'] == len(t['keyframes']) - 1 and len(r['warnings']) == 2, r" "$tmp/r.json" "$tmp/one/tour.json" \
  || fail "partial report: $(cat "$tmp/r.json")"

# Bad input: errors naming the file; nothing overwritten.
mkdir -p "$tmp/empty"
"$cli" import-tour --package "$tmp/empty" --project "$tmp/e/p.plenopath" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] && grep -q "empty: not a tour package: it holds no tour.json" "$tmp/err.txt" \
  || fail "folder without tour.json: exit $code, $(cat "$tmp/err.txt")"
head -c 3000 "$tmp/one.zip" > "$tmp/cut.zip"
"$cli" import-tour --package "$tmp/cut.zip" --project "$tmp/e/p.plenopath" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] && grep -q "cut.zip" "$tmp/err.txt" || fail "damaged zip: exit $code, $(cat "$tmp/err.txt")"
[[ ! -e "$tmp/e/p_tour" ]] || fail "a failed import left its media folder behind"
echo '{"format": "plenopath-tour", "version": 99}' > "$tmp/empty/tour.json"
"$cli" import-tour --package "$tmp/empty" --project "$tmp/e/p.plenopath" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] && grep -q "tour.json.*newer than this build reads" "$tmp/err.txt" \
  || fail "newer tour: exit $code, $(cat "$tmp/err.txt")"
# A tour.json naming a file outside its package is refused, and nothing is written outside.
cp -r "$tmp/one" "$tmp/evil"
python3 - "$tmp/evil/tour.json" <<'PY'
import json, sys
t = json.load(open(sys.argv[1])); t["keyframes"][0]["full"] = "../one/images/x.jpg"; json.dump(t, open(sys.argv[1], "w"))
PY
"$cli" import-tour --package "$tmp/evil" --project "$tmp/e/p.plenopath" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] && grep -q 'unsafe entry name "../one/images/x.jpg"' "$tmp/err.txt" \
  || fail "unsafe name: exit $code, $(cat "$tmp/err.txt")"
[[ ! -e "$tmp/e/p_tour" ]] || fail "an unsafe import left its media folder behind"
"$cli" import-tour --package "$tmp/one" --project "$tmp/p/back.plenopath" 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] && grep -q "back.plenopath: already exists" "$tmp/err.txt" || fail "existing project: exit $code"
"$cli" import-tour --package "$tmp/one" --project "$tmp/p/back.plenopath" --force 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] && grep -q "back_tour: already exists and is not empty" "$tmp/err.txt" \
  || fail "existing media folder: exit $code, $(cat "$tmp/err.txt")"
"$cli" import-tour --project "$tmp/x.plenopath" 2> /dev/null; code=$?
[[ $code -eq 2 ]] || fail "missing --package: exit $code"
echo ok
