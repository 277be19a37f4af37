#!/usr/bin/python3
"""POV-Ray test corpus: walks through buildings the project's renderer did not make, with ground truth.

For each scene (scenes/*.pov, hand-written SDL) and its walk, this script generates the camera poses,
renders the equirectangular frames with POV-Ray (one thread, nice 19), applies the capture nuisances that are
image post-processing (auto-exposure drift and jumps, sensor noise, JPEG; ImageMagick `convert`), and writes
truth.json (the project's path format, ARCHITECTURE.md) and plan.dxf (walls and columns as lines on layer
A-WALL, read from the scene's Wall/Column/SqColumn calls) into a cache folder

    ${PLENOPATH_BENCH_CACHE:-$HOME/.cache/plenopath/povray}/<scene>-<hash>/

where the hash covers the scene files, the walk and nuisance parameters and SCRIPT_VERSION: change any of them
and the scene is rendered again; otherwise the cached frames are reused. A render that stops part-way resumes
where it stopped.

  corpus.py list                     scenes, frame counts and whether they are cached
  corpus.py render [SCENE ...]       render what is missing (all scenes by default)
  corpus.py dir SCENE                print the cache folder of SCENE (rendered or not)
  corpus.py walk SCENE OUT.json      write the truth path only (no rendering)
  corpus.py dxf SCENE OUT.dxf        write the floor plan only
  corpus.py frame SCENE INDEX OUT.png   render one frame (no nuisances), for looking at a scene

Standard library only (plus ezdxf for the plan, Debian's python3-ezdxf); run with /usr/bin/python3.
"""
import hashlib
import json
import math
import os
import random
import re
import subprocess
import sys
import time

SCRIPT_VERSION = "1"
HERE = os.path.dirname(os.path.abspath(__file__))
SCENES_DIR = os.path.join(HERE, "scenes")
WIDTH, HEIGHT = 1024, 512

# ---------------------------------------------------------------------------------------------------------
# Scenes. Walk parameters:
#   waypoints      plan (x, y) metres; corners are rounded with corner_radius
#   step           (min, mean, max) metres between frames; the step varies smoothly (speed_wobble) with a
#                  little jitter, and slows to 70 % in turns
#   lateral        amplitude (m) of a smooth sideways wander about the line
#   heading_wobble amplitude (deg) of the camera heading about the direction of travel
#   shake          amplitude (deg) of pitch and roll (trolley on an uneven floor)
#   dt             seconds between frames (for the people walking)
# Nuisances (post-processing of each frame): exposure drift amplitude, exposure jumps [(first, last, gain)],
# exposure per still (gain exp(u * amplitude), u uniform in [-1, 1] per frame: auto-exposure shot to shot),
# Gaussian noise (ImageMagick -attenuate), JPEG quality (None: PNG).
# Clean-plate scenes (issue 24) have "truth_variants": every `every`-th frame rendered again with `declares`
# (the people, or the people and the rig, left out) into `folder`, with the same nuisances: the truth of a
# clean plate.
# Stills scenes (issue 20) have "stills" instead of a walk: tripod positions in capture order, each with a
# random heading (seeded), and their own "size" (default 1024x512).
SCENES = {
    "office": {
        "pov": "office.pov",
        "camera_height": 1.6,
        "description": "office floor: corridor, open doors, furnished room N2; hand-held walk, clean PNG",
        "walk": {
            "waypoints": [(4.5, 6.0), (9.0, 6.0), (9.0, 9.0), (11.0, 9.0), (11.0, 11.0), (7.2, 11.0),
                          (7.2, 8.2), (9.0, 8.2), (9.0, 6.0), (12.0, 6.0)],
            "corner_radius": 0.5, "step": (0.06, 0.1, 0.13), "speed_wobble": 0.2, "lateral": 0.03,
            "heading_wobble": 1.5, "shake": 0.0, "dt": 0.1, "seed": 1,
        },
        "nuisances": {},
    },
    "corridor": {
        "pov": "corridor.pov",
        "camera_height": 1.5,
        "description": "trolley capture round a 95 m plain corridor loop: operator and trolley in every frame, "
                       "1 deg shake, three people walking, a door frame 0.2 m away, frames subsampled from "
                       "video (12-30 cm steps), auto-exposure drift and jumps, noise, JPEG",
        "walk": {
            "waypoints": [(5.0, 1.1), (30.9, 1.1), (30.9, 18.9), (1.1, 18.9), (1.1, 1.1), (8.0, 1.1)],
            "corner_radius": 0.7, "step": (0.12, 0.26, 0.30), "speed_wobble": 0.15, "lateral": 0.03,
            "heading_wobble": 0.8, "shake": 1.0, "dt": 0.27, "seed": 2,
        },
        "nuisances": {"exposure_drift": 0.12, "exposure_jumps": [(60, 95, 1.2), (210, 240, 0.7)],
                      "noise": 0.5, "jpeg_quality": 82},
    },
    "people": {
        "pov": "corridor.pov",
        "camera_height": 1.5,
        "description": "trolley walk along two legs of the corridor loop as three people walk past, towards "
                       "and away from the camera; operator and trolley in every frame, auto-exposure drift, "
                       "PNG; every 20th frame rendered again without people, operator and trolley",
        "walk": {
            "waypoints": [(12.0, 1.1), (30.9, 1.1), (30.9, 9.0)],
            "corner_radius": 0.7, "step": (0.12, 0.15, 0.18), "speed_wobble": 0.15, "lateral": 0.03,
            "heading_wobble": 0.8, "shake": 0.0, "dt": 0.2, "seed": 5,
        },
        "nuisances": {"exposure_drift": 0.12},
        "truth_variants": [{"declares": ["Declare=NoPeople=1", "Declare=NoRig=1"], "every": 20, "folder": "clean"},
                           {"declares": ["Declare=NoPeople=1"], "every": 20, "folder": "no_people"}],
    },
    "gallery": {
        "pov": "gallery.pov",
        "camera_height": 1.7,
        "description": "gallery hall 26 x 16 m, 7 m high: two rows of round columns, glossy stone floor, sun "
                       "through tall windows, area lights; hand-held walk, clean PNG",
        "walk": {
            "waypoints": [(5.0, 8.0), (15.0, 8.0), (15.0, 13.0), (8.0, 13.0)],
            "corner_radius": 0.8, "step": (0.07, 0.1, 0.13), "speed_wobble": 0.2, "lateral": 0.04,
            "heading_wobble": 1.5, "shake": 0.3, "dt": 0.1, "seed": 3,
        },
        "nuisances": {},
    },
    "stills": {
        "pov": "office_stills.pov",
        "camera_height": 1.6,
        "size": (2048, 1024),
        "description": "office floor as 15 tripod stills 1.8-3.7 m apart at random headings: N1, the "
                       "corridor, N2 through its door, N3 and S3 through theirs; tripod at the nadir, "
                       "exposure differing from shot to shot (+-20 %), PNG",
        "stills": {
            "positions": [(3.8, 9.5), (2.5, 8.2), (2.5, 6.0), (4.5, 6.0), (6.8, 6.0), (9.0, 6.0), (9.0, 8.0),
                          (7.2, 8.2), (9.0, 9.7), (10.8, 9.6), (11.5, 6.0), (14.0, 6.0), (16.5, 6.0),
                          (16.5, 3.6), (15.5, 8.8)],
            "seed": 20,
        },
        "walk": {"dt": 1.0, "seed": 20},
        "nuisances": {"exposure_per_still": 0.2},
    },
    "gallery_stills": {
        "pov": "gallery_stills.pov",
        "camera_height": 1.6,
        "size": (2048, 1024),
        "description": "gallery hall 26 x 16 m as 17 tripod stills 3.5-4 m apart at random headings: along the "
                       "windows, down the middle aisle between the columns and back along the north wall; "
                       "walls 8-13 m away, sun patches on a glossy floor; tripod at the nadir, exposure "
                       "differing from shot to shot (+-20 %), PNG",
        "stills": {
            "positions": [(3.0, 2.5), (6.5, 2.5), (10.0, 2.5), (13.5, 2.5), (17.0, 2.5), (20.5, 2.5), (23.5, 2.5),
                          (24.0, 6.0), (21.0, 8.0), (17.5, 8.0), (14.0, 8.0), (10.5, 8.0), (7.0, 8.0), (3.5, 8.0),
                          (5.0, 13.5), (8.5, 13.5), (12.0, 13.5)],
            "seed": 21,
        },
        "walk": {"dt": 1.0, "seed": 21},
        "nuisances": {"exposure_per_still": 0.2},
    },
    "gap": {
        "pov": "office.pov",
        "camera_height": 1.6,
        "description": "office walk from closed room S1 through the 0.9 m service wall into closed room S2: "
                       "about 10 frames inside the wall, two pieces that share nothing; clean PNG",
        "walk": {
            "waypoints": [(4.0, 1.3), (6.6, 1.3), (6.6, 3.6), (3.5, 3.6), (3.5, 2.5), (12.5, 2.5),
                          (12.5, 3.9), (9.6, 3.9), (9.6, 1.5)],
            "corner_radius": 0.5, "step": (0.06, 0.095, 0.13), "speed_wobble": 0.2, "lateral": 0.02,
            "heading_wobble": 1.5, "shake": 0.0, "dt": 0.1, "seed": 4,
        },
        "nuisances": {},
    },
}


def cache_root():
    return os.environ.get("PLENOPATH_BENCH_CACHE") or os.path.join(os.path.expanduser("~"), ".cache",
                                                                  "plenopath", "povray")


def log(msg):
    print("povray-corpus: " + msg, file=sys.stderr, flush=True)


# ---------------------------------------------------------------------------------------------------------
# Walks


def rounded_polyline(points, radius, step=0.005):
    """Dense points along the polyline with each corner replaced by a circular arc of the given radius."""
    out = [points[0]]
    for i in range(1, len(points) - 1):
        p0, p1, p2 = points[i - 1], points[i], points[i + 1]
        a = math.atan2(p1[1] - p0[1], p1[0] - p0[0])
        b = math.atan2(p2[1] - p1[1], p2[0] - p1[0])
        turn = math.remainder(b - a, 2 * math.pi)
        l0 = math.dist(p0, p1)
        l1 = math.dist(p1, p2)
        d = min(radius * math.tan(abs(turn) / 2), 0.45 * l0, 0.45 * l1)
        r = d / math.tan(abs(turn) / 2) if abs(turn) > 1e-9 else 0.0
        start = (p1[0] - d * math.cos(a), p1[1] - d * math.sin(a))
        out.append(start)
        if r > 0:
            side = 1 if turn > 0 else -1  # centre to the left for a left turn
            cx = start[0] - side * r * math.sin(a)
            cy = start[1] + side * r * math.cos(a)
            n = max(2, int(abs(turn) * r / step))
            for k in range(1, n):
                ang = a + turn * k / n
                out.append((cx + side * r * math.sin(ang), cy - side * r * math.cos(ang)))
        out.append((p1[0] + d * math.cos(b), p1[1] + d * math.sin(b)))
    out.append(points[-1])
    # resample evenly
    dense = [out[0]]
    for q in out[1:]:
        p = dense[-1]
        L = math.dist(p, q)
        n = int(L / step)
        for k in range(1, n + 1):
            t = k * step / L
            dense.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
        if math.dist(dense[-1], q) > 1e-9:
            dense.append(q)
    return dense


def smooth_noise(rng, t, terms=3, base_period=1.0):
    """A smooth pseudo-random function of t in [-1, 1]: a sum of sines with random periods and phases."""
    parts = [(base_period * (0.6 + 0.8 * rng.random()) / (k + 1), rng.random() * 2 * math.pi, 1.0 / (k + 1))
             for k in range(terms)]
    norm = sum(w for _, _, w in parts)

    def f(x):
        return sum(w * math.sin(2 * math.pi * x / p + ph) for p, ph, w in parts) / norm
    return f


def generate_walk(walk):
    rng = random.Random(walk["seed"])
    line = rounded_polyline(walk["waypoints"], walk["corner_radius"])
    cum = [0.0]
    for i in range(1, len(line)):
        cum.append(cum[-1] + math.dist(line[i - 1], line[i]))
    total = cum[-1]
    tangent = []
    for i in range(len(line)):
        a, b = line[max(0, i - 2)], line[min(len(line) - 1, i + 2)]
        tangent.append(math.atan2(b[1] - a[1], b[0] - a[0]))

    def at(s):
        k = min(len(line) - 2, max(0, int(s / (cum[-1] / (len(line) - 1)))))
        while k > 0 and cum[k] > s:
            k -= 1
        while k < len(line) - 2 and cum[k + 1] < s:
            k += 1
        t = (s - cum[k]) / max(1e-12, cum[k + 1] - cum[k])
        x = line[k][0] + t * (line[k + 1][0] - line[k][0])
        y = line[k][1] + t * (line[k + 1][1] - line[k][1])
        th = tangent[k] + t * math.remainder(tangent[k + 1] - tangent[k], 2 * math.pi)
        # turning rate (rad/m) over +-0.15 m
        k0, k1 = max(0, k - 30), min(len(line) - 1, k + 30)
        curv = abs(math.remainder(tangent[k1] - tangent[k0], 2 * math.pi)) / max(1e-9, cum[k1] - cum[k0])
        return x, y, th, curv

    smin, smean, smax = walk["step"]
    speed = smooth_noise(rng, 0, 3, 40.0)
    lateral = smooth_noise(rng, 0, 3, 6.0)
    wob = smooth_noise(rng, 0, 3, 30.0)
    pitch = smooth_noise(rng, 0, 4, 9.0)
    roll = smooth_noise(rng, 0, 4, 7.0)
    frames = []
    s = 0.0
    i = 0
    while s <= total:
        x, y, th, curv = at(s)
        lat = walk["lateral"] * lateral(s)
        x += -math.sin(th) * lat
        y += math.cos(th) * lat
        heading = math.degrees(th) + walk["heading_wobble"] * wob(i)
        frames.append({"x": x, "y": y, "heading_deg": math.remainder(heading, 360.0),
                       "pitch_deg": walk["shake"] * pitch(i), "roll_deg": walk["shake"] * roll(i)})
        turn_slow = 1.0 - 0.3 * min(1.0, curv * walk["corner_radius"])
        step = smean * (1 + walk["speed_wobble"] * speed(i)) * turn_slow * (1 + 0.08 * rng.gauss(0, 1))
        s += min(smax, max(smin, step))
        i += 1
    return frames


def generate_stills(stills):
    """Tripod stills: the positions as given, level, each at a random heading."""
    rng = random.Random(stills["seed"])
    return [{"x": x, "y": y, "heading_deg": rng.uniform(-180.0, 180.0), "pitch_deg": 0.0, "roll_deg": 0.0}
            for x, y in stills["positions"]]


def scene_size(spec):
    return tuple(spec.get("size", (WIDTH, HEIGHT)))


def camera_declares(f, height, index, dt):
    """POV-Ray Declare= options for a frame: the camera basis in POV coordinates (see scenes/camera.inc)."""
    th = math.radians(f["heading_deg"])
    p = math.radians(f["pitch_deg"])
    r = math.radians(f["roll_deg"])
    # plan frame: forward, right (clockwise of forward), up at zero pitch/roll
    F0 = (math.cos(th), math.sin(th), 0.0)
    R0 = (math.sin(th), -math.cos(th), 0.0)
    U0 = (0.0, 0.0, 1.0)
    # pitch (nose up) about the right axis, then roll (right side down) about the new forward axis
    F1 = tuple(F0[k] * math.cos(p) + U0[k] * math.sin(p) for k in range(3))
    U1 = tuple(U0[k] * math.cos(p) - F0[k] * math.sin(p) for k in range(3))
    R2 = tuple(R0[k] * math.cos(r) - U1[k] * math.sin(r) for k in range(3))
    U2 = tuple(U1[k] * math.cos(r) + R0[k] * math.sin(r) for k in range(3))

    def pov(v):
        return (v[0], v[2], v[1])
    vals = {"CamL": pov((f["x"], f["y"], height)), "CamF": pov(F1), "CamR": pov(R2), "CamU": pov(U2)}
    out = []
    for name, v in vals.items():
        for axis, c in zip("xyz", v):
            out.append("Declare=%s%s=%.9f" % (name, axis, c))
    out.append("Declare=FrameIndex=%d" % index)
    out.append("Declare=FrameTime=%.6f" % (index * dt))
    return out


# ---------------------------------------------------------------------------------------------------------
# Plan geometry, read from the scene's SDL

_NUM = r"\s*(-?[0-9.]+)\s*"


def plan_elements(pov_file):
    """Walls as rectangles (4 corners) and columns, from Wall(x0,y0,x1,y1,t), Column(x,y,r), SqColumn(x,y,s)."""
    # The scene and the scenes it includes (office_stills.pov is office.pov plus a tripod); .inc files hold
    # the macros, not calls.
    text = "\n".join(open(os.path.join(SCENES_DIR, f)).read() for f in scene_files(pov_file) if f.endswith(".pov"))
    text = re.sub(r"//[^\n]*", "", text)
    walls, columns = [], []
    for m in re.finditer(r"(?<![A-Za-z])Wall\(" + ",".join([_NUM] * 5) + r"\)", text):
        x0, y0, x1, y1, t = map(float, m.groups())
        L = math.hypot(x1 - x0, y1 - y0)
        c, s = (x1 - x0) / L, (y1 - y0) / L
        pts = []
        for u, v in ((-t / 2, -t / 2), (L + t / 2, -t / 2), (L + t / 2, t / 2), (-t / 2, t / 2)):
            pts.append((x0 + u * c - v * s, y0 + u * s + v * c))
        walls.append(pts)
    for m in re.finditer(r"(?<![A-Za-z])Column\(" + ",".join([_NUM] * 3) + r"\)", text):
        x, y, r = map(float, m.groups())
        columns.append([(x + r * math.cos(2 * math.pi * k / 24), y + r * math.sin(2 * math.pi * k / 24))
                        for k in range(24)])
    for m in re.finditer(r"SqColumn\(" + ",".join([_NUM] * 3) + r"\)", text):
        x, y, s = map(float, m.groups())
        h = s / 2
        columns.append([(x - h, y - h), (x + h, y - h), (x + h, y + h), (x - h, y + h)])
    return walls, columns


def inside_polygon(pt, poly):
    x, y = pt
    inside = False
    for i in range(len(poly)):
        (x0, y0), (x1, y1) = poly[i], poly[(i + 1) % len(poly)]
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            inside = not inside
    return inside


def write_dxf(scene, out):
    import ezdxf
    walls, columns = plan_elements(SCENES[scene]["pov"])
    doc = ezdxf.new("R2010")
    doc.units = ezdxf.units.M
    doc.layers.add("A-WALL", color=7)
    msp = doc.modelspace()
    for poly in walls + columns:
        for i in range(len(poly)):
            msp.add_line(poly[i], poly[(i + 1) % len(poly)], dxfattribs={"layer": "A-WALL"})
    tmp = out + ".%d.tmp" % os.getpid()
    doc.saveas(tmp)
    os.replace(tmp, out)


# ---------------------------------------------------------------------------------------------------------
# Truth and cache


def truth_for(scene):
    spec = SCENES[scene]
    frames = generate_stills(spec["stills"]) if "stills" in spec else generate_walk(spec["walk"])
    ext = "jpg" if spec["nuisances"].get("jpeg_quality") else "png"
    walls, columns = plan_elements(spec["pov"])
    solids = walls + columns
    blind = [any(inside_polygon((f["x"], f["y"]), poly) for poly in solids) for f in frames]
    pieces = []  # named like the path format's pieces, but kept apart: the truth itself is one placed path
    for i, b in enumerate(blind):
        if b:
            continue
        if pieces and pieces[-1]["last_index"] == i - 1:
            pieces[-1]["last_index"] = i
        else:
            pieces.append({"first_index": i, "last_index": i})
    truth = {
        "units": "m",
        "scene": scene,
        "description": spec["description"],
        "camera_height_m": spec["camera_height"],
        "true_pieces": pieces,
        "frames_inside_walls": [i for i, b in enumerate(blind) if b],
        "frames": [],
    }
    for i, f in enumerate(frames):
        truth["frames"].append({"index": i, "file": "frames/%06d.%s" % (i, ext), "x": round(f["x"], 6),
                                "y": round(f["y"], 6), "heading_deg": round(f["heading_deg"], 6),
                                "pitch_deg": round(f["pitch_deg"], 4), "roll_deg": round(f["roll_deg"], 4)})
    if spec.get("truth_variants"):
        truth["truth_variants"] = {
            v["folder"]: {"declares": v["declares"],
                          "frames": [{"index": i, "file": "%s/%06d.%s" % (v["folder"], i, ext)}
                                     for i in range(0, len(frames), v["every"])]}
            for v in spec["truth_variants"]}
    length = sum(math.dist((a["x"], a["y"]), (b["x"], b["y"])) for a, b in zip(frames, frames[1:]))
    truth["length_m"] = round(length, 3)
    return truth


def scene_files(pov):
    files = [pov]
    text = open(os.path.join(SCENES_DIR, pov)).read()
    files += re.findall(r'#include\s+"([^"]+)"', text)
    for inc in list(files[1:]):
        path = os.path.join(SCENES_DIR, inc)
        if os.path.exists(path):
            files += [f for f in re.findall(r'#include\s+"([^"]+)"', open(path).read()) if f not in files]
    return [f for f in files if os.path.exists(os.path.join(SCENES_DIR, f))]


def scene_hash(scene):
    spec = SCENES[scene]
    h = hashlib.sha256()
    h.update(("version %s %dx%d\n" % ((SCRIPT_VERSION,) + scene_size(spec))).encode())
    keys = ("camera_height", "walk", "nuisances") + tuple(k for k in ("stills", "truth_variants") if k in spec)
    h.update(json.dumps({k: spec[k] for k in keys}, sort_keys=True).encode())
    for f in scene_files(spec["pov"]):
        h.update(f.encode())
        h.update(open(os.path.join(SCENES_DIR, f), "rb").read())
    return h.hexdigest()[:12]


def scene_dir(scene):
    return os.path.join(cache_root(), "%s-%s" % (scene, scene_hash(scene)))


def is_complete(scene):
    return os.path.exists(os.path.join(scene_dir(scene), "complete.json"))


def render_frame(pov, out_png, declares, width=WIDTH, height=HEIGHT, extra=()):
    tmp = out_png + ".%d.part.png" % os.getpid()
    cmd = ["nice", "-n", "19", "povray", "+I" + os.path.join(SCENES_DIR, pov), "+L" + SCENES_DIR, "+O" + tmp,
           "+W%d" % width, "+H%d" % height, "+FN", "-D", "-V", "+WT1", "-A", "-GS", "-GR"] + list(extra) + declares
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0 or not os.path.exists(tmp):
        raise RuntimeError("povray failed on %s (exit %d):\n%s" % (pov, p.returncode, p.stderr[-3000:]))
    os.replace(tmp, out_png)


def exposure_gain(nuis, i, rng_seed):
    g = 1.0
    amp = nuis.get("exposure_drift", 0.0)
    if amp:
        f = smooth_noise(random.Random(rng_seed), 0, 2, 150.0)
        g *= math.exp(amp * f(i))
    if nuis.get("exposure_per_still"):
        g *= math.exp(nuis["exposure_per_still"] * random.Random(rng_seed * 1000 + i).uniform(-1.0, 1.0))
    for first, last, gain in nuis.get("exposure_jumps", []):
        if first <= i <= last:
            g *= gain
    return g


def postprocess(raw_png, out, nuis, i, seed):
    cmd = ["nice", "-n", "19", "convert", raw_png]
    g = exposure_gain(nuis, i, seed)
    if abs(g - 1.0) > 1e-6:
        cmd += ["-evaluate", "multiply", "%.4f" % g]
    if nuis.get("noise"):
        cmd += ["-seed", str(1000 + i), "-attenuate", "%.3f" % nuis["noise"], "+noise", "Gaussian"]
    if nuis.get("jpeg_quality"):
        cmd += ["-quality", str(nuis["jpeg_quality"])]
    tmp = out + ".%d.part" % os.getpid() + os.path.splitext(out)[1]
    subprocess.run(cmd + [tmp], check=True)
    os.replace(tmp, out)


def take_claim(claim, stale_seconds=900):
    try:
        os.close(os.open(claim, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
        return True
    except FileExistsError:
        try:
            if time.time() - os.path.getmtime(claim) > stale_seconds:  # left by a killed render
                os.utime(claim)
                return True
        except OSError:
            pass
        return False


def save_stats(stats_file, stats):
    old = json.load(open(stats_file)) if os.path.exists(stats_file) else {}
    old.update(stats)
    with open(stats_file + ".%d.tmp" % os.getpid(), "w") as fh:
        json.dump(old, fh)
    os.replace(stats_file + ".%d.tmp" % os.getpid(), stats_file)


def remove_strays(d):
    """Removes what killed renders left in frames/ (part files, POV-Ray state files): the tracker reads every
    image file there."""
    truth = json.load(open(os.path.join(d, "truth.json")))
    keep = {os.path.basename(f["file"]) for f in truth["frames"]}
    for name in os.listdir(os.path.join(d, "frames")):
        if name not in keep and not name.endswith(".claim"):
            os.remove(os.path.join(d, "frames", name))


def ensure(scene, quiet=False):
    """Renders whatever is missing of SCENE into its cache folder; returns the folder."""
    spec = SCENES[scene]
    d = scene_dir(scene)
    os.makedirs(os.path.join(d, "frames"), exist_ok=True)
    # truth and plan are cheap and deterministic: always written, so that they follow this script
    truth = truth_for(scene)
    tmp = os.path.join(d, "truth.json.%d.tmp" % os.getpid())
    with open(tmp, "w") as fh:
        json.dump(truth, fh, indent=1)
    os.replace(tmp, os.path.join(d, "truth.json"))
    write_dxf(scene, os.path.join(d, "plan.dxf"))
    if is_complete(scene):
        remove_strays(d)
        return d
    frames = truth["frames"]
    # A truth variant's frames are jobs like the others: the walk's pose, more declares, another folder.
    jobs = [(f, f["file"], []) for f in frames]
    for folder, variant in truth.get("truth_variants", {}).items():
        os.makedirs(os.path.join(d, folder), exist_ok=True)
        jobs += [(frames[v["index"]], v["file"], variant["declares"]) for v in variant["frames"]]
    missing = [j for j in jobs if not os.path.exists(os.path.join(d, j[1]))]
    if missing:
        w, h = scene_size(spec)
        per_frame = 3 * w * h // (1024 * 512)
        log("%s: rendering %d of %d images into %s (%dx%d, one thread at nice 19: about %d CPU-seconds a "
            "frame, about %d min on an idle core, much longer on a busy machine)" %
            (scene, len(missing), len(jobs), d, w, h, per_frame, max(1, len(missing) * per_frame // 60)))
    nuis = spec["nuisances"]
    t0 = time.time()
    stats_file = os.path.join(d, "render_seconds.json")
    stats = json.load(open(stats_file)) if os.path.exists(stats_file) else {}
    # Frames are claimed one by one (a .claim file), so that two renders of the same scene (say `make bench`
    # and a `corpus.py render` in another shell, or two on a multi-core machine) share the work.
    n = 0
    for f, file, extra_declares in missing:
        i = f["index"]
        out = os.path.join(d, file)
        claim = out + ".claim"
        if os.path.exists(out) or not take_claim(claim):
            continue
        try:
            declares = camera_declares(f, spec["camera_height"], i, spec["walk"]["dt"]) + extra_declares
            t1 = time.time()
            if nuis:
                raw = os.path.join(d, "raw-%06d.png" % i)
                render_frame(spec["pov"], raw, declares, *scene_size(spec))
                postprocess(raw, out, nuis, i, spec["walk"]["seed"])
                os.remove(raw)
            else:
                render_frame(spec["pov"], out, declares, *scene_size(spec))
            stats[file] = round(time.time() - t1, 2)
        finally:
            os.remove(claim)
        n += 1
        if n % 20 == 0:
            save_stats(stats_file, stats)
            el = time.time() - t0
            left = sum(1 for j in jobs if not os.path.exists(os.path.join(d, j[1])))
            log("%s: %d frames rendered here in %.0f s; %d left in the scene" % (scene, n, el, left))
    save_stats(stats_file, stats)
    # Wait for frames that another process is rendering.
    while True:
        left = [j[1] for j in jobs if not os.path.exists(os.path.join(d, j[1]))]
        if not left:
            break
        if not any(os.path.exists(os.path.join(d, file) + ".claim") for file in left):
            raise RuntimeError("%s: %d frames neither rendered nor being rendered (e.g. %s)" %
                               (scene, len(left), left[0]))
        time.sleep(5)
    stats.update(json.load(open(stats_file)) if os.path.exists(stats_file) else {})
    remove_strays(d)
    done = {"scene": scene, "frames": len(frames), "hash": scene_hash(scene),
            "render_seconds_total": round(sum(stats.values()), 1), "script_version": SCRIPT_VERSION}
    with open(os.path.join(d, "complete.json"), "w") as fh:
        json.dump(done, fh, indent=1)
    return d


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    cmd = argv[1]
    if cmd == "list":
        for s in SCENES:
            t = truth_for(s)
            print("%-9s %4d frames %6.1f m  pieces %s  %s  %s" % (
                s, len(t["frames"]), t["length_m"], [(p["first_index"], p["last_index"]) for p in t["true_pieces"]],
                "cached" if is_complete(s) else "not rendered", scene_dir(s)))
        return 0
    if cmd == "render":
        for s in argv[2:] or list(SCENES):
            if s not in SCENES:
                raise SystemExit("unknown scene '%s' (scenes: %s)" % (s, ", ".join(SCENES)))
            print(ensure(s))
        return 0
    if cmd == "dir":
        print(scene_dir(argv[2]))
        return 0
    if cmd == "walk":
        with open(argv[3], "w") as fh:
            json.dump(truth_for(argv[2]), fh, indent=1)
        return 0
    if cmd == "dxf":
        write_dxf(argv[2], argv[3])
        return 0
    if cmd == "frame":
        s, i, out = argv[2], int(argv[3]), argv[4]
        spec = SCENES[s]
        f = truth_for(s)["frames"][i]
        render_frame(spec["pov"], out, camera_declares(f, spec["camera_height"], i, spec["walk"]["dt"]),
                     *scene_size(spec))
        return 0
    raise SystemExit("unknown command '%s' (see --help)" % cmd)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
