#!/usr/bin/python3
"""Benchmark: a scene from Debian's povray-examples, made by someone else, taken end to end (issue 23).

Installed by CMake as <build>/tests/bench/bench_povray_examples (a wrapper passing --plenopath and --results);
prints one JSON object on stdout.

For each scene below (povray-examples' radiosity/patio-radio_37: a cloister in centimetres, with the author's
ground fog and radiosity):
  1. `render-scene --online --loss-target L --project P --section-plan`: the whole walk as coarse depth,
     full frames only for the fewest keyframes meeting the loss target, landed in a project whose plan is
     the scene cut at eye height (the scene comes without a DXF);
  2. the depth of the keyframes against the scene's own geometry where it is known by hand: the cloister's
     floor (POV y = 0), seen within 25 degrees of the nadir, at camera_height / cos(angle off the nadir);
     the author's fog would put it off by the fog's share if the depth passes kept it;
  3. `export --project P`: the tour package, its keyframe count;
  4. with --track: a dense stretch of the walk rendered in full (colour and depth), tracked by `plenopath
     track` and scored against the render's truth with `eval-path`.
Needs Debian's povray-examples (cmake/install-deps.sh installs it); a scene that is not there is reported
skipped. The renders are cached under ${PLENOPATH_BENCH_CACHE:-~/.cache/plenopath/povray}/examples-<scene>.

Options: --scenes a,b, --plenopath PATH, --results DIR, --size WxH (default 1024x512), --loss-target L
(default 0.1), --track (also the dense stretch), --force (render again).
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "app"))
from png16 import read_png16  # noqa: E402

EXAMPLES = "/usr/share/povray-3.7/scenes"
SCENES = {
    # A cloister: an arcade of columns and vaults round a courtyard, modelled in centimetres, y up.
    "patio": {
        "scene": "radiosity/patio-radio_37.pov",
        "units_per_metre": 100,
        "z_up": False,
        # 1.5 m: the arches across the arcade are rings clipped to their upper half, and POV-Ray keeps the
        # inside of a clipped object's whole shape; their lower halves reach down to 1.6 m, and a camera
        # there gets no fog, so no depth (render-scene says so, naming the frame).
        "camera_height_m": 1.5,
        # Along the arcade between its two rows of columns, then out into the courtyard.
        "waypoints": "-6.4,-3.6 -6.4,3.0 -3.2,3.0 0,0.5",
        "step": 0.1,
        "floor_y": 0.0,
        # A dense stretch for tracking: 0.1 m steps along the arcade.
        "track_waypoints": "-6.4,-3.6 -6.4,0.4",
    },
}


def run(cmd, **kw):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def git_commit():
    p = run(["git", "-C", os.path.dirname(os.path.abspath(__file__)), "rev-parse", "--short", "HEAD"])
    return p.stdout.strip() if p.returncode == 0 else "unknown"


def load_average():
    try:
        return float(open("/proc/loadavg").read().split()[0])
    except OSError:
        return -1.0


def floor_depth_errors(depth_png, camera_height, max_off_nadir_deg=25.0):
    """Relative errors of the depth of the floor pixels near the nadir (the floor is flat at y = 0)."""
    w, h, rows = read_png16(depth_png)
    errors = []
    for v in range(h):
        elevation = math.pi / 2 - (v + 0.5) / h * math.pi
        off_nadir = math.degrees(math.pi / 2 + elevation)
        if off_nadir > max_off_nadir_deg:
            continue
        expected = camera_height / math.cos(math.radians(off_nadir))
        for u in range(w):
            if rows[v][u] > 0:
                errors.append(abs(rows[v][u] / 1000.0 - expected) / expected)
    errors.sort()
    return errors


def percentile(sorted_values, q):
    if not sorted_values:
        return None
    return sorted_values[min(len(sorted_values) - 1, int(q * len(sorted_values)))]


def bench_scene(args, name, spec, root):
    scene = os.path.join(EXAMPLES, spec["scene"])
    out = {"scene": name, "file": scene}
    if not os.path.exists(scene):
        out["skipped"] = "not installed: sudo apt-get install povray-examples"
        return out
    work = os.path.join(root, "examples-" + name)
    if args.force and os.path.isdir(work):
        shutil.rmtree(work)
    os.makedirs(work, exist_ok=True)
    project = os.path.join(work, name + ".plenopath")
    capture = os.path.join(work, "online")
    common = ["--scene", scene, "--units-per-metre", str(spec["units_per_metre"]), "--camera-height",
              str(spec["camera_height_m"])] + (["--z-up"] if spec["z_up"] else [])
    # 1. Online render into a project, its plan cut at eye height.
    report_file = os.path.join(capture, "online_sampling.json")
    if not (os.path.exists(report_file) and os.path.exists(project)):
        t0 = time.time()
        p = run([args.plenopath, "render-scene"] + common +
                ["--waypoints", spec["waypoints"], "--step", str(spec["step"]), "--size", args.size, "--online",
                 "--loss-target", str(args.loss_target), "--project", project, "--section-plan", "--out", capture])
        out["render_seconds"] = round(time.time() - t0, 1)
        if p.returncode != 0:
            out["error"] = "render-scene exit %d: %s" % (p.returncode, p.stderr.strip()[-2000:])
            return out
    report = json.load(open(report_file))
    out["online"] = {k: report[k] for k in ("path_frames", "coarse_frames", "coarse_width", "full_frames",
                                            "full_size", "loss_mean", "loss_p95", "loss_target",
                                            "loss_target_met", "samplings", "seconds_coarse", "seconds_total")}
    out["online"]["full_share"] = round(report["full_frames"] / report["path_frames"], 4)
    info = json.loads(run([args.plenopath, "info", project, "--json"]).stdout)
    out["project"] = {"frames": info["capture"]["frames"], "keyframes": info["keyframes"]["count"],
                      "plan_segments": info["plan"]["segments"], "plan_extents_m": info["plan"].get("extents_m")}
    # 2. Depth against the floor.
    errors = []
    for f in sorted(os.listdir(os.path.join(capture, "depth"))):
        errors += floor_depth_errors(os.path.join(capture, "depth", f), spec["camera_height_m"])
    out["floor_depth"] = {"pixels": len(errors), "relative_error_median": percentile(errors, 0.5),
                          "relative_error_p95": percentile(errors, 0.95)}
    # 3. Export.
    tour = os.path.join(work, "tour")
    shutil.rmtree(tour, ignore_errors=True)
    p = run([args.plenopath, "export", "--project", project, "--out", tour])
    if p.returncode != 0:
        out["error"] = "export exit %d: %s" % (p.returncode, p.stderr.strip()[-2000:])
        return out
    tour_json = json.load(open(os.path.join(tour, "tour.json")))
    out["export"] = {"keyframes": len(tour_json["keyframes"]), "folder": tour}
    # 4. A dense stretch, tracked.
    if args.track:
        dense = os.path.join(work, "dense")
        if not os.path.exists(os.path.join(dense, "groundtruth.json")):
            t0 = time.time()
            p = run([args.plenopath, "render-scene"] + common +
                    ["--waypoints", spec["track_waypoints"], "--step", "0.1", "--size", args.track_size,
                     "--out", dense])
            out["dense_render_seconds"] = round(time.time() - t0, 1)
            if p.returncode != 0:
                out["error"] = "dense render-scene exit %d: %s" % (p.returncode, p.stderr.strip()[-2000:])
                return out
        estimate = os.path.join(work, "dense_track.json")
        t0 = time.time()
        p = run([args.plenopath, "track", "--capture", os.path.join(dense, "frames"), "--camera-height",
                 str(spec["camera_height_m"]), "--out", estimate, "--json", "--quiet"])
        out["track_seconds"] = round(time.time() - t0, 1)
        if p.returncode != 0:
            out["track_error"] = p.stderr.strip()[-2000:]
        else:
            e = run([args.plenopath, "eval-path", "--estimate", estimate, "--truth",
                     os.path.join(dense, "groundtruth.json"), "--json"])
            out["track"] = json.loads(e.stdout) if e.returncode == 0 else {"error": e.stderr.strip()}
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plenopath", default="plenopath")
    ap.add_argument("--results", default="povray-results-examples")
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--size", default="1024x512")
    ap.add_argument("--track-size", default="512x256")
    ap.add_argument("--loss-target", type=float, default=0.1)
    ap.add_argument("--track", action="store_true")
    ap.add_argument("--force", action="store_true")
    args = ap.parse_args()
    root = os.environ.get("PLENOPATH_BENCH_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "plenopath",
                                                                   "povray")
    result = {"benchmark": "povray_examples", "commit": git_commit(), "load_average_at_start": load_average(),
              "scenes": []}
    t0 = time.time()
    for name in args.scenes.split(","):
        result["scenes"].append(bench_scene(args, name, SCENES[name], root))
    result["seconds"] = round(time.time() - t0, 1)
    os.makedirs(args.results, exist_ok=True)
    json.dump(result, open(os.path.join(args.results, "povray_examples.json"), "w"), indent=2)
    print(json.dumps(result))


if __name__ == "__main__":
    main()
