#pragma once
// The frame of the package's plan.svg: the plan's extents with a margin, drawn y-up, at a pixel size that
// maps (Photo Sphere Viewer's map plugin) read from the SVG's width and height.
#include <Eigen/Core>

#include "model/floor_plan.h"

namespace plenopath {

struct PlanSvgFrame {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Ones();  // plan metres
  double pixels_per_metre = 100.0;
  int width_px() const;
  int height_px() const;
  // Pixel (x right, y down from the top-left corner) of a plan point.
  Eigen::Vector2d pixel(const Eigen::Vector2d& plan) const;
};

// 100 px a metre, fewer when the larger side would pass 4096 px.
PlanSvgFrame plan_svg_frame(const FloorPlan& plan);

}  // namespace plenopath
