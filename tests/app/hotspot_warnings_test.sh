#!/usr/bin/env bash
# `plenopath info` lists hotspot warnings: missing media, markup in a title, a non-http link, a quad whose
# 3-D corners are not planar. A clean project has none.
set -u
cli=$1; data=$2
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$cli" info --json "$data/projects/minimal.plenopath" > "$tmp/clean.json" || fail "info exit $?"
python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); assert s["hotspot_warnings"] == [], s' "$tmp/clean.json" \
  || fail "clean project has warnings: $(cat "$tmp/clean.json")"

python3 - "$data/projects/minimal.plenopath" "$tmp/spots.plenopath" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
p["hotspots"] = [
  {"id": "tv", "kind": "movie_texture", "title": "<b>TV</b>", "media": "no-such-video.mp4", "frame": 0,
   "image_corners_deg": [[-10, 10], [10, 10], [10, -10], [-10, -10]],
   "world_corners": [[4, 2, 2], [4, 1, 2], [4.4, 1, 1], [4, 2, 1]]},
  {"id": "link", "kind": "event", "title": "Shop", "frame": 1, "action": "open_url",
   "action_target": "javascript:alert(1)", "image_corners_deg": [[-5, 5], [5, 5], [5, -5]]},
]
json.dump(p, open(sys.argv[2], "w"))
PY
"$cli" info "$tmp/spots.plenopath" > "$tmp/out.txt" || fail "info exit $?"
grep -q "warning: hotspot 'tv'.*media file not found" "$tmp/out.txt" || fail "missing media: $(cat "$tmp/out.txt")"
grep -q "warning: hotspot 'tv'.*markup" "$tmp/out.txt" || fail "markup: $(cat "$tmp/out.txt")"
grep -q "warning: hotspot 'tv'.*not on one plane" "$tmp/out.txt" || fail "planarity: $(cat "$tmp/out.txt")"
grep -q "warning: hotspot 'link'.*only http and https" "$tmp/out.txt" || fail "link: $(cat "$tmp/out.txt")"
"$cli" info --json "$tmp/spots.plenopath" > "$tmp/out.json" || fail "info --json exit $?"
python3 - "$tmp/out.json" <<'PY' || fail "json warnings: $(cat "$tmp/out.json")"
import json, sys
s = json.load(open(sys.argv[1]))
fields = {(w["hotspot"], w["field"]) for w in s["hotspot_warnings"]}
assert ("tv", "media") in fields and ("tv", "title") in fields and ("link", "action_target") in fields, fields
PY
echo "ok"
