#include "processing/plan/dxf_curves.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace plenopath {
namespace {

constexpr int kMaxArcPieces = 4096;
constexpr std::size_t kMaxSplinePoints = 200000;

// Pieces for a circular arc of radius r and |sweep| so that no chord is further than tolerance from it.
int arc_pieces(double r, double sweep, double tolerance) {
  int pieces = 1;
  if (r > tolerance) {
    const double step = 2.0 * std::acos(std::clamp(1.0 - tolerance / r, -1.0, 1.0));
    pieces = static_cast<int>(std::ceil(std::abs(sweep) / std::max(step, 1e-9)));
  }
  return std::clamp(pieces, std::abs(sweep) > 1e-12 ? 2 : 1, kMaxArcPieces);
}

// Points of the arc (centre c, radius r, from angle a0 by sweep), without its first point.
void append_arc(const Eigen::Vector3d& c, double r, double a0, double sweep, double tolerance,
                std::vector<Eigen::Vector3d>* out) {
  r = std::abs(r);
  const int pieces = arc_pieces(r, sweep, tolerance);
  for (int k = 1; k <= pieces; ++k) {
    const double a = a0 + sweep * k / pieces;
    out->push_back(c + r * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0));
  }
}

// Points of the bulged span p -> q (bulge = tan(included angle / 4), positive = CCW), without p.
void append_bulge(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double bulge, double tolerance,
                  std::vector<Eigen::Vector3d>* out, int* arcs) {
  const Eigen::Vector2d p2 = p.head<2>(), q2 = q.head<2>();
  const double chord = (q2 - p2).norm();
  if (std::abs(bulge) < 1e-9 || chord <= 0.0 || !std::isfinite(bulge)) {
    out->push_back(q);
    return;
  }
  bulge = std::clamp(bulge, -1e6, 1e6);
  const double sweep = 4.0 * std::atan(bulge);
  const double radius = chord / (2.0 * std::sin(std::abs(sweep) / 2.0));
  const Eigen::Vector2d dir = (q2 - p2) / chord;
  const Eigen::Vector2d left(-dir.y(), dir.x());
  // From the chord's midpoint to the centre: to the left for a CCW arc under a half turn.
  const double h = radius * std::cos(std::abs(sweep) / 2.0);
  const Eigen::Vector2d centre = 0.5 * (p2 + q2) + (sweep > 0 ? 1.0 : -1.0) * h * left;
  const double a0 = std::atan2(p2.y() - centre.y(), p2.x() - centre.x());
  append_arc({centre.x(), centre.y(), p.z()}, radius, a0, sweep, tolerance, out);
  out->back() = q;  // exact end
  ++*arcs;
}

// A non-uniform rational B-spline by de Boor's algorithm (homogeneous control points).
Eigen::Vector3d eval_spline(const std::vector<Eigen::Vector4d>& control, const std::vector<double>& knots,
                            int degree, double t) {
  const int n = static_cast<int>(control.size());
  const auto span = std::upper_bound(knots.begin() + degree + 1, knots.begin() + n, t);
  const int k = static_cast<int>(span - knots.begin()) - 1;
  Eigen::Vector4d d[16];
  for (int j = 0; j <= degree; ++j) d[j] = control[k - degree + j];
  for (int r = 1; r <= degree; ++r)
    for (int j = degree; j >= r; --j) {
      const int i = k - degree + j;
      const double denom = knots[i + degree + 1 - r] - knots[i];
      const double alpha = denom > 0.0 ? (t - knots[i]) / denom : 0.0;
      d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j];
    }
  const double w = std::abs(d[degree].w()) > 1e-300 ? d[degree].w() : 1.0;
  return d[degree].head<3>() / w;
}

double distance_to_chord(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return (p - a).norm();
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

void refine_spline(const DxfCurve& c, const std::vector<double>& knots, double ta, const Eigen::Vector3d& pa,
                   double tb, const Eigen::Vector3d& pb, int depth, double tolerance,
                   std::vector<Eigen::Vector3d>* out) {
  const double tm = 0.5 * (ta + tb);
  const Eigen::Vector3d pm = eval_spline(c.control, knots, c.degree, tm);
  if (depth < 12 && out->size() < kMaxSplinePoints && distance_to_chord(pm, pa, pb) > tolerance) {
    refine_spline(c, knots, ta, pa, tm, pm, depth + 1, tolerance, out);
    refine_spline(c, knots, tm, pm, tb, pb, depth + 1, tolerance, out);
  } else {
    out->push_back(pb);
  }
}

std::vector<Eigen::Vector3d> spline_points(const DxfCurve& c, double tolerance) {
  std::vector<Eigen::Vector3d> pts;
  const int n = static_cast<int>(c.control.size());
  const int degree = c.degree;
  if (degree < 1 || degree > 15 || n <= degree) {
    for (const auto& p : c.control) pts.push_back(p.head<3>() / (std::abs(p.w()) > 1e-300 ? p.w() : 1.0));
    return pts;
  }
  std::vector<double> knots = c.knots;
  bool ok = static_cast<int>(knots.size()) == n + degree + 1;
  for (std::size_t i = 1; ok && i < knots.size(); ++i)
    ok = std::isfinite(knots[i]) && knots[i] >= knots[i - 1];
  if (!ok) {  // missing or inconsistent knots: a clamped uniform vector
    knots.clear();
    for (int i = 0; i < n + degree + 1; ++i)
      knots.push_back(std::clamp(static_cast<double>(i - degree), 0.0, static_cast<double>(n - degree)));
  }
  const double t0 = knots[degree], t1 = knots[n];
  if (!(t1 > t0)) {
    for (const auto& p : c.control) pts.push_back(p.head<3>() / (std::abs(p.w()) > 1e-300 ? p.w() : 1.0));
    return pts;
  }
  pts.push_back(eval_spline(c.control, knots, degree, t0));
  const int initial = std::clamp(n * 4, 8, 20000);
  double prev_t = t0;
  for (int k = 1; k <= initial; ++k) {
    const double t = k == initial ? t1 - 1e-12 * (t1 - t0) : t0 + (t1 - t0) * k / initial;
    const Eigen::Vector3d prev = pts.back();
    refine_spline(c, knots, prev_t, prev, t, eval_spline(c.control, knots, degree, t), 0, tolerance, &pts);
    prev_t = t;
  }
  return pts;
}

// The outline of a wide centreline: each chord k (from c[k] to c[k + 1]) has its own half widths at its
// start and end (spans[k]), so its two edges are lines offset by those widths; at a vertex the edges of
// the chords before and after meet where their lines cross (a full mitre, as CAD programs draw wide
// polylines: a sharp corner makes a long spike).
// Where an arc (a bulged span) meets another span, the two are not mitred but butt-joined (both edge
// ends kept), as AutoCAD and ezdxf draw them: `mitre[i]` says which vertices are mitred.
std::vector<Eigen::Vector2d> wide_outline(const std::vector<Eigen::Vector2d>& c,
                                          const std::vector<Eigen::Vector2d>& spans,
                                          const std::vector<bool>& mitre, bool closed) {
  const std::size_t n = c.size();
  const std::size_t chords = closed ? n : n - 1;
  struct Edge {
    Eigen::Vector2d a, b;
  };
  std::vector<Edge> left(chords), right(chords);
  for (std::size_t k = 0; k < chords; ++k) {
    const Eigen::Vector2d p = c[k], q = c[(k + 1) % n];
    const Eigen::Vector2d d = q - p;
    const double len = d.norm();
    const Eigen::Vector2d nrm =
        len > 0.0 ? Eigen::Vector2d(-d.y() / len, d.x() / len) : Eigen::Vector2d(0, 0);
    left[k] = {p + spans[k].x() * nrm, q + spans[k].y() * nrm};
    right[k] = {p - spans[k].x() * nrm, q - spans[k].y() * nrm};
  }
  // Where the edge lines of two chords cross; `fallback` (the next chord's edge start) when they are
  // within 1.8 degrees of parallel, where the crossing would run off along a gently tapering wall.
  auto meet = [](const Edge& e, const Edge& f, const Eigen::Vector2d& fallback) {
    const Eigen::Vector2d r = e.b - e.a, s = f.b - f.a;
    const double cross = r.x() * s.y() - r.y() * s.x();
    const double angle = std::atan2(std::abs(cross), std::abs(r.dot(s)));  // between the lines, 0..pi/2
    if (!(r.norm() > 0.0) || !(s.norm() > 0.0) || angle < 0.031415) return fallback;
    const Eigen::Vector2d w = f.a - e.a;
    const double t = (w.x() * s.y() - w.y() * s.x()) / cross;
    return Eigen::Vector2d(e.a + t * r);
  };
  std::vector<Eigen::Vector2d> l, r;
  for (std::size_t i = 0; i < n; ++i) {
    const bool has_prev = closed || i > 0, has_next = closed || i < chords;
    const std::size_t prev = (i + chords - 1) % chords, next = i % chords;
    if (has_prev && has_next && mitre[i]) {
      l.push_back(meet(left[prev], left[next], left[next].a));
      r.push_back(meet(right[prev], right[next], right[next].a));
    } else if (has_prev && has_next) {
      l.push_back(left[prev].b);
      l.push_back(left[next].a);
      r.push_back(right[prev].b);
      r.push_back(right[next].a);
    } else if (has_next) {
      l.push_back(left[next].a);
      r.push_back(right[next].a);
    } else {
      l.push_back(left[prev].b);
      r.push_back(right[prev].b);
    }
  }
  std::vector<Eigen::Vector2d> out = l;
  out.insert(out.end(), r.rbegin(), r.rend());
  return out;
}

double max_stretch(const Eigen::Affine3d& t) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(t.linear());
  const double s = svd.singularValues()(0);
  return std::isfinite(s) && s > 0.0 ? s : 1.0;
}

}  // namespace

Eigen::Affine3d world_from_ocs(const Eigen::Vector3d& normal) {
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  const double len = normal.norm();
  if (!(len > 0.0) || !std::isfinite(len)) return t;
  const Eigen::Vector3d nz = normal / len;
  if (std::abs(nz.x()) < 1e-12 && std::abs(nz.y()) < 1e-12 && nz.z() > 0.0) return t;
  const Eigen::Vector3d ax =
      (std::abs(nz.x()) < 1.0 / 64.0 && std::abs(nz.y()) < 1.0 / 64.0 ? Eigen::Vector3d::UnitY().cross(nz)
                                                                      : Eigen::Vector3d::UnitZ().cross(nz))
          .normalized();
  const Eigen::Vector3d ay = nz.cross(ax).normalized();
  t.linear().col(0) = ax;
  t.linear().col(1) = ay;
  t.linear().col(2) = nz;
  return t;
}

std::vector<Eigen::Vector2d> tessellate(const DxfCurve& curve, const Eigen::Affine3d& world_from_curve,
                                        double tolerance, bool* closed, int* arcs) {
  const double local_tolerance = tolerance / max_stretch(world_from_curve);
  std::vector<Eigen::Vector3d> pts;
  std::vector<Eigen::Vector2d> chord_widths;  // half widths (start, end) per chord, for wide polylines
  std::vector<int> chord_span;                // the polyline span each chord belongs to
  std::vector<bool> chord_curved;             // from a bulged span
  bool is_closed = curve.closed;
  switch (curve.kind) {
    case DxfCurve::Kind::polyline: {
      const auto& v = curve.points;
      if (v.empty()) break;
      const bool wide = !curve.widths.empty();
      pts.push_back(v[0]);
      const std::size_t n = v.size();
      const std::size_t spans = is_closed ? n : n - 1;
      for (std::size_t i = 0; i < spans; ++i) {
        const std::size_t before = pts.size();
        append_bulge(v[i], v[(i + 1) % n], i < curve.bulges.size() ? curve.bulges[i] : 0.0, local_tolerance,
                     &pts, arcs);
        if (wide) {
          const Eigen::Vector2d w = i < curve.widths.size() ? curve.widths[i] : Eigen::Vector2d::Zero();
          const double added = static_cast<double>(pts.size() - before);
          const bool curved = std::abs(i < curve.bulges.size() ? curve.bulges[i] : 0.0) >= 1e-9;
          for (std::size_t k = 0; k < pts.size() - before; ++k) {
            chord_widths.emplace_back(0.5 * (w.x() + (w.y() - w.x()) * k / added),
                                      0.5 * (w.x() + (w.y() - w.x()) * (k + 1) / added));
            chord_span.push_back(static_cast<int>(i));
            chord_curved.push_back(curved);
          }
        }
      }
      if (is_closed && pts.size() > 1) pts.pop_back();  // the closing point repeats the first
      if (wide && pts.size() >= 2 &&
          std::any_of(chord_widths.begin(), chord_widths.end(),
                      [](const Eigen::Vector2d& w) { return w.x() > 0.0 || w.y() > 0.0; })) {
        // The outline of the wide line, in the curve's plane, then mapped.
        std::vector<Eigen::Vector2d> centre;
        for (const auto& p : pts) centre.push_back(p.head<2>());
        const double z = pts[0].z();
        // Vertex k joins chord k - 1 and chord k: a mitre within one span or between two straight spans.
        const std::size_t chords = chord_widths.size();
        std::vector<bool> mitre(centre.size(), true);
        for (std::size_t k = 0; k < centre.size(); ++k) {
          if (!is_closed && (k == 0 || k >= chords)) continue;
          const std::size_t prev = (k + chords - 1) % chords, next = k % chords;
          mitre[k] = chord_span[prev] == chord_span[next] || (!chord_curved[prev] && !chord_curved[next]);
        }
        const std::vector<Eigen::Vector2d> outline = wide_outline(centre, chord_widths, mitre, is_closed);
        std::vector<Eigen::Vector2d> out;
        for (const auto& p : outline)
          out.push_back((world_from_curve * Eigen::Vector3d(p.x(), p.y(), z)).head<2>());
        *closed = true;
        return out;
      }
      break;
    }
    case DxfCurve::Kind::arc: {
      const double r = std::abs(curve.radius);
      const bool full = std::abs(curve.sweep) >= 2.0 * M_PI - 1e-12;
      pts.push_back(curve.centre + r * Eigen::Vector3d(std::cos(curve.start), std::sin(curve.start), 0.0));
      append_arc(curve.centre, r, curve.start, curve.sweep, local_tolerance, &pts);
      if (full) {
        pts.pop_back();
        is_closed = true;
      }
      ++*arcs;
      break;
    }
    case DxfCurve::Kind::ellipse: {
      const double a = std::max(curve.major.norm(), curve.minor.norm());
      // |p''| <= a, so a parameter step dt keeps the chord within a dt^2 / 8 of the curve.
      const double dt = std::sqrt(8.0 * local_tolerance / std::max(a, 1e-300));
      int pieces = static_cast<int>(std::ceil(std::abs(curve.sweep) / std::max(dt, 1e-9)));
      pieces = std::clamp(pieces, 4, kMaxArcPieces);
      for (int k = 0; k <= pieces; ++k) {
        const double t = curve.start + curve.sweep * k / pieces;
        pts.push_back(curve.centre + std::cos(t) * curve.major + std::sin(t) * curve.minor);
      }
      if (std::abs(curve.sweep) >= 2.0 * M_PI - 1e-9) {
        pts.pop_back();
        is_closed = true;
      }
      ++*arcs;
      break;
    }
    case DxfCurve::Kind::path: {
      for (const DxfCurve& piece : curve.pieces) {
        bool piece_closed = false;
        const auto piece_points =
            tessellate(piece, Eigen::Affine3d::Identity(), local_tolerance, &piece_closed, arcs);
        const double z = piece.kind == DxfCurve::Kind::polyline && !piece.points.empty() ? piece.points[0].z()
                                                                                         : piece.centre.z();
        for (const auto& p : piece_points) {
          const Eigen::Vector3d q(p.x(), p.y(), z);
          if (pts.empty() || (pts.back() - q).norm() > 1e-12 * (1.0 + q.norm())) pts.push_back(q);
        }
      }
      if (pts.size() > 2 && (pts.front() - pts.back()).norm() <= local_tolerance) pts.pop_back();
      is_closed = true;
      break;
    }
    case DxfCurve::Kind::spline: {
      pts = spline_points(curve, local_tolerance);
      if (is_closed && pts.size() > 2 && (pts.front() - pts.back()).norm() <= local_tolerance) pts.pop_back();
      ++*arcs;
      break;
    }
  }
  *closed = is_closed;
  std::vector<Eigen::Vector2d> out;
  out.reserve(pts.size());
  for (const auto& p : pts) out.push_back((world_from_curve * p).head<2>());
  return out;
}

}  // namespace plenopath
