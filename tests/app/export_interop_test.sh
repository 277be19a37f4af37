#!/usr/bin/env bash
# `plenopath export` with the interop files (issue 21), each read by its real reader: gpsbabel reads path.kml
# and path.gpx, exiftool reads GPano and GPS from a keyframe; positions against a hand-computed local
# tangent plane (at 48 N one metre north is 1/111190.3 deg, one metre east 1/74625.2 deg). Without a
# geo-anchor: no map files by default, an error naming the anchor when --kml-gpx asks for them.
set -u
cli=$1
fail() { echo "FAIL: $*"; exit 1; }
for tool in gpsbabel exiftool; do
  command -v $tool > /dev/null || { echo "SKIP: $tool is not installed (cmake/install-deps.sh)"; exit 77; }
done
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

"$cli" make-sample --out "$tmp/s" --frames 30 --size 128x64 > /dev/null || fail "make-sample exit $?"
"$cli" render --plan "$tmp/s/office.dxf" --path "$tmp/s/office_path.json" --size 128x64 --depth --quiet \
  --out "$tmp/s/capture" > /dev/null || fail "render exit $?"
"$cli" sample --project "$tmp/s/office.plenopath" --method uniform --count 5 --save > /dev/null 2>&1 \
  || fail "sample exit $?"
project="$tmp/s/office.plenopath"

# Without an anchor (the sample has none): the package has no map files; asking for them is an error.
"$cli" export --project "$project" --out "$tmp/plain" --max-size 128 --preview-size 64 > /dev/null 2>&1 \
  || fail "export without anchor: exit $?"
[[ -f "$tmp/plain/tour.json" && ! -e "$tmp/plain/path.kml" && ! -e "$tmp/plain/path.gpx" ]] \
  || fail "without an anchor: $(ls "$tmp/plain")"
"$cli" export --project "$project" --out "$tmp/asked" --kml-gpx 2> "$tmp/err.txt"; code=$?
[[ $code -eq 1 ]] || fail "--kml-gpx without anchor: exit $code"
grep -q "geo-anchor" "$tmp/err.txt" || fail "--kml-gpx message: $(cat "$tmp/err.txt")"
[[ ! -e "$tmp/asked" ]] || fail "a failed export left a package behind"

# Anchor the plan at 48 N 2 E, 35 m, plan +X east.
python3 - "$project" <<'PY' || fail "anchoring the project"
import json, sys
p = json.load(open(sys.argv[1]))
p["geo_anchor"] = {"valid": True, "latitude_deg": 48.0, "longitude_deg": 2.0, "altitude_m": 35.0,
                   "plan_rotation_deg": 0.0, "scale": 1.0, "plan_origin": [0.0, 0.0]}
json.dump(p, open(sys.argv[1], "w"))
PY
"$cli" export --project "$project" --out "$tmp/tour" --max-size 128 --preview-size 64 --kml-gpx --tum \
  --opensfm --nerfstudio --json > "$tmp/report.json" || fail "export exit $?"
for f in path.kml path.gpx trajectory.tum reconstruction.json reference_lla.json transforms.json; do
  [[ -f "$tmp/tour/$f" ]] || fail "no $f in the package"
done
for kind in -w -t; do
  for format in kml gpx; do
    gpsbabel $kind -i $format -f "$tmp/tour/path.$format" -o unicsv -F "$tmp/$format$kind.csv" \
      || fail "gpsbabel cannot read path.$format ($kind)"
  done
done
exiftool -j -n -G "$tmp/tour/images/"k*_full.jpg > "$tmp/exif.json" || fail "exiftool exit $?"

python3 - "$tmp" "$project" <<'PY' || fail "interop files disagree with the project"
import csv, json, math, os, sys
tmp, project = sys.argv[1], json.load(open(sys.argv[2]))
frames = {f["index"]: f for f in project["path"]["frames"]}
keyframes = sorted(project["keyframes"]["indices"])
height = project["capture"]["camera_height_m"]

def expected(f):  # local tangent plane at 48 N 2 E: metres to degrees, hand-computed
    return 48.0 + f["y"] / 111190.3, 2.0 + f["x"] / 74625.2

def rows(name):
    return list(csv.DictReader(open(os.path.join(tmp, name))))

worst = 0.0
for fmt in ("kml", "gpx"):
    track, waypoints = rows(fmt + "-t.csv"), rows(fmt + "-w.csv")
    assert len(track) == len(frames), (fmt, len(track), len(frames))
    assert [w["Name"] for w in waypoints] == ["Keyframe %d" % k for k in keyframes], (fmt, waypoints)
    for row, f in list(zip(track, sorted(frames.values(), key=lambda f: f["index"]))) + \
                  [(w, frames[k]) for w, k in zip(waypoints, keyframes)]:
        lat, lon = expected(f)
        error = max(abs(float(row["Latitude"]) - lat), abs(float(row["Longitude"]) - lon))
        worst = max(worst, error)
        assert error < 1.5e-6, (fmt, f["index"], row, lat, lon)
        assert abs(float(row["Altitude"]) - (35.0 + height)) < 0.051, (fmt, row)

exif = json.load(open(os.path.join(tmp, "exif.json")))
assert len(exif) == len(keyframes), len(exif)
for e in exif:
    frame = int(os.path.basename(e["SourceFile"])[1:7])
    f = frames[frame]
    assert e["XMP:ProjectionType"] == "equirectangular" and e["XMP:UsePanoramaViewer"] is True, e
    assert e["XMP:FullPanoWidthPixels"] == 128 and e["XMP:FullPanoHeightPixels"] == 64, e
    compass = (90.0 - f["heading_deg"]) % 360.0
    assert abs((e["XMP:PoseHeadingDegrees"] - compass + 180) % 360 - 180) < 0.006, (e, f)
    lat, lon = expected(f)
    assert abs(e["Composite:GPSLatitude"] - lat) < 2e-7 and abs(e["Composite:GPSLongitude"] - lon) < 2e-7, e
    assert abs(e["Composite:GPSAltitude"] - (35.0 + height)) < 0.01, e

tum = [l for l in open(os.path.join(tmp, "tour", "trajectory.tum")) if not l.startswith("#")]
assert len(tum) == len(frames), len(tum)
shots = json.load(open(os.path.join(tmp, "tour", "reconstruction.json")))[0]["shots"]
assert sorted(shots) == ["k%06d_full.jpg" % k for k in keyframes], sorted(shots)
nerf = json.load(open(os.path.join(tmp, "tour", "transforms.json")))
assert sorted(f["file_path"] for f in nerf["frames"]) == ["images/k%06d_full.jpg" % k for k in keyframes], nerf
assert nerf["camera_model"] == "EQUIRECTANGULAR" and (nerf["w"], nerf["h"]) == (128, 64), nerf
print("interop: %d frames, %d keyframes, worst gpsbabel position error %.1e deg" %
      (len(frames), len(keyframes), worst))
PY
echo ok
