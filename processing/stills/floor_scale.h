#pragma once
// Metric scale of still panoramas from the tripod's height (issue 20): the camera stands at a known height
// h above the floor, so points seen steeply downwards lie mostly on the floor, at z = -h in metres. Their
// depth below the camera in the solution's units gives metres per unit: h / depth. The floor is the most
// common level among the steep points (furniture tops and the tripod's own legs are less common); the
// depth is the median of the points within 4 % of that mode.
#include <Eigen/Core>
#include <vector>

namespace plenopath {

struct FloorLevel {
  double depth = 0.0;  // the floor's depth below the cameras, in the points' units; 0 when not found
  int points = 0;      // steep points at that level
};

// depths: -z of points seen at least min_steepness below the horizon (positive values). Needs at least
// min_points of them at the floor level; otherwise depth 0.
FloorLevel floor_level(const std::vector<double>& depths, int min_points);

// The steepness that makes a point a floor candidate: seen this far below the horizon.
constexpr double kFloorSteepnessDeg = 25.0;

// One pair of stills: A at the origin, B at unit distance along `direction` with heading `turn` (radians,
// planar_two_point.h's conventions), and the pair's verified correspondences. Triangulates them (rays at
// least min_parallax_deg apart, in front of both), keeps those seen steeply downwards from both, and
// returns the metric baseline camera_height_m / floor depth, or 0 when fewer than min_points are on the
// floor level. floor_points (when not null) gets the count used.
double baseline_from_floor(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                           double turn, double direction, double camera_height_m, int min_points,
                           double min_parallax_deg = 2.0, int* floor_points = nullptr);

}  // namespace plenopath
