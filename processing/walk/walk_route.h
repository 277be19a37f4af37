#pragma once
// The walkable line between two spots of the plan (issue 20): the player walks from one still to the next
// along it, through the door rather than through the wall. The free space is a raster of the plan (walls
// drawn as blocked cells); the route is the cheapest 8-connected path through it, cells near a wall
// costing more (so it keeps to the middle of a door), pulled taut where the plan's walls allow a straight
// line.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "model/floor_plan.h"

namespace plenopath {

// Whether the straight line a-b crosses one of `walls` (touching a wall's end counts; running along one
// does not).
bool crosses_any_wall(const std::vector<PlanSegment>& walls, const Eigen::Vector2d& a,
                      const Eigen::Vector2d& b);

struct WalkRouteOptions {
  double cell_m = 0.05;      // raster resolution
  double clearance_m = 0.3;  // cells nearer a wall than this cost more, the more the nearer
  double wall_cost = 8.0;    // extra cost a cell next to a wall adds per step
  double margin_m = 1.0;     // the raster reaches this far beyond the plan and the spots
  void check() const;        // throws Error naming the bad field
};

class WalkRouter {
 public:
  WalkRouter(const FloorPlan& plan, const WalkRouteOptions& options = {});
  // The route from a to b, a and b included; just {a, b} when the straight line crosses no wall. Empty when
  // no route joins them (a spot outside the plan's raster, or walled in).
  std::vector<Eigen::Vector2d> route(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  // Whether the straight line a-b crosses a sight-blocking segment of the plan.
  bool crosses_wall(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

 private:
  cv::Point cell_of(const Eigen::Vector2d& p) const;
  Eigen::Vector2d centre_of(const cv::Point& c) const;

  WalkRouteOptions options_;
  std::vector<PlanSegment> walls_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  cv::Mat blocked_;   // CV_8U, 255 on walls
  cv::Mat distance_;  // CV_32F, metres to the nearest wall cell
};

}  // namespace plenopath
