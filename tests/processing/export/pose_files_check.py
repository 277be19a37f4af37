#!/usr/bin/env python3
"""Reads the package's pose files as their own tools define them and checks them against the project's path.

  pose_files_check.py tum FILE TRUTH.json
  pose_files_check.py opensfm RECONSTRUCTION.json TRUTH.json
  pose_files_check.py nerfstudio TRANSFORMS.json TRUTH.json

TRUTH.json is the path as the test wrote it by hand (ARCHITECTURE.md's path file, plus what the check needs):
{"frame_rate": r, "camera_height_m": h, "anchor": null | {"rotation_deg": a, "scale": s, "origin": [x, y]},
 "width": w, "height": h, "frames": [{"index", "x", "y", "heading_deg", "shot"?}]}.

tum: each line is "t tx ty tz qx qy qz qw", world_from_camera. With the camera axes the export documents
(x right of the panorama centre, y down, z forward) the camera's z axis must point along the frame's heading,
its x axis 90 degrees clockwise of it, its y axis down; the position is the frame's, at the camera height.

opensfm: for each shot, world points at known azimuth/elevation from the keyframe (ARCHITECTURE.md's
equirectangular convention gives their pixel) are projected through OpenSfM's spherical camera as its
documentation writes it (doc/source/geometry.rst: lon = atan(x/z), lat = atan(-y/sqrt(x^2+z^2)), normalised
(lon/2pi, -lat/2pi), pixel = normalised * max(w, h) + ((w-1)/2, (h-1)/2), x_cam = R x_world + t with R from
the angle-axis "rotation"). Prints the worst pixel error; fails above 1e-6 px.

nerfstudio: for pixels of each keyframe image, the world ray nerfstudio's EQUIRECTANGULAR camera shoots
(cameras.py: pixel centre (x, y), coord = ((x - cx) / fl_x, -(y - cy) / fl_y), theta = -pi coord_x,
phi = pi (1/2 - coord_y), d = (-sin theta sin phi, cos phi, -cos theta sin phi), world = R d from
"transform_matrix") must be the bearing ARCHITECTURE.md gives that pixel from the keyframe's heading, and the
ray's origin the keyframe's position. Fails above 1e-9.
"""
import json
import math
import sys


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def quaternion_matrix(qx, qy, qz, qw):
    return [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
            [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
            [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]


def rodrigues(r):
    angle = math.sqrt(sum(v * v for v in r))
    if angle < 1e-15:
        return [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    k = [v / angle for v in r]
    c, s, C = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    x, y, z = k
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]


def column(m, j):
    return [m[0][j], m[1][j], m[2][j]]


def angle_diff_deg(a, b):
    return abs((a - b + 180.0) % 360.0 - 180.0)


def world_of(truth, x, y, heading_deg):
    """The frame's position and heading in the file's world: plan, or the anchor's east/north/up."""
    anchor = truth.get("anchor")
    if not anchor:
        return x, y, heading_deg
    a = math.radians(anchor["rotation_deg"])
    dx = (x - anchor["origin"][0]) * anchor["scale"]
    dy = (y - anchor["origin"][1]) * anchor["scale"]
    return (math.cos(a) * dx - math.sin(a) * dy, math.sin(a) * dx + math.cos(a) * dy,
            heading_deg + anchor["rotation_deg"])


def check_tum(path, truth):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            values = [float(v) for v in line.split()]
            if len(values) != 8:
                fail("a TUM line has %d values, not 8: %r" % (len(values), line))
            rows.append(values)
    frames = truth["frames"]
    if len(rows) != len(frames):
        fail("%d poses for %d path frames" % (len(rows), len(frames)))
    worst = 0.0
    for row, frame in zip(rows, frames):
        t, tx, ty, tz, qx, qy, qz, qw = row
        if abs(t - frame["index"] / truth["frame_rate"]) > 1e-6:
            fail("frame %d: timestamp %f" % (frame["index"], t))
        if max(abs(tx - frame["x"]), abs(ty - frame["y"]), abs(tz - truth["camera_height_m"])) > 1e-6:
            fail("frame %d: position %f %f %f" % (frame["index"], tx, ty, tz))
        norm = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
        if abs(norm - 1) > 1e-6:
            fail("frame %d: quaternion norm %f" % (frame["index"], norm))
        r = quaternion_matrix(qx / norm, qy / norm, qz / norm, qw / norm)
        forward, right, down = column(r, 2), column(r, 0), column(r, 1)
        heading = math.degrees(math.atan2(forward[1], forward[0]))
        right_angle = math.degrees(math.atan2(right[1], right[0]))
        worst = max(worst, angle_diff_deg(heading, frame["heading_deg"]))
        if angle_diff_deg(heading, frame["heading_deg"]) > 1e-6 or abs(forward[2]) > 1e-9:
            fail("frame %d: camera z points at %f deg, heading is %f" % (frame["index"], heading,
                                                                          frame["heading_deg"]))
        if angle_diff_deg(right_angle, frame["heading_deg"] - 90.0) > 1e-6:
            fail("frame %d: camera x at %f deg, not 90 deg clockwise of the heading" % (frame["index"],
                                                                                        right_angle))
        if abs(down[2] + 1) > 1e-9:
            fail("frame %d: camera y is not down: %r" % (frame["index"], down))
    print("tum: %d poses, worst heading error %.2e deg" % (len(rows), worst))


def check_opensfm(path, truth):
    with open(path) as f:
        reconstructions = json.load(f)
    if not isinstance(reconstructions, list) or len(reconstructions) != 1:
        fail("reconstruction.json is not a list of one reconstruction")
    rec = reconstructions[0]
    w, h = truth["width"], truth["height"]
    cameras = rec["cameras"]
    worst = 0.0
    checked = 0
    for frame in truth["frames"]:
        if "shot" not in frame:
            continue
        shot = rec["shots"].get(frame["shot"])
        if shot is None:
            fail("no shot %s" % frame["shot"])
        camera = cameras[shot["camera"]]
        if camera["projection_type"] not in ("spherical", "equirectangular"):
            fail("camera %s is %s" % (shot["camera"], camera["projection_type"]))
        if (camera["width"], camera["height"]) != (w, h):
            fail("camera size %dx%d, images are %dx%d" % (camera["width"], camera["height"], w, h))
        R = rodrigues(shot["rotation"])
        t = shot["translation"]
        cx, cy, heading = world_of(truth, frame["x"], frame["y"], frame["heading_deg"])
        centre = [cx, cy, truth["camera_height_m"]]
        for azimuth_deg in (-170.0, -90.0, -33.0, 0.0, 12.5, 90.0, 135.0):
            for elevation_deg in (-60.0, -10.0, 0.0, 25.0, 70.0):
                a, e = math.radians(azimuth_deg), math.radians(elevation_deg)
                world_angle = math.radians(heading) - a  # ARCHITECTURE.md: azimuth grows clockwise
                d = 3.7
                p = [centre[0] + d * math.cos(e) * math.cos(world_angle),
                     centre[1] + d * math.cos(e) * math.sin(world_angle), centre[2] + d * math.sin(e)]
                xc = [sum(R[i][j] * p[j] for j in range(3)) + t[i] for i in range(3)]
                lon = math.atan2(xc[0], xc[2])
                lat = math.atan2(-xc[1], math.hypot(xc[0], xc[2]))
                u, v = lon / (2 * math.pi), -lat / (2 * math.pi)
                size = max(w, h)
                px, py = u * size + (w - 1) / 2.0, v * size + (h - 1) / 2.0
                # Our pixel: the continuous coordinate minus the half pixel of OpenSfM's centred origin.
                ex = (a + math.pi) / (2 * math.pi) * w - 0.5
                ey = (math.pi / 2 - e) / math.pi * h - 0.5
                error = math.hypot(px - ex, py - ey)
                worst = max(worst, error)
                if error > 1e-6:
                    fail("shot %s: azimuth %g elevation %g projects to (%f, %f), expected (%f, %f)" %
                         (frame["shot"], azimuth_deg, elevation_deg, px, py, ex, ey))
                checked += 1
    if checked == 0:
        fail("no shot checked")
    anchor = truth.get("anchor")
    if anchor and "reference_lla" in anchor:
        ref = rec.get("reference_lla")
        if not ref or any(abs(ref[k] - anchor["reference_lla"][k]) > 1e-12
                          for k in ("latitude", "longitude", "altitude")):
            fail("reference_lla %r, expected %r" % (ref, anchor["reference_lla"]))
    print("opensfm: %d shots, %d points, worst reprojection %.2e px" % (len(rec["shots"]), checked, worst))


def check_nerfstudio(path, truth):
    with open(path) as f:
        transforms = json.load(f)
    if transforms.get("camera_model") != "EQUIRECTANGULAR":
        fail("camera_model %r" % transforms.get("camera_model"))
    w, h = transforms["w"], transforms["h"]
    if (w, h) != (truth["width"], truth["height"]):
        fail("size %dx%d, images are %dx%d" % (w, h, truth["width"], truth["height"]))
    fx, fy, cx, cy = transforms["fl_x"], transforms["fl_y"], transforms["cx"], transforms["cy"]
    by_file = {frame["file_path"]: frame for frame in transforms["frames"]}
    worst = 0.0
    checked = 0
    for frame in truth["frames"]:
        if "shot" not in frame:
            continue
        entry = by_file.get("images/" + frame["shot"])
        if entry is None:
            fail("no frame for images/%s" % frame["shot"])
        m = entry["transform_matrix"]
        wx, wy, heading = world_of(truth, frame["x"], frame["y"], frame["heading_deg"])
        origin = [m[0][3], m[1][3], m[2][3]]
        if max(abs(a - b) for a, b in zip(origin, [wx, wy, truth["camera_height_m"]])) > 1e-9:
            fail("%s: origin %r" % (frame["shot"], origin))
        for col in (0, 1, w // 4, w // 2 - 1, w // 2, 3 * w // 4 + 3, w - 1):
            for row in (0, h // 5, h // 2 - 1, h // 2, h - 2, h - 1):
                x, y = col + 0.5, row + 0.5  # nerfstudio: rays through pixel centres
                coord_x, coord_y = (x - cx) / fx, -(y - cy) / fy
                theta, phi = -math.pi * coord_x, math.pi * (0.5 - coord_y)
                d = [-math.sin(theta) * math.sin(phi), math.cos(phi), -math.cos(theta) * math.sin(phi)]
                ray = [sum(m[i][j] * d[j] for j in range(3)) for i in range(3)]
                # ARCHITECTURE.md: azimuth from the column, elevation from the row, world angle heading - azimuth
                a = x / w * 2 * math.pi - math.pi
                e = math.pi / 2 - y / h * math.pi
                world_angle = math.radians(heading) - a
                expected = [math.cos(e) * math.cos(world_angle), math.cos(e) * math.sin(world_angle), math.sin(e)]
                error = max(abs(p - q) for p, q in zip(ray, expected))
                worst = max(worst, error)
                if error > 1e-9:
                    fail("%s: pixel (%d, %d) ray %r, expected %r" % (frame["shot"], col, row, ray, expected))
                checked += 1
    if checked == 0:
        fail("no frame checked")
    print("nerfstudio: %d frames, %d rays, worst direction error %.2e" % (len(by_file), checked, worst))


def main():
    checks = {"tum": check_tum, "opensfm": check_opensfm, "nerfstudio": check_nerfstudio}
    if len(sys.argv) != 4 or sys.argv[1] not in checks:
        print(__doc__)
        sys.exit(2)
    with open(sys.argv[3]) as f:
        truth = json.load(f)
    checks[sys.argv[1]](sys.argv[2], truth)


main()
