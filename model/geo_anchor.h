#pragma once
// Where the plan sits on Earth: plan (x, y) -> local east/north by scale, rotation and translation.
#include <Eigen/Core>

namespace plenopath {

struct GeoAnchor {
  bool valid = false;
  double latitude_deg = 0.0;  // WGS84 position of plan_origin
  double longitude_deg = 0.0;
  double altitude_m = 0.0;
  double plan_rotation = 0.0;  // radians, CCW angle from east to the plan's +X
  double scale = 1.0;          // metres on the ground per plan metre
  Eigen::Vector2d plan_origin = Eigen::Vector2d::Zero();

  // Local east/north (metres) of a plan point.
  Eigen::Vector2d enu_from_plan(const Eigen::Vector2d& plan) const;
  Eigen::Vector2d plan_from_enu(const Eigen::Vector2d& enu) const;
};
bool operator==(const GeoAnchor& l, const GeoAnchor& r);

}  // namespace plenopath
