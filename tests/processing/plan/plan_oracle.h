#pragma once
// Hand-built plans and the brute-force visibility oracle shared by the visibility and sampling tests and
// benchmarks: walls added one by one, and the area seen from a point measured by casting rays against every
// wall (no CGAL, no grid: independent of processing/visibility).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <vector>

#include "model/floor_plan.h"

namespace plenopath::test {

inline void add_wall(FloorPlan* plan, Eigen::Vector2d a, Eigen::Vector2d b) {
  PlanSegment s;
  s.a = a;
  s.b = b;
  s.layer = "WALLS";
  s.occluder = true;
  plan->segments.push_back(s);
}

// The closed polygon through `points`, as walls.
inline void add_polygon(FloorPlan* plan, const std::vector<Eigen::Vector2d>& points) {
  for (std::size_t i = 0; i < points.size(); ++i) add_wall(plan, points[i], points[(i + 1) % points.size()]);
}

// A w x h rectangle centred on c, turned by `angle` radians.
inline void add_rectangle(FloorPlan* plan, Eigen::Vector2d c, double w, double h, double angle) {
  const Eigen::Rotation2Dd r(angle);
  using V = Eigen::Vector2d;
  add_polygon(plan, {c + r * V(-w / 2, -h / 2), c + r * V(w / 2, -h / 2), c + r * V(w / 2, h / 2),
                     c + r * V(-w / 2, h / 2)});
}

// A wall of thickness t round the centre line a-b, extended by t/2 at both ends: a closed outline, as the
// POV-Ray scenes' plans and many architects' plans draw walls.
inline void add_thick_wall(FloorPlan* plan, Eigen::Vector2d a, Eigen::Vector2d b, double t) {
  const Eigen::Vector2d d = (b - a).normalized(), n(-d.y(), d.x());
  add_polygon(plan, {a - d * t / 2 - n * t / 2, b + d * t / 2 - n * t / 2, b + d * t / 2 + n * t / 2,
                     a - d * t / 2 + n * t / 2});
}

// Distance along the ray from p at `angle` (radians from +X) to the first wall, or infinity.
inline double cast_ray(const std::vector<PlanSegment>& walls, const Eigen::Vector2d& p, double angle) {
  const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
  double best = std::numeric_limits<double>::infinity();
  for (const auto& w : walls) {
    const Eigen::Vector2d a = w.a - p, e = w.b - w.a;
    const double denom = d.x() * e.y() - d.y() * e.x();
    if (std::abs(denom) < 1e-15) continue;
    const double t = (a.x() * e.y() - a.y() * e.x()) / denom;
    const double u = (a.x() * d.y() - a.y() * d.x()) / denom;
    if (t > 0 && u >= 0 && u <= 1) best = std::min(best, t);
  }
  return best;
}

// Area seen from p: the fan of `rays` ray hits.
inline double ray_cast_area(const std::vector<PlanSegment>& walls, const Eigen::Vector2d& p, int rays) {
  double area = 0.0;
  const double first = cast_ray(walls, p, 0.0);
  double prev = first;
  for (int k = 1; k <= rays; ++k) {
    const double r = k == rays ? first : cast_ray(walls, p, 2 * M_PI * k / rays);
    area += 0.5 * prev * r * std::sin(2 * M_PI / rays);
    prev = r;
  }
  return area;
}

}  // namespace plenopath::test
