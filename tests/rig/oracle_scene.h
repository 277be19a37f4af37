#pragma once
// The synthetic camera's scene as a test understands it from the plan alone, intersected by brute force in
// 3-D (an independent truth for the renderer's depth): occluding segments are full-height walls, closed
// FURNITURE outlines are boxes, floor and ceiling cover the extents grown by 1 m.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "model/floor_plan.h"

namespace plenopath::test {

inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

inline bool inside_polygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  // Winding number (a different test from the renderer's crossing parity).
  int winding = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[(i + 1) % poly.size()];
    const double side = cross2(b - a, p - a);
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && side > 0) ++winding;
    } else if (b.y() <= p.y() && side < 0) {
      --winding;
    }
  }
  return winding != 0;
}

struct OracleScene {
  struct Face {
    Eigen::Vector2d a, b;
    double top;
  };
  std::vector<Face> faces;
  std::vector<std::pair<std::vector<Eigen::Vector2d>, double>> tops;
  Eigen::Vector2d lo, hi;
  double ceiling = 2.8;

  explicit OracleScene(const FloorPlan& plan, double furniture_height = 0.75, double wall_height = 2.8)
      : ceiling(wall_height) {
    for (const auto& s : plan.segments)
      if (s.occluder) faces.push_back({s.a, s.b, ceiling});
    for (const auto& o : plan.outlines)
      if (o.closed && o.layer == "FURNITURE") {
        for (std::size_t i = 0; i < o.points.size(); ++i)
          faces.push_back({o.points[i], o.points[(i + 1) % o.points.size()], furniture_height});
        tops.push_back({o.points, furniture_height});
      }
    lo = hi = faces[0].a;
    for (const auto& f : faces) {
      lo = lo.cwiseMin(f.a).cwiseMin(f.b);
      hi = hi.cwiseMax(f.a).cwiseMax(f.b);
    }
    lo -= Eigen::Vector2d(1, 1);
    hi += Eigen::Vector2d(1, 1);
  }

  // Distance along the unit ray to the nearest surface, 0 if none.
  double intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
    double best = std::numeric_limits<double>::infinity();
    auto in_rect = [&](const Eigen::Vector3d& p) {
      return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
    };
    for (double plane : {0.0, ceiling}) {
      if (d.z() == 0) continue;
      const double t = (plane - o.z()) / d.z();
      if (t > 0 && in_rect(o + t * d)) best = std::min(best, t);
    }
    for (const auto& [poly, z] : tops) {
      if (d.z() == 0) continue;
      const double t = (z - o.z()) / d.z();
      const Eigen::Vector3d p = o + t * d;
      if (t > 0 && inside_polygon(poly, p.head<2>())) best = std::min(best, t);
    }
    for (const auto& f : faces) {
      // Plane through the segment, vertical: n . (p - a) = 0 with n horizontal.
      const Eigen::Vector2d e = f.b - f.a;
      const Eigen::Vector3d n(-e.y(), e.x(), 0.0);
      const double denom = n.dot(d);
      if (denom == 0) continue;
      const double t = n.dot(Eigen::Vector3d(f.a.x(), f.a.y(), 0.0) - o) / denom;
      if (!(t > 0)) continue;
      const Eigen::Vector3d p = o + t * d;
      const double along = (p.head<2>() - f.a).dot(e) / e.squaredNorm();
      if (along >= 0 && along <= 1 && p.z() >= 0 && p.z() <= f.top) best = std::min(best, t);
    }
    return std::isfinite(best) ? best : 0.0;
  }
};

}  // namespace plenopath::test
