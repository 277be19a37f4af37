#!/usr/bin/python3
"""The DXF importer against python3-ezdxf over a corpus of real files (issue 16).

    /usr/bin/python3 tests/app/dxf_corpus_check.py PLENOPATH CORPUS_DIR [--report out.json]
                     [--jobs N] [--only NAME ...]

For each DXF file:
  ezdxf (the oracle, Debian's python3-ezdxf) reads it (ezdxf.readfile, or ezdxf.recover.readfile for files
  it refuses) and gives, for model space only, the count per layer per kind of the entities the importer
  reads, and the XY bounding box (drawing units) of the geometry they make without text: INSERTs exploded
  recursively (arrays too, attributes dropped), TEXT/MTEXT/ATTRIB/DIMENSION/POINT dropped, arcs and
  ellipses bounded exactly, splines flattened to 1e-7 of their size.
  `PLENOPATH plan-info --json --keep-stray FILE` must exit 0 with JSON, or exit 1 with a message on stderr
  that names the file; never a signal, a hang (60 s) or "internal error".
  Then per layer and kind: ours read + ours skipped as invalid == ezdxf's count, and the boxes agree within
  0.005 / metres_per_unit (our chord tolerance) + 1e-7 * size (ours) + 1e-6 * size.

Exit status 0 only when at least MIN_IMPORTED of the files with 2-D geometry import, nothing crashes, hangs
or says "internal error", and every imported file agrees with ezdxf (apart from the ALLOWED list below).
The last line is "P passed, F failed".
"""
import argparse
import concurrent.futures
import json
import logging
import math
import os
import subprocess
import sys
import time

import ezdxf
import ezdxf.recover
from ezdxf.addons import iterdxf
from ezdxf.math import Vec3, bulge_to_arc
from ezdxf.math import BSpline, fit_points_to_cad_cv
from ezdxf.math.transformtools import InsertTransformationError, NonUniformScalingError
from ezdxf.entities import Ellipse
from ezdxf.render.trace import TraceBuilder

# Issue 16: "of the 69 ezdxf files with 2-D geometry, at least 66 import".
MIN_IMPORTED = 66
TIMEOUT_S = 60
# Kinds the importer reads (counted per layer); the subset that makes geometry (the box).
READ_KINDS = {"LINE", "LWPOLYLINE", "POLYLINE", "ARC", "CIRCLE", "ELLIPSE", "SPLINE", "INSERT", "HATCH",
              "SOLID", "TRACE", "MLINE", "TEXT", "MTEXT"}
GEOMETRY_KINDS = READ_KINDS - {"TEXT", "MTEXT", "INSERT"}
# Reasons in our "skipped" list that do not concern model-space entities of READ_KINDS that ezdxf counts:
# entities outside model space, and 3-D polylines (ezdxf's count leaves them out too).
NOT_COUNTED_REASONS = ("paper space", "3-d only")
MAX_NESTING = 32
logging.getLogger("ezdxf").setLevel(logging.ERROR)  # the recover notes are kept in the report instead
SPLINE_FLATTENING = 1e-7  # of the spline's control-point box diagonal

# Genuine disagreements between ezdxf and the file, each with the reason: file -> {"counts": {(layer, kind): the
# count the file holds (ezdxf.addons.iterdxf sees them)}, "box": why ezdxf's box is no oracle here}.
_TEXT_FRAMES = ("ezdxf 0.18 destroys the LWPOLYLINE text frames that AutoCAD writes beside a framed MTEXT for "
                "readers older than R2018 (MTEXT xdata ACAD_MTEXT_TEXT_BORDERS, ezdxf/entities/mtext.py "
                "post_load_hook); they are model-space entities of the file and the importer reads them as such")
ALLOWED = {
    "integration_tests_data_mtext_framed_columns.dxf": {
        "counts": {("DYNAMIC", "LWPOLYLINE"): 3, ("STATIC", "LWPOLYLINE"): 3}, "box": _TEXT_FRAMES},
    "integration_tests_data_mtext_text_frame.dxf": {
        "counts": {("MTEXT_EXPLODE", "LWPOLYLINE"): 1}, "box": _TEXT_FRAMES},
}


# ---------------------------------------------------------------------------------------------- ezdxf side
class Box:
    def __init__(self):
        self.min = [math.inf, math.inf]
        self.max = [-math.inf, -math.inf]
        self.non_finite = 0

    def add(self, x, y):
        if not (math.isfinite(x) and math.isfinite(y)):
            self.non_finite += 1
            return
        self.min[0] = min(self.min[0], x)
        self.min[1] = min(self.min[1], y)
        self.max[0] = max(self.max[0], x)
        self.max[1] = max(self.max[1], y)

    def add_point(self, p):
        self.add(float(p[0]), float(p[1]))

    @property
    def valid(self):
        return self.min[0] <= self.max[0]

    def as_json(self):
        return {"min": self.min, "max": self.max} if self.valid else None


def add_elliptic_arc(box, c, u, v, t0, t1):
    """Exact XY box of c + u cos t + v sin t for t in [t0, t1] (t1 >= t0, radians, 3-D vectors)."""
    ts = [t0, t1]
    for k in (0, 1):  # d/dt x_k = -u_k sin t + v_k cos t = 0 at t = atan2(v_k, u_k) + n pi
        phi = math.atan2(v[k], u[k])
        n = math.ceil((t0 - phi) / math.pi)
        t = phi + n * math.pi
        while t <= t1:
            ts.append(t)
            t += math.pi
    for t in ts:
        ct, st = math.cos(t), math.sin(t)
        box.add(c[0] + u[0] * ct + v[0] * st, c[1] + u[1] * ct + v[1] * st)


def ccw_sweep(a0, a1):
    """Counter-clockwise sweep from a0 to a1 (radians) as (a0, a1') with a0 <= a1' < a0 + 2 pi + eps."""
    while a1 < a0:
        a1 += 2 * math.pi
    while a1 - a0 > 2 * math.pi + 1e-12:
        a1 -= 2 * math.pi
    return a0, a1


def add_ocs_arc(box, ocs, cx, cy, elevation, r, a0, a1):
    """Circular arc in an OCS, counter-clockwise from a0 to a1 (radians)."""
    c = Vec3(ocs.to_wcs(Vec3(cx, cy, elevation)))
    u = Vec3(ocs.to_wcs(Vec3(r, 0, 0)))
    v = Vec3(ocs.to_wcs(Vec3(0, r, 0)))
    t0, t1 = ccw_sweep(a0, a1)
    add_elliptic_arc(box, c, u, v, t0, t1)


def add_bulge_polyline(box, ocs, elevation, vertices, closed):
    """vertices: [(x, y, bulge)] in the OCS; a bulge belongs to the segment starting at its vertex."""
    n = len(vertices)
    if n < 2:
        return 0
    segments = n if closed else n - 1
    for i in range(segments):
        x0, y0, b = vertices[i]
        x1, y1, _ = vertices[(i + 1) % n]
        if abs(b) < 1e-12 or (x0 == x1 and y0 == y1):
            box.add_point(Vec3(ocs.to_wcs(Vec3(x0, y0, elevation))))
            box.add_point(Vec3(ocs.to_wcs(Vec3(x1, y1, elevation))))
        else:
            center, a0, a1, r = bulge_to_arc((x0, y0), (x1, y1), b)
            add_ocs_arc(box, ocs, center.x, center.y, elevation, r, a0, a1)
    return segments


def add_widths(box, polyline, ocs, elevation, wide):
    """A wide polyline is drawn as a filled band (AutoCAD's extents include it): the band's outline from
    ezdxf's renderer (miter joints; arcs as 4096 chords per circle, 3e-7 of the radius inside)."""
    if not wide:
        return
    for face in TraceBuilder.from_polyline(polyline, segments=4096).faces_wcs(ocs, elevation):
        for p in face:
            box.add_point(p)


def add_points(box, points, transform=None):
    n = 0
    for p in points:
        box.add_point(transform(p) if transform else p)
        n += 1
    return n


def add_bspline(box, bspline, transform=None):
    cps = list(bspline.control_points)
    if not cps:
        return 0
    span = Box()
    for p in cps:
        span.add_point(p)
    diag = math.hypot(span.max[0] - span.min[0], span.max[1] - span.min[1]) if span.valid else 0.0
    distance = max(diag * SPLINE_FLATTENING, 1e-12)
    return add_points(box, bspline.flattening(distance, segments=8), transform)


def add_hatch(box, hatch):
    ocs = hatch.ocs()
    elevation = hatch.dxf.elevation.z
    to_wcs = lambda p: Vec3(ocs.to_wcs(Vec3(p[0], p[1], elevation)))
    n = 0
    for path in hatch.paths:
        if hasattr(path, "vertices"):  # polyline path: (x, y, bulge)
            n += add_bulge_polyline(box, ocs, elevation, [(v[0], v[1], v[2] if len(v) > 2 else 0.0)
                                                          for v in path.vertices], path.is_closed)
            continue
        for edge in path.edges:
            kind = type(edge).__name__
            if kind == "LineEdge":
                box.add_point(to_wcs(edge.start))
                box.add_point(to_wcs(edge.end))
            elif kind == "ArcEdge":  # ezdxf stores the angles counter-clockwise (see ArcEdge.load_tags)
                add_ocs_arc(box, ocs, edge.center[0], edge.center[1], elevation, edge.radius,
                            math.radians(edge.start_angle), math.radians(edge.end_angle))
            elif kind == "EllipseEdge":
                e = edge.construction_tool()  # in the OCS, counter-clockwise
                c = to_wcs(e.center)
                u = Vec3(ocs.to_wcs(Vec3(e.major_axis.x, e.major_axis.y, 0)))
                v = Vec3(ocs.to_wcs(Vec3(e.minor_axis.x, e.minor_axis.y, 0)))
                t0, t1 = ccw_sweep(e.start_param, e.end_param)
                if t1 - t0 < 1e-12:
                    t1 = t0 + 2 * math.pi
                add_elliptic_arc(box, c, u, v, t0, t1)
            elif kind == "SplineEdge":
                if edge.control_points:
                    bs = BSpline([Vec3(p[0], p[1], 0) for p in edge.control_points], order=edge.degree + 1,
                                 knots=edge.knot_values or None, weights=edge.weights or None)
                elif len(edge.fit_points) >= 2:
                    bs = fit_points_to_cad_cv([Vec3(p[0], p[1], 0) for p in edge.fit_points])
                else:
                    continue
                add_bspline(box, bs, to_wcs)
            else:
                continue
            n += 1
    return n


def add_geometry(box, e, depth, problems):
    """Adds the XY extent of one entity (exploding INSERT/MLINE); returns how many pieces it made."""
    kind = e.dxftype()
    if kind == "LINE":
        box.add_point(e.dxf.start)
        box.add_point(e.dxf.end)
        return 1
    if kind in ("ARC", "CIRCLE"):
        r = e.dxf.radius
        if not r > 0:
            return 0
        a0, a1 = (math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle)) if kind == "ARC" \
            else (0.0, 2 * math.pi)
        c = e.dxf.center  # OCS, z = elevation
        add_ocs_arc(box, e.ocs(), c.x, c.y, c.z, r, a0, a1)
        return 1
    if kind == "ELLIPSE":
        u = Vec3(e.dxf.major_axis)
        if u.magnitude == 0 or not e.dxf.ratio > 0:
            return 0
        t0, t1 = ccw_sweep(e.dxf.start_param, e.dxf.end_param)
        if t1 - t0 < 1e-12:
            t1 = t0 + 2 * math.pi
        add_elliptic_arc(box, Vec3(e.dxf.center), u, Vec3(e.minor_axis), t0, t1)
        return 1
    if kind == "LWPOLYLINE":
        ocs = e.ocs()
        add_widths(box, e, ocs, e.dxf.elevation,
                   e.dxf.const_width > 0 or any(s > 0 or t > 0 for s, t in e.get_points("se")))
        return add_bulge_polyline(box, ocs, e.dxf.elevation, [(x, y, b) for x, y, b in e.get_points("xyb")],
                                  e.closed)
    if kind == "POLYLINE":
        if not e.is_2d_polyline:
            return 0  # 3-D polyline, polyface or polygon mesh: "3-D only"
        spline_fit = bool(e.dxf.flags & 4)
        # A spline-fit polyline is drawn through its fit vertices (flag 8), not its frame (flag 16).
        vs = [v for v in e.vertices if not (spline_fit and v.dxf.flags & 16)]
        verts = [(v.dxf.location.x, v.dxf.location.y, v.dxf.bulge) for v in vs]
        if not spline_fit:
            add_widths(box, e, e.ocs(), e.dxf.elevation.z,
                       e.dxf.default_start_width > 0 or e.dxf.default_end_width > 0 or
                       any(v.dxf.get("start_width", 0) > 0 or v.dxf.get("end_width", 0) > 0 for v in vs))
        return add_bulge_polyline(box, e.ocs(), e.dxf.elevation.z, verts, e.is_closed)
    if kind == "SPLINE":
        try:
            bs = e.construction_tool()
        except Exception as err:  # no control points and no fit points
            problems.append(f"SPLINE {e.dxf.handle}: {err}")
            return 0
        return 1 if add_bspline(box, bs) else 0
    if kind in ("SOLID", "TRACE"):
        return 1 if add_points(box, e.wcs_vertices()) else 0
    if kind == "HATCH":
        return 1 if add_hatch(box, e) else 0
    if kind == "MLINE":
        # One polyline per element: the element lines only; end caps lie between their ends, and round caps
        # are not drawn by the importer.
        n = 0
        try:
            for ve in e.virtual_entities():
                if ve.dxftype() == "LINE":
                    box.add_point(ve.dxf.start)
                    box.add_point(ve.dxf.end)
                    n += 1
        except Exception as err:
            problems.append(f"MLINE {e.dxf.handle}: {err}")
        return 1 if n else 0
    if kind == "INSERT":
        n = 0
        try:
            for piece in block_geometry(e, depth, problems):
                n += add_geometry(box, piece, depth + 1, problems)
        except Exception as err:
            problems.append(f"INSERT {e.dxf.get('name', '?')}: {type(err).__name__}: {err}")
        return n
    return 0


def block_geometry(insert, depth, problems):
    """The geometry entities of a block reference in WCS, nested blocks and MINSERT arrays resolved.

    Like ezdxf's Insert.virtual_entities(), but leaving out what the box leaves out before it is copied:
    virtual_entities() renders a DIMENSION (and other non-copyable entities) inside a block into LINE/SOLID/
    MTEXT pieces, which would put dimension graphics into the box."""
    if depth >= MAX_NESTING:
        problems.append(f"INSERT nested deeper than {MAX_NESTING}")
        return
    if insert.mcount > 1:
        for cell in insert.multi_insert():
            yield from block_geometry(cell, depth, problems)
        return
    block = insert.block()
    if block is None:
        return  # missing block definition: nothing to draw (the importer skips or reads it empty)
    m = insert.matrix44()
    for entity in block:
        kind = entity.dxftype()
        if kind not in GEOMETRY_KINDS and kind != "INSERT":
            continue
        if kind == "POLYLINE" and not entity.is_2d_polyline:
            continue
        yield from transformed(entity.copy(), m, depth, problems)


def transformed(entity, m, depth, problems):
    """`entity` (a copy) moved by the block transformation m; what cannot be moved as such (arcs under
    non-uniform scaling, sheared nested blocks) is split into pieces first, as ezdxf's explode does."""
    try:
        entity.transform(m)
        yield entity
    except NonUniformScalingError:
        kind = entity.dxftype()
        if kind in ("ARC", "CIRCLE"):
            if entity.dxf.radius > 0:
                yield Ellipse.from_arc(entity).transform(m)
        elif kind in ("LWPOLYLINE", "POLYLINE"):
            for piece in entity.virtual_entities():
                yield from transformed(piece, m, depth, problems)
        else:
            problems.append(f"{kind} in a block: non-uniform scaling not supported by ezdxf")
    except InsertTransformationError:  # nested INSERT sheared by m: resolve it first, then move the pieces
        for piece in block_geometry(entity, depth + 1, problems):
            yield from transformed(piece, m, depth, problems)


def read_with_ezdxf(path):
    try:
        return ezdxf.readfile(path), "readfile", []
    except Exception as first:
        try:
            doc, auditor = ezdxf.recover.readfile(path)
            return doc, "recover", [f"readfile: {type(first).__name__}: {first}"] + \
                [str(e.message) for e in auditor.errors[:5]]
        except Exception as second:
            return None, "unreadable", [f"readfile: {type(first).__name__}: {first}",
                                        f"recover: {type(second).__name__}: {second}"]


def modelspace_entities(path, facts):
    """Model-space entities from the whole document, or, for files whose tables or blocks ezdxf 0.18 cannot
    build a document from, entity by entity from the ENTITIES section (ezdxf.addons.iterdxf)."""
    doc, how, notes = read_with_ezdxf(path)
    facts.update(read=how, notes=notes)
    if doc is not None:
        return list(doc.modelspace())
    try:
        entities = list(iterdxf.modelspace(path))
    except Exception as err:
        facts["notes"].append(f"iterdxf: {type(err).__name__}: {err}")
        return []
    facts["read"] = "iterdxf"
    return entities


def ezdxf_facts(path):
    """What ezdxf finds in model space: counts per layer per kind, 3-D polylines, the geometry's XY box."""
    t = time.time()
    facts = {"read": "", "notes": [], "counts": {}, "three_d": {}, "box": None, "box_complete": True,
             "geometry_pieces": 0, "problems": [], "seconds": 0.0}
    entities = modelspace_entities(path, facts)
    box = Box()
    counts, three_d = {}, {}
    pieces = 0
    for e in entities:
        kind = e.dxftype()
        if kind not in READ_KINDS:
            continue
        layer = e.dxf.get("layer", "0")
        if kind == "POLYLINE" and not e.is_2d_polyline:
            three_d[layer] = three_d.get(layer, 0) + 1
            continue
        n = 1
        if kind == "MTEXT" and e.has_columns:
            # Before R2018 each further column is an MTEXT of its own in the file, which ezdxf links to the
            # first and takes out of the layout: count them as the file holds them.
            n += len(e.columns.linked_columns)
        counts.setdefault(layer, {})
        counts[layer][kind] = counts[layer].get(kind, 0) + n
        if kind == "INSERT" and facts["read"] == "iterdxf":
            facts["box_complete"] = False  # no blocks without the document
            facts["problems"].append("INSERT not exploded (no document)")
        elif kind in GEOMETRY_KINDS or kind == "INSERT":
            try:
                pieces += add_geometry(box, e, 0, facts["problems"])
            except Exception as err:
                facts["problems"].append(f"{kind} {e.dxf.handle}: {type(err).__name__}: {err}")
    if any(p.startswith(("INSERT", "MLINE")) for p in facts["problems"]):
        facts["box_complete"] = False  # ezdxf could not explode all of it: its box is no oracle
    facts.update(counts=counts, three_d=three_d, box=box.as_json(), geometry_pieces=pieces,
                 non_finite_points=box.non_finite, seconds=time.time() - t)
    return facts


# ------------------------------------------------------------------------------------------ plenopath side
def run_plenopath(binary, path):
    t = time.time()
    out = {"status": "", "rc": None, "stderr": "", "json": None}
    try:
        p = subprocess.run([binary, "plan-info", "--json", "--keep-stray", path], capture_output=True,
                           timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        out.update(status="hang", seconds=time.time() - t)
        return out
    out["seconds"] = time.time() - t
    out["rc"] = p.returncode
    stdout = p.stdout.decode("utf-8", "replace")
    stderr = p.stderr.decode("utf-8", "replace")
    out["stderr"] = stderr.strip()[-400:]
    if p.returncode < 0 or p.returncode > 1:
        out["status"] = "crash"
    elif "internal error" in (stdout + stderr).lower():
        out["status"] = "internal error"
    elif p.returncode == 1:
        named = os.path.basename(path) in stderr
        out["status"] = "refused" if named and stderr.strip() else "unnamed refusal"
    else:
        try:
            out["json"] = json.loads(stdout)
            out["status"] = "imported"
        except ValueError as err:
            out["status"] = "bad json"
            out["stderr"] = f"{err}; stdout starts {stdout[:120]!r}"
    return out


# ------------------------------------------------------------------------------------------------- compare
REQUIRED_FIELDS = ("metres_per_unit", "entities_by_layer", "skipped", "entities_skipped", "drawing_extents")


def compare(name, facts, ours):
    """Mismatches between ezdxf's facts and our JSON, as short strings (empty = agree)."""
    j = ours["json"]
    missing = [f for f in REQUIRED_FIELDS if f not in j]
    if missing:
        return [f"JSON lacks {', '.join(missing)}"], {}
    allowed = ALLOWED.get(name, {})
    allowed_counts = allowed.get("counts", {})
    mismatches = []
    skipped_listed = j["skipped"]
    truncated = j["entities_skipped"] > len(skipped_listed)
    invalid = {}
    for s in skipped_listed:
        why = str(s.get("why", "")).lower()
        if s.get("kind") in READ_KINDS and not any(r in why for r in NOT_COUNTED_REASONS):
            key = (s.get("layer", ""), s.get("kind"))
            invalid[key] = invalid.get(key, 0) + 1
    read = {}
    for layer, kinds in j["entities_by_layer"].items():
        for kind, n in kinds.items():
            read[(layer, kind)] = n
    theirs = {(layer, kind): n for layer, kinds in facts["counts"].items() for kind, n in kinds.items()}
    for key in sorted(set(read) | set(theirs) | set(invalid)):
        if key[1] not in READ_KINDS:
            continue
        r, s, t = read.get(key, 0), invalid.get(key, 0), theirs.get(key, 0)
        if key in allowed_counts:
            t = allowed_counts[key]
        if r + s == t:
            continue
        if truncated and r <= t:
            continue  # the rest may be among the skipped entities not listed
        mismatches.append(f"layer {key[0]!r} {key[1]}: ours {r} read + {s} invalid, ezdxf {t}")
    box_info = {}
    ez, ob = facts["box"], j["drawing_extents"]
    if "box" in allowed or not facts["box_complete"]:
        pass
    elif ez is None and ob is None:
        pass
    elif ez is None or ob is None:
        mismatches.append(f"box: ours {ob}, ezdxf {ez}")
    else:
        mpu = j["metres_per_unit"]
        size = max(ez["max"][0] - ez["min"][0], ez["max"][1] - ez["min"][1])
        tol = 0.005 / mpu + SPLINE_FLATTENING * size + 1e-6 * size
        dev = max(abs(ob["min"][0] - ez["min"][0]), abs(ob["min"][1] - ez["min"][1]),
                  abs(ob["max"][0] - ez["max"][0]), abs(ob["max"][1] - ez["max"][1]))
        box_info = {"deviation": dev, "tolerance": tol}
        if not dev <= tol:
            mismatches.append(f"box: ours {fmt_box(ob)}, ezdxf {fmt_box(ez)} (off by {dev:.6g} > {tol:.6g})")
    return mismatches, box_info


def fmt_box(b):
    return "[{:.6g}, {:.6g}]-[{:.6g}, {:.6g}]".format(b["min"][0], b["min"][1], b["max"][0], b["max"][1])


def check_file(binary, path):
    name = os.path.basename(path)
    facts = ezdxf_facts(path)
    ours = run_plenopath(binary, path)
    has_2d = facts["box"] is not None
    result = {"file": name, "has_2d": has_2d, "ezdxf": facts, "plenopath": {k: v for k, v in ours.items()
                                                                           if k != "json"}}
    mismatches, box_info = [], {}
    if ours["status"] == "imported":
        mismatches, box_info = compare(name, facts, ours)
        j = ours["json"]
        result["ours"] = {k: j.get(k) for k in ("units", "metres_per_unit", "units_source", "version", "binary",
                                                "codepage", "entities_read", "entities_skipped",
                                                "skipped_by_kind", "drawing_extents", "stray_entities")}
    result["mismatches"] = mismatches
    result["box_check"] = box_info
    status = ours["status"]
    if status in ("crash", "hang", "internal error", "bad json", "unnamed refusal"):
        result["verdict"] = "FAIL " + status
    elif status == "refused":
        result["verdict"] = "FAIL refused" if has_2d else "ok (refused, no 2-D geometry)"
    elif mismatches:
        result["verdict"] = "FAIL disagrees"
    else:
        result["verdict"] = "ok"
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("plenopath")
    ap.add_argument("corpus")
    ap.add_argument("--report", help="write every file's facts and verdict as JSON here")
    ap.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1))
    ap.add_argument("--only", nargs="*", help="check only these file names")
    args = ap.parse_args()
    files = sorted(f for f in os.listdir(args.corpus) if f.lower().endswith(".dxf"))
    if args.only:
        files = [f for f in files if f in set(args.only)]
    paths = [os.path.join(args.corpus, f) for f in files]
    t0 = time.time()
    results = {}
    # Largest first, so the slow files do not end the run on one core.
    order = sorted(paths, key=os.path.getsize, reverse=True)
    with concurrent.futures.ProcessPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = {pool.submit(check_file, args.plenopath, p): p for p in order}
        for fut in concurrent.futures.as_completed(futures):
            r = fut.result()
            results[r["file"]] = r
    rows = [results[f] for f in files]

    print(f"{'file':<68} {'2-D':>3} {'ezdxf':>8} {'ours':>15} {'ez s':>5} {'our s':>5}  verdict")
    for r in rows:
        print(f"{r['file'][:68]:<68} {'yes' if r['has_2d'] else 'no':>3} {r['ezdxf']['read']:>8} "
              f"{r['plenopath']['status']:>15} {r['ezdxf']['seconds']:5.1f} "
              f"{r['plenopath'].get('seconds', 0):5.1f}  {r['verdict']}")
        for m in r["mismatches"][:12]:
            print(f"    {m}")
        if len(r["mismatches"]) > 12:
            print(f"    ... and {len(r['mismatches']) - 12} more")
        if r["plenopath"]["status"] not in ("imported",) and r["plenopath"]["stderr"]:
            print(f"    stderr: {r['plenopath']['stderr'].splitlines()[-1][:150]}")
    with_2d = [r for r in rows if r["has_2d"]]
    imported_2d = [r for r in with_2d if r["plenopath"]["status"] == "imported"]
    broken = [r for r in rows if r["plenopath"]["status"] in ("crash", "hang", "internal error", "bad json",
                                                               "unnamed refusal")]
    disagree = [r for r in rows if r["mismatches"]]
    passed = sum(1 for r in rows if r["verdict"].startswith("ok"))
    failed = len(rows) - passed
    print(f"ezdxf finds 2-D model-space geometry in {len(with_2d)} of {len(rows)} files")
    print(f"dxf corpus: {len(imported_2d)} of {len(with_2d)} files with 2-D geometry import "
          f"({len(broken)} crash/hang/internal error/unnamed, {len(disagree)} disagree with ezdxf; "
          f"{time.time() - t0:.0f} s)")
    if args.report:
        with open(args.report, "w") as f:
            json.dump({"files": rows, "with_2d": [r["file"] for r in with_2d],
                       "imported_2d": [r["file"] for r in imported_2d]}, f, indent=1)
    needed = min(MIN_IMPORTED, len(with_2d))
    ok = len(imported_2d) >= needed and not broken and not disagree
    print(f"{passed} passed, {failed} failed")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
