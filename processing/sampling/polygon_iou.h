#pragma once
// Area of the intersection and intersection-over-union of two simple polygons (plan frame, metres), exact:
// CGAL's Boolean set operations on the exact kernel (polygon_iou_cgal.cpp). Plain types only here.
#include <Eigen/Core>
#include <vector>

namespace plenopath {

// Area (m^2) of a ∩ b. Either polygon may be given clockwise or counter-clockwise; consecutive duplicate
// vertices are dropped. A polygon with fewer than 3 distinct vertices has no area (result 0). A polygon
// that is not simple (self-touching after rounding to doubles) is measured on a fine grid instead
// (`exact` reports which way was taken).
double polygon_intersection_area(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                                 bool* exact = nullptr);

// |a ∩ b| / |a ∪ b| in [0, 1]; 1 when both are empty (nothing differs), 0 when exactly one is.
double polygon_iou(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                   bool* exact = nullptr);

// Signed area (shoelace): > 0 counter-clockwise.
double polygon_signed_area(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace plenopath
