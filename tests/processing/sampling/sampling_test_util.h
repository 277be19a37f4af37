#pragma once
// Small plans and paths shared by the sampling tests.
#include <Eigen/Core>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "tests/processing/plan/plan_oracle.h"

namespace plenopath::sampling_test {

using test::add_wall;

// A path along +X from (x0, y): frame i at x0 + i * step, heading 0.
inline CameraPath straight_path(int n, double step, double x0 = 0.0, double y = 0.0) {
  CameraPath path;
  for (int i = 0; i < n; ++i) path.frames.push_back({i, "", x0 + i * step, y, 0.0, 1.0, kFrameOk, ""});
  return path;
}

// Three rooms in a row, 6 m x 4 m each (x in [0, 18], y in [0, 4]), joined by 1 m doors at y in [1.5, 2.5],
// with a square pillar in the middle room; the path runs along y = 2 from x = 0.5 to 17.5.
inline FloorPlan three_rooms() {
  FloorPlan plan;
  PlanLayer layer;
  layer.name = "WALLS";
  layer.occluder = true;
  plan.layers.push_back(layer);
  add_wall(&plan, {0, 0}, {18, 0});
  add_wall(&plan, {18, 0}, {18, 4});
  add_wall(&plan, {18, 4}, {0, 4});
  add_wall(&plan, {0, 4}, {0, 0});
  for (double x : {6.0, 12.0}) {
    add_wall(&plan, {x, 0}, {x, 1.5});
    add_wall(&plan, {x, 2.5}, {x, 4});
  }
  const Eigen::Vector2d c(9.0, 3.0);
  const double h = 0.3;
  add_wall(&plan, c + Eigen::Vector2d(-h, -h), c + Eigen::Vector2d(h, -h));
  add_wall(&plan, c + Eigen::Vector2d(h, -h), c + Eigen::Vector2d(h, h));
  add_wall(&plan, c + Eigen::Vector2d(h, h), c + Eigen::Vector2d(-h, h));
  add_wall(&plan, c + Eigen::Vector2d(-h, h), c + Eigen::Vector2d(-h, -h));
  return plan;
}

inline CameraPath three_rooms_path() { return straight_path(341, 0.05, 0.5, 2.0); }  // 17 m

}  // namespace plenopath::sampling_test
