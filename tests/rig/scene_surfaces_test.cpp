// Surfaces of the synthetic scene a real capture meets: plain painted walls (near uniform, few corners,
// against the default textured plaster), and walls passed at arm's length (a door frame 0.2 m away: every
// pixel's depth against the brute-force 3-D oracle).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "rig/plan_drawing.h"
#include "rig/spherical.h"
#include "rig/synthetic_camera.h"
#include "tests/rig/oracle_scene.h"

namespace plenopath {
namespace {

struct WallStats {
  double median_local_std = 0;  // grey levels, 5x5 windows wholly on one wall face
  double corner_share = 0;      // of those pixels, the share with a min-eigenvalue corner response above T
  int pixels = 0;
};

WallStats wall_stats(const SceneOptions& scene_options) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan(), scene_options);
  RenderOptions options;
  options.width = 512;
  options.height = 256;
  const PathFrame pose{0, "", 4.0, 7.5, 0.3, 1.0, kFrameOk, ""};  // the corridor
  const cv::Mat rgb = render_panorama(scene, pose, options).rgb;
  cv::Mat gray, mean, sq, eig;
  cv::cvtColor(rgb, gray, cv::COLOR_BGR2GRAY);
  gray.convertTo(gray, CV_32F);
  cv::blur(gray, mean, cv::Size(5, 5));
  cv::blur(gray.mul(gray), sq, cv::Size(5, 5));
  cv::cornerMinEigenVal(gray, eig, 5, 3);
  // Which pixels see a wall, and which wall: traced ray by ray, with the face told apart by its distance's
  // smoothness (a 5x5 window on one plane has depth within a few per cent of its centre).
  const cv::Mat depth = render_panorama(scene, pose, options).depth;
  const Eigen::Matrix3d r = world_from_camera_rotation(pose.heading);
  std::vector<double> stds;
  int corners = 0;
  for (int v = 72; v < 184; v += 2)
    for (int u = 2; u < options.width - 2; u += 2) {
      const Eigen::Vector3d d = r * equirect_to_bearing({u + 0.5, v + 0.5}, options.width, options.height);
      if (trace_ray(scene, {pose.x, pose.y, 1.6}, d, options).kind != SurfaceKind::kWall) continue;
      bool one_face = true;
      for (int dv = -2; dv <= 2 && one_face; ++dv)
        for (int du = -2; du <= 2 && one_face; ++du)
          one_face = std::abs(depth.at<float>(v + dv, u + du) / depth.at<float>(v, u) - 1.0f) < 0.05f;
      if (!one_face) continue;
      const float m = mean.at<float>(v, u);
      stds.push_back(std::sqrt(std::max(0.0f, sq.at<float>(v, u) - m * m)));
      corners += eig.at<float>(v, u) > 20.0f;
    }
  WallStats s;
  s.pixels = static_cast<int>(stds.size());
  if (stds.empty()) return s;
  std::nth_element(stds.begin(), stds.begin() + stds.size() / 2, stds.end());
  s.median_local_std = stds[stds.size() / 2];
  s.corner_share = double(corners) / stds.size();
  return s;
}

TEST(SceneSurfaces, PlainPaintedWallsAreNearUniform) {
  SceneOptions textured;
  SceneOptions painted;
  painted.wall_finish = WallFinish::kPlainPaint;
  painted.posters = false;
  const WallStats t = wall_stats(textured), p = wall_stats(painted);
  ASSERT_GT(t.pixels, 2000);
  ASSERT_GT(p.pixels, 2000);
  EXPECT_GT(t.median_local_std, 4.0);
  EXPECT_LT(p.median_local_std, 1.5);
  EXPECT_GT(p.median_local_std, 0.05);  // faint noise, not a flat fill
  EXPECT_LT(p.corner_share, 0.1 * t.corner_share);
  RecordProperty("textured_local_std", std::to_string(t.median_local_std));
  RecordProperty("painted_local_std", std::to_string(p.median_local_std));
}

// A 6 m x 4 m room split by a 10 cm thick wall with a 0.9 m doorway: jambs at y = +-0.45.
FloorPlan door_plan() {
  PlanDrawing d;
  d.layers = {{"WALLS", 7}};
  d.polylines.push_back({{{-3, -2}, {3, -2}, {3, 2}, {-3, 2}}, true, "WALLS"});
  d.polylines.push_back({{{-0.05, -2}, {-0.05, -0.45}, {0.05, -0.45}, {0.05, -2}}, false, "WALLS"});
  d.polylines.push_back({{{-0.05, 2}, {-0.05, 0.45}, {0.05, 0.45}, {0.05, 2}}, false, "WALLS"});
  return flatten_drawing(d);
}

TEST(SceneSurfaces, ADoorFramePassedAtArmsLengthHasExactDepth) {
  const FloorPlan plan = door_plan();
  const test::OracleScene oracle(plan);
  SceneOptions no_grid;
  no_grid.use_grid = false;
  const SyntheticScene scene = build_synthetic_scene(plan), brute = build_synthetic_scene(plan, no_grid);
  RenderOptions options;
  options.width = 256;
  options.height = 128;
  struct Case {
    double x, y, heading, pitch_deg;
  };
  // In the doorway 0.2 m from a jamb, 0.15 m beside the wall's face, 5 cm from it, and tilted.
  const Case cases[] = {{0.0, 0.25, 0.0, 0.0},
                        {0.0, -0.25, 1.2, 0.0},
                        {0.2, 0.6, -0.7, 0.0},
                        {0.1, 1.0, 2.0, 0.0},
                        {0.0, 0.25, 0.4, 1.5}};
  for (const Case& c : cases) {
    options.pitch_deg = c.pitch_deg;
    const PathFrame pose{0, "", c.x, c.y, c.heading, 1.0, kFrameOk, ""};
    const RenderedPanorama pano = render_panorama(scene, pose, options);
    EXPECT_EQ(cv::norm(pano.depth, render_panorama(brute, pose, options).depth, cv::NORM_INF), 0.0);
    const Eigen::Matrix3d r = (Eigen::AngleAxisd(c.heading, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(-c.pitch_deg * M_PI / 180, Eigen::Vector3d::UnitY()))
                                  .toRotationMatrix();
    int off = 0;
    double nearest = 1e9;
    for (int v = 0; v < options.height; ++v)
      for (int u = 0; u < options.width; ++u) {
        const Eigen::Vector3d d = r * equirect_to_bearing({u + 0.5, v + 0.5}, options.width, options.height);
        const double expected = oracle.intersect({c.x, c.y, 1.6}, d.normalized());
        const double got = pano.depth.at<float>(v, u);
        nearest = std::min(nearest, got);
        if (!(std::abs(got - expected) <= 1e-5 * std::max(1.0, expected))) ++off;
        const cv::Vec3b p = pano.rgb.at<cv::Vec3b>(v, u);
        ASSERT_FALSE(p[0] == 235 && p[1] == 206 && p[2] == 160) << "sky inside a closed room";
      }
    // Level: exact everywhere; tilted: but for faces narrower than a column's spacing.
    EXPECT_LE(off, c.pitch_deg == 0.0 ? 0 : options.width * options.height / 500)
        << "camera at " << c.x << "," << c.y;
    EXPECT_LT(nearest, 0.25);  // the near surface is in view
  }
}

}  // namespace
}  // namespace plenopath
