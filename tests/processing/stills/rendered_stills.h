#pragma once
// Test helpers for the stills tests: stills rendered by the studio's renderer at known poses, the frames
// at those poses, and heading errors. The truth of these tests is the pose each still was rendered at.
#include <Eigen/Core>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "rig/synthetic_camera.h"

namespace plenopath::test {

// A frame of capture index `index` at `pose` (x, y, heading in radians).
inline PathFrame frame_at(int index, const Eigen::Vector3d& pose) {
  PathFrame f;
  f.index = index;
  f.x = pose.x();
  f.y = pose.y();
  f.heading = pose.z();
  return f;
}

// One colour panorama per pose, 1440 x 720, of the plan's synthetic scene.
inline std::vector<cv::Mat> render_stills_at(const FloorPlan& plan,
                                             const std::vector<Eigen::Vector3d>& poses) {
  const SyntheticScene world = build_synthetic_scene(plan, SceneOptions{});
  RenderOptions render;
  render.width = 1440;
  render.height = 720;
  render.depth = false;
  std::vector<cv::Mat> stills;
  for (std::size_t i = 0; i < poses.size(); ++i)
    stills.push_back(render_panorama(world, frame_at(static_cast<int>(i), poses[i]), render).rgb);
  return stills;
}

// The angle between two headings (radians), in degrees.
inline double heading_error_deg(double a, double b) {
  return std::abs(std::remainder(a - b, 2 * M_PI)) * 180 / M_PI;
}

}  // namespace plenopath::test
