// The CGAL half of polygon_iou.h: exact Boolean intersection of two simple polygons (Epeck). Polygons that
// rounding to doubles made non-simple are measured on a grid instead (even-odd rule), so the caller always
// gets an answer.
#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_with_holes_2.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <list>

#include "processing/sampling/polygon_iou.h"

namespace plenopath {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Polygon = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<Kernel>;

// Consecutive duplicates (and a closing copy of the first vertex) removed.
std::vector<Eigen::Vector2d> distinct_vertices(const std::vector<Eigen::Vector2d>& polygon) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : polygon)
    if (out.empty() || p != out.back()) out.push_back(p);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

bool inside_even_odd(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& q) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

// Fallback for polygons CGAL cannot take: cell-centre sampling over the common bounding box.
double grid_intersection_area(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b) {
  Eigen::Vector2d lo = a[0], hi = a[0];
  for (const auto& p : a) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  Eigen::Vector2d lo_b = b[0], hi_b = b[0];
  for (const auto& p : b) lo_b = lo_b.cwiseMin(p), hi_b = hi_b.cwiseMax(p);
  lo = lo.cwiseMax(lo_b);
  hi = hi.cwiseMin(hi_b);
  if (!(hi.x() > lo.x() && hi.y() > lo.y())) return 0.0;
  constexpr int kCells = 512;
  const double dx = (hi.x() - lo.x()) / kCells, dy = (hi.y() - lo.y()) / kCells;
  long hits = 0;
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const Eigen::Vector2d q(lo.x() + (i + 0.5) * dx, lo.y() + (j + 0.5) * dy);
      if (inside_even_odd(a, q) && inside_even_odd(b, q)) ++hits;
    }
  return hits * dx * dy;
}

Polygon to_cgal(const std::vector<Eigen::Vector2d>& points) {
  Polygon polygon;
  for (const auto& p : points) polygon.push_back(Kernel::Point_2(p.x(), p.y()));
  if (polygon.is_simple() && polygon.orientation() == CGAL::CLOCKWISE) polygon.reverse_orientation();
  return polygon;
}

}  // namespace

double polygon_signed_area(const std::vector<Eigen::Vector2d>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const auto& a = polygon[i];
    const auto& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

double polygon_intersection_area(const std::vector<Eigen::Vector2d>& a_in,
                                 const std::vector<Eigen::Vector2d>& b_in, bool* exact) {
  if (exact) *exact = true;
  const auto a = distinct_vertices(a_in);
  const auto b = distinct_vertices(b_in);
  if (a.size() < 3 || b.size() < 3) return 0.0;
  const Polygon pa = to_cgal(a), pb = to_cgal(b);
  if (!pa.is_simple() || !pb.is_simple()) {
    if (exact) *exact = false;
    return grid_intersection_area(a, b);
  }
  std::list<PolygonWithHoles> pieces;
  CGAL::intersection(pa, pb, std::back_inserter(pieces));
  Kernel::FT area = 0;
  for (const auto& piece : pieces) {
    area += CGAL::abs(piece.outer_boundary().area());
    for (auto hole = piece.holes_begin(); hole != piece.holes_end(); ++hole) area -= CGAL::abs(hole->area());
  }
  return CGAL::to_double(area);
}

double polygon_iou(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                   bool* exact) {
  const double area_a = std::abs(polygon_signed_area(distinct_vertices(a)));
  const double area_b = std::abs(polygon_signed_area(distinct_vertices(b)));
  if (exact) *exact = true;
  if (area_a <= 0.0 && area_b <= 0.0) return 1.0;
  if (area_a <= 0.0 || area_b <= 0.0) return 0.0;
  const double common = polygon_intersection_area(a, b, exact);
  const double united = area_a + area_b - common;
  return united > 0.0 ? std::clamp(common / united, 0.0, 1.0) : 0.0;
}

}  // namespace plenopath
