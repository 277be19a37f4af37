#!/usr/bin/python3
"""Benchmark: `plenopath track` on the POV-Ray corpus (corpus.py), scored against the renders' ground truth.

Installed by CMake as <build>/tests/bench/bench_povray_track (a wrapper passing --plenopath and --results);
`make bench` runs it with the other bench_* executables and expects one JSON object on stdout.

For each scene: renders whatever is missing from the cache (corpus.ensure; says so on stderr, with the time it
may take), runs `plenopath track --capture FRAMES --camera-height H --json`, then `plenopath eval-path` on the
whole path and, when the estimate carries a per-frame "piece" field, on each piece on its own (both files
split by the estimate's piece). Figures are reported as measured, against the targets of issue #18. Frames
the truth puts inside a wall (nothing to see) must be flagged by the tracker and are left out of the
figures, here and on the plan.
With --plan (default on): `track --plan plan.dxf` again, the path placed on the scene's plan by itself and
refined on its walls (issue 19), scored as it is, in plan coordinates, with no alignment at all: position
and heading RMS per placed piece, against issue 19's targets (5 cm, 0.2 deg), with the registration's and
the refinement's figures.

Options: --scenes a,b,c (default all), --plenopath PATH, --results DIR (estimates and split files),
--no-render (skip scenes that are not fully cached instead of rendering them; the default when
PLENOPATH_BENCH_QUICK=1), --partial (score a scene still rendering on its longest rendered prefix; the
figures are marked "partial" and are not the benchmark's), --stride K (video subsampled: every K-th frame
tracked, the path renumbered to the truth's frames by file name and scored against them; issue 18 asks for
10-30 cm steps).
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, HERE)
import corpus  # noqa: E402

TARGETS = {"heading_rms_deg": 0.05, "ate_pct": 0.05, "scale_error_pct": 0.5}
PLAN_TARGETS = {"position_rms_m": 0.05, "heading_rms_deg": 0.2}


def number_as_truth(estimate, truth):
    """A path tracked with --stride numbers its frames 0, 1, ... among those kept (as the studio does):
    renumbered here by file name to the truth's indices, so that every figure below matches them."""
    by_file = {os.path.basename(f["file"]): f["index"] for f in truth["frames"]}
    est = json.load(open(estimate))
    renumbered = {}
    for f in est["frames"]:
        renumbered[f["index"]] = by_file[os.path.basename(f["file"])]
        f["index"] = renumbered[f["index"]]
    for piece in est.get("pieces", []):
        for key in ("first_index", "last_index"):
            if key in piece:
                piece[key] = renumbered.get(piece[key], piece[key])
    write_json(estimate, est)
    # The points name the frame that measured each (the sight lines registration checks): renumbered alike,
    # so that the two files stay one tracked path.
    points_file = os.path.splitext(estimate)[0] + ".points.json"
    if os.path.exists(points_file):
        points = json.load(open(points_file))
        for p in points["points"]:
            if len(p) == 6 and p[5] >= 0:
                p[5] = renumbered.get(p[5], -1)
        write_json(points_file, points)


def track_args(args):
    return args.track_args.split() + (["--stride", str(args.stride)] if args.stride > 1 else [])


def on_plan(args, d, res, truth, frames_dir):
    """track --plan: the placed path's absolute errors per placed piece (plan coordinates, no alignment)."""
    estimate = os.path.join(res, "path_plan.json")
    cmd = [args.plenopath, "track", "--capture", frames_dir, "--camera-height", str(truth["camera_height_m"]),
           "--plan", os.path.join(d, "plan.dxf"), "--out", estimate, "--json", "--quiet"] + track_args(args)
    t0 = time.time()
    p = run(cmd)
    out = {"seconds": round(time.time() - t0, 1)}
    try:
        summary = json.loads(p.stdout)
        reg = summary.get("registration", {})
        out["registration"] = [{k: v for k, v in r.items() if k != "candidates"} for r in reg.get("pieces", [])]
        out["registration_seconds"] = reg.get("seconds")
        out["plan_refinement"] = reg.get("plan_refinement")
    except ValueError:
        pass
    if p.returncode != 0 or not os.path.exists(estimate):
        out["error"] = "track --plan exit %d: %s" % (p.returncode, (p.stderr or p.stdout).strip()[-2000:])
        out["pass"] = False
        return out
    number_as_truth(estimate, truth)
    est = json.load(open(estimate))
    truth_by_index = {f["index"]: f for f in truth["frames"]}
    blind = set(truth.get("frames_inside_walls", []))
    placed = {k for k, pc in enumerate(est.get("pieces", [{"placed": True}])) if pc.get("placed", True)}
    pieces = {}
    for f in est["frames"]:
        k = int(f.get("piece", 0))
        t = truth_by_index.get(f["index"])
        if k not in placed or t is None or f["index"] in blind:
            continue
        e = pieces.setdefault(k, {"piece": k, "frames": 0, "p2": 0.0, "h2": 0.0})
        e["frames"] += 1
        e["p2"] += (f["x"] - t["x"]) ** 2 + (f["y"] - t["y"]) ** 2
        e["h2"] += math.remainder(f["heading_deg"] - t["heading_deg"], 360.0) ** 2
    out["pieces"] = []
    for k in sorted(pieces):
        e = pieces[k]
        fig = {"piece": k, "frames": e["frames"], "position_rms_m": round(math.sqrt(e["p2"] / e["frames"]), 4),
               "heading_rms_deg": round(math.sqrt(e["h2"] / e["frames"]), 4)}
        fig["pass"] = all(fig[key] <= v for key, v in PLAN_TARGETS.items())
        out["pieces"].append(fig)
    out["unplaced_pieces"] = len(est.get("pieces", [{}])) - len(placed)
    out["pass"] = bool(out["pieces"]) and out["unplaced_pieces"] == 0 and all(f["pass"] for f in out["pieces"])
    return out


def run(cmd, **kw):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def git_commit():
    p = run(["git", "-C", HERE, "rev-parse", "--short", "HEAD"])
    return p.stdout.strip() if p.returncode == 0 else "unknown"


def loadavg():
    try:
        return open("/proc/loadavg").read().split()[:3]
    except OSError:
        return None


def eval_path(plenopath, estimate, truth):
    p = run([plenopath, "eval-path", "--estimate", estimate, "--truth", truth, "--json"])
    if p.returncode != 0:
        return {"error": (p.stderr or p.stdout).strip()[-2000:]}
    e = json.loads(p.stdout)
    return {"frames_matched": e["frames_matched"], "heading_rms_deg": e["rot_rms_deg"],
            "heading_max_deg": e["rot_max_deg"], "ate_rms_m": e["ate_rms_m"], "ate_pct": e["ate_pct"],
            "length_m": e["truth_length_m"], "scale_error_pct": e["scale_error_pct"]}


def meets(fig):
    if "error" in fig:
        return False
    return all(fig.get(k) is not None and fig[k] <= v for k, v in TARGETS.items())


def write_json(path, obj):
    with open(path + ".tmp", "w") as fh:
        json.dump(obj, fh, indent=1)
    os.replace(path + ".tmp", path)


def bench_scene(scene, args):
    spec = corpus.SCENES[scene]
    out = {"scene": scene, "description": spec["description"]}
    res = os.path.join(args.results, scene)
    os.makedirs(res, exist_ok=True)
    last = None
    if corpus.is_complete(scene):
        d = corpus.ensure(scene)
    elif args.partial:
        # The longest rendered prefix 0..last, scored against the truth of those frames only.
        d = corpus.scene_dir(scene)
        full = corpus.truth_for(scene)
        n = 0
        while n < len(full["frames"]) and os.path.exists(os.path.join(d, full["frames"][n]["file"])):
            n += 1
        if n < 10:
            out["skipped"] = "only %d frames rendered (--partial needs 10)" % n
            return out
        last = n - 1
        part = dict(full, frames=full["frames"][:n],
                    true_pieces=[dict(p, last_index=min(p["last_index"], last)) for p in full["true_pieces"]
                                 if p["first_index"] <= last])
        fr = part["frames"]
        part["length_m"] = round(sum(((a["x"] - b["x"]) ** 2 + (a["y"] - b["y"]) ** 2) ** 0.5
                                     for a, b in zip(fr, fr[1:])), 3)
        write_json(os.path.join(res, "truth_partial.json"), part)
        # the tracker reads every image in the folder: give it the prefix only
        pdir = os.path.join(res, "frames_partial")
        shutil.rmtree(pdir, ignore_errors=True)
        os.makedirs(pdir)
        for f in part["frames"]:
            os.symlink(os.path.join(d, f["file"]), os.path.join(pdir, os.path.basename(f["file"])))
        out["partial"] = {"frames_used": n, "frames_in_scene": len(full["frames"])}
    elif args.no_render:
        out["skipped"] = "not rendered (run tests/bench/povray/corpus.py render %s)" % scene
        return out
    else:
        d = corpus.ensure(scene)
    truth_file = os.path.join(res, "truth_partial.json") if last is not None else os.path.join(d, "truth.json")
    truth = json.load(open(truth_file))
    done_file = os.path.join(d, "complete.json")
    done = json.load(open(done_file)) if os.path.exists(done_file) else {}
    estimate = os.path.join(res, "path.json")
    out.update({"frames": len(truth["frames"]), "length_m": truth["length_m"],
                "render_seconds": done.get("render_seconds_total"), "cache": d,
                "true_pieces": [[p["first_index"], p["last_index"]] for p in truth["true_pieces"]]})
    frames_dir = os.path.join(res, "frames_partial") if last is not None else os.path.join(d, "frames")
    cmd = [args.plenopath, "track", "--capture", frames_dir, "--camera-height",
           str(truth["camera_height_m"]), "--out", estimate, "--json", "--quiet"] + track_args(args)
    corpus.log("%s: tracking %d frames" % (scene, len(truth["frames"])))
    t0 = time.time()
    p = run(cmd)
    out["seconds"] = round(time.time() - t0, 1)
    if p.returncode != 0 or not os.path.exists(estimate):
        out["error"] = "track exit %d: %s" % (p.returncode, (p.stderr or p.stdout).strip()[-2000:])
        out["pass"] = False
        return out
    try:
        summary = json.loads(p.stdout)
        if isinstance(summary, dict):
            out["track_summary"] = {k: v for k, v in summary.items() if not isinstance(v, (list, dict))}
            if isinstance(summary.get("pieces"), list):
                out["track_pieces"] = summary["pieces"]
            # What the frames' flags say (issue 18: be honest where the images do not connect); "reliable" and
            # any "warning" are among the scalars above.
            if isinstance(summary.get("flag_counts"), dict):
                out["track_flag_counts"] = summary["flag_counts"]
    except ValueError:
        pass
    number_as_truth(estimate, truth)
    est = json.load(open(estimate))
    out["frames_tracked"] = len(est["frames"])
    out["whole"] = eval_path(args.plenopath, estimate, truth_file)
    # Frames inside a wall have nothing to see: no image can place them. The tracker must flag them, and
    # they are left out of the pieces' figures (held at the last pose, they would only measure the hold).
    blind = set(truth.get("frames_inside_walls", []))
    if blind:
        flagged = sum(1 for f in est["frames"] if f["index"] in blind and int(f.get("flags", 0)) != 0)
        tracked = sum(1 for f in est["frames"] if f["index"] in blind)  # with --stride, not all of them
        out["frames_inside_walls"] = {"frames": tracked, "flagged": flagged}
    by_piece = {}
    for f in est["frames"]:
        if f["index"] not in blind:
            by_piece.setdefault(int(f.get("piece", 0)), []).append(f)
    truth_by_index = {f["index"]: f for f in truth["frames"]}
    out["pieces_found"] = len(by_piece)
    out["pieces_true"] = len(truth["true_pieces"])
    pieces = []
    for k in sorted(by_piece):
        frames = by_piece[k]
        idx = [f["index"] for f in frames]
        entry = {"piece": k, "first": min(idx), "last": max(idx), "frames": len(frames)}
        if len(by_piece) == 1:
            entry.update(out["whole"])
        elif len(frames) < 3:
            entry["error"] = "fewer than 3 frames"
        else:
            ef = os.path.join(res, "piece%d_estimate.json" % k)
            tf = os.path.join(res, "piece%d_truth.json" % k)
            # each piece as a one-piece path of its own
            write_json(ef, {"units": est.get("units", "m"),
                            "frames": [{k2: v for k2, v in f.items() if k2 != "piece"} for f in frames]})
            write_json(tf, {"units": truth["units"],
                            "frames": [truth_by_index[i] for i in idx if i in truth_by_index]})
            entry.update(eval_path(args.plenopath, ef, tf))
        entry["pass"] = meets(entry)
        pieces.append(entry)
    out["pieces"] = pieces
    all_flagged = not blind or out["frames_inside_walls"]["flagged"] == out["frames_inside_walls"]["frames"]
    out["pass"] = out["pieces_found"] == out["pieces_true"] and all(e["pass"] for e in pieces) and all_flagged
    if not args.no_plan and os.path.exists(os.path.join(d, "plan.dxf")):
        corpus.log("%s: tracking again with --plan" % scene)
        out["on_plan"] = on_plan(args, d, res, truth, frames_dir)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    # Stills scenes have their own benchmark (bench_povray_stills.py).
    ap.add_argument("--scenes", default=",".join(s for s in corpus.SCENES if "stills" not in corpus.SCENES[s]))
    ap.add_argument("--plenopath", default=os.path.join(HERE, "..", "..", "..", "build", "app", "plenopath"))
    ap.add_argument("--results", default=os.path.join(corpus.cache_root(), "results"))
    ap.add_argument("--no-render", action="store_true")
    ap.add_argument("--partial", action="store_true",
                    help="score scenes still rendering on their longest rendered prefix (marked partial)")
    ap.add_argument("--track-args", default="",
                    help="more options for plenopath track, e.g. \"--tilt-prior 0\" (to compare in one run)")
    ap.add_argument("--no-plan", action="store_true", help="skip the run with --plan (placement on the plan)")
    ap.add_argument("--stride", type=int, default=1,
                    help="track every K-th frame (video subsampled to K times the steps), scored against the "
                         "truth of those frames")
    args = ap.parse_args()
    if os.environ.get("PLENOPATH_BENCH_QUICK") == "1":
        args.no_render = True
    report = {"benchmark": "povray_track", "commit": git_commit(), "load_before": loadavg(),
              "targets": TARGETS, "plan_targets": PLAN_TARGETS, "cache": corpus.cache_root(), "track_args": args.track_args, "stride": args.stride,
              "scenes": []}
    t0 = time.time()
    for scene in [s for s in args.scenes.split(",") if s]:
        if scene not in corpus.SCENES:
            report["scenes"].append({"scene": scene, "error": "unknown scene"})
            continue
        try:
            report["scenes"].append(bench_scene(scene, args))
        except Exception as e:  # a broken scene must not hide the others' figures
            report["scenes"].append({"scene": scene, "error": "%s: %s" % (type(e).__name__, e), "pass": False})
    report["load_after"] = loadavg()
    report["seconds"] = round(time.time() - t0, 1)
    report["pass"] = all(s.get("pass", False) for s in report["scenes"] if "skipped" not in s and "partial" not in s)
    print(json.dumps(report, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
