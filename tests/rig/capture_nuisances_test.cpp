// The capture nuisances of the synthetic camera against independent truth: a tilted camera's depth against a
// brute-force 3-D intersection along rays rotated by Eigen's own AngleAxis; where the horizon lies in the
// depth image (a vertical wall is nearest along a column at the world horizon) for a known pitch and roll;
// the wobble's and the exposure steps' statistics, and a render's brightness against the gain ratio; a camera
// riding up and down against the same brute-force intersection from the raised or lowered centre.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "model/error.h"
#include "rig/plan_drawing.h"
#include "rig/spherical.h"
#include "rig/synthetic_camera.h"
#include "tests/rig/oracle_scene.h"

namespace plenopath {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Matrix3d independent_rotation(double heading, double pitch, double roll) {
  return (Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// An 8 m x 6 m room, walls at x = +-4 and y = +-3.
FloorPlan box_room() {
  PlanDrawing d;
  d.layers = {{"WALLS", 7}};
  d.polylines.push_back({{{-4, -3}, {4, -3}, {4, 3}, {-4, 3}}, true, "WALLS"});
  return flatten_drawing(d);
}

TEST(CaptureNuisances, TiltedDepthMatchesIndependentIntersection) {
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan);
  const test::OracleScene oracle(plan);
  RenderOptions options;
  options.width = 256;
  options.height = 128;
  options.pitch_deg = 1.7;
  options.roll_deg = -2.3;
  std::mt19937 rng(777);
  const PathFrame poses[] = {
      {0, "", 4.0, 7.5, 0.3, 1.0, kFrameOk, ""},     // corridor
      {1, "", 11.0, 10.0, -2.0, 1.0, kFrameOk, ""},  // meeting room, table in view
      {2, "", 12.6, 2.6, 3.1, 1.0, kFrameOk, ""},    // lobby between round pillars
  };
  int checked = 0, off = 0;
  for (const PathFrame& pose : poses) {
    const RenderedPanorama pano = render_panorama(scene, pose, options);
    const Eigen::Vector3d origin(pose.x, pose.y, 1.6);
    const Eigen::Matrix3d r = independent_rotation(pose.heading, 1.7 * kDeg, -2.3 * kDeg);
    for (int k = 0; k < 3000; ++k) {
      const int u = std::uniform_int_distribution<int>(0, options.width - 1)(rng);
      const int v = std::uniform_int_distribution<int>(0, options.height - 1)(rng);
      const Eigen::Vector3d d = r * equirect_to_bearing({u + 0.5, v + 0.5}, options.width, options.height);
      const double expected = oracle.intersect(origin, d.normalized());
      const double got = pano.depth.at<float>(v, u);
      ++checked;
      // Exact but for faces narrower than a column's spacing that neither neighbouring column met.
      if (std::abs(got - expected) > 1e-5 * std::max(1.0, expected)) ++off;
    }
  }
  EXPECT_EQ(checked, 9000);
  EXPECT_LE(off, checked / 500) << off << " of " << checked << " pixels off";
  // The same render without tilt is not the tilted one (the options do act).
  RenderOptions level = options;
  level.pitch_deg = level.roll_deg = 0;
  EXPECT_GT(cv::norm(render_panorama(scene, poses[0], level).depth,
                     render_panorama(scene, poses[0], options).depth, cv::NORM_INF),
            0.01);
}

// Sub-row position of the depth minimum along column u within 7 deg of the middle row, where every column
// sees a wall (parabola through the three samples around the smallest).
double depth_minimum_row(const cv::Mat& depth, int u) {
  const int reach = depth.rows * 7 / 180;
  int best = depth.rows / 2;
  for (int v = depth.rows / 2 - reach; v < depth.rows / 2 + reach; ++v)
    if (depth.at<float>(v, u) < depth.at<float>(best, u)) best = v;
  const double a = depth.at<float>(best - 1, u), b = depth.at<float>(best, u),
               c = depth.at<float>(best + 1, u);
  return best + 0.5 * (a - c) / (a - 2 * b + c);
}

TEST(CaptureNuisances, HorizonRowMovesByTheKnownPitchAndRoll) {
  const SyntheticScene scene = build_synthetic_scene(box_room());
  RenderOptions options;
  options.width = 1024;
  options.height = 512;
  const PathFrame pose{0, "", 0.0, 0.0, 0.0, 1.0, kFrameOk, ""};
  const int front = options.width / 2, back = 0, right = 3 * options.width / 4, left = options.width / 4;
  // Level: every wall is nearest at the middle of the image (row centre h/2, sample index h/2 - 0.5).
  const cv::Mat level = render_panorama(scene, pose, options).depth;
  for (int u : {front, back, left, right}) EXPECT_NEAR(depth_minimum_row(level, u), 255.5, 0.02) << u;
  const double rows_per_rad = options.height / M_PI;
  // Pitch 1.5 deg nose up: the horizon drops in front (larger rows) and rises behind; the sides stay.
  options.pitch_deg = 1.5;
  const cv::Mat pitched = render_panorama(scene, pose, options).depth;
  const double shift = 1.5 * kDeg * rows_per_rad;  // 4.27 rows
  EXPECT_NEAR(depth_minimum_row(pitched, front), 255.5 + shift, 0.05);
  EXPECT_NEAR(depth_minimum_row(pitched, back), 255.5 - shift, 0.05);
  EXPECT_NEAR(depth_minimum_row(pitched, left), 255.5, 0.05);
  EXPECT_NEAR(depth_minimum_row(pitched, right), 255.5, 0.05);
  // Roll 2 deg, left side up: the horizon drops on the left (azimuth -90) and rises on the right.
  options.pitch_deg = 0.0;
  options.roll_deg = 2.0;
  const cv::Mat rolled = render_panorama(scene, pose, options).depth;
  const double roll_shift = 2.0 * kDeg * rows_per_rad;
  EXPECT_NEAR(depth_minimum_row(rolled, left), 255.5 + roll_shift, 0.05);
  EXPECT_NEAR(depth_minimum_row(rolled, right), 255.5 - roll_shift, 0.05);
  EXPECT_NEAR(depth_minimum_row(rolled, front), 255.5, 0.05);
}

TEST(CaptureNuisances, WobbleIsSmoothWithBumpsAndLeavesTheHeadingAlone) {
  RenderOptions o;
  EXPECT_FALSE(camera_tilt_at_frame(o, 17).any());  // off by default
  o.tilt_wobble_deg = 1.0;
  double s2 = 0, worst_step = 0, worst = 0;
  const int n = 4000;
  CameraTilt previous = camera_tilt_at_frame(o, 0);
  for (int f = 1; f <= n; ++f) {
    const CameraTilt t = camera_tilt_at_frame(o, f);
    s2 += t.pitch * t.pitch + t.roll * t.roll;
    worst = std::max({worst, std::abs(t.pitch), std::abs(t.roll)});
    worst_step = std::max({worst_step, std::abs(t.pitch - previous.pitch), std::abs(t.roll - previous.roll)});
    previous = t;
  }
  const double rms_deg = std::sqrt(s2 / (2 * n)) / kDeg;
  EXPECT_GT(rms_deg, 0.6);
  EXPECT_LT(rms_deg, 1.3);
  EXPECT_LT(worst / kDeg, 5.0);
  EXPECT_LT(worst_step / kDeg, 0.35);  // smooth: over about 20 frames
  // Bumps: jolts of up to 1.5 deg at about 3 frames in 100.
  o.bump_deg = 1.5;
  int jolts = 0;
  previous = camera_tilt_at_frame(o, 0);
  for (int f = 1; f <= n; ++f) {
    const CameraTilt t = camera_tilt_at_frame(o, f);
    jolts += std::max(std::abs(t.pitch - previous.pitch), std::abs(t.roll - previous.roll)) > 0.5 * kDeg;
    previous = t;
  }
  EXPECT_GT(jolts, n * 3 / 100 / 3);
  EXPECT_LT(jolts, n * 3 / 100 * 3);
  // The camera's forward direction keeps the pose's heading whatever the tilt.
  for (int f : {3, 500, 1234}) {
    const Eigen::Matrix3d r = world_from_tilted_camera(0.8, camera_tilt_at_frame(o, f));
    const Eigen::Vector3d forward = r * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(std::atan2(forward.y(), forward.x()), 0.8, 1e-12);
    const CameraTilt t = camera_tilt_at_frame(o, f);
    EXPECT_LT((r - independent_rotation(0.8, t.pitch, t.roll)).norm(), 1e-12);
  }
}

TEST(CaptureNuisances, HeightWobbleRaisesAndLowersTheCameraSmoothly) {
  RenderOptions o;
  EXPECT_EQ(camera_height_offset_at_frame(o, 17), 0.0);  // off by default
  o.height_wobble_m = 0.03;
  double s2 = 0, worst_step = 0, previous = camera_height_offset_at_frame(o, 0);
  const int n = 4000;
  for (int f = 1; f <= n; ++f) {
    const double h = camera_height_offset_at_frame(o, f);
    s2 += h * h;
    worst_step = std::max(worst_step, std::abs(h - previous));
    previous = h;
  }
  const double rms = std::sqrt(s2 / n);
  EXPECT_GT(rms, 0.6 * 0.03);
  EXPECT_LT(rms, 1.3 * 0.03);
  EXPECT_LT(worst_step, 0.006);  // smooth: over about 40 frames
  // The render sees from the moved centre: its depth against a brute-force intersection from there.
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan);
  const test::OracleScene oracle(plan);
  o.width = 256;
  o.height = 128;
  std::mt19937 rng(778);
  int checked = 0, off = 0;
  for (int index : {5, 61, 140}) {
    const PathFrame pose{index, "", 4.0, 7.5, 0.3, 1.0, kFrameOk, ""};
    const double offset = camera_height_offset_at_frame(o, index);
    ASSERT_GT(std::abs(offset), 0.002) << index;  // frames where the camera has moved
    const cv::Mat depth = render_panorama(scene, pose, o).depth;
    const Eigen::Vector3d origin(pose.x, pose.y, scene.options.camera_height + offset);
    const Eigen::Matrix3d r = independent_rotation(pose.heading, 0.0, 0.0);
    for (int k = 0; k < 2000; ++k) {
      const int u = std::uniform_int_distribution<int>(0, o.width - 1)(rng);
      const int v = std::uniform_int_distribution<int>(0, o.height - 1)(rng);
      const Eigen::Vector3d d = r * equirect_to_bearing({u + 0.5, v + 0.5}, o.width, o.height);
      const double expected = oracle.intersect(origin, d.normalized());
      ++checked;
      if (std::abs(depth.at<float>(v, u) - expected) > 1e-5 * std::max(1.0, expected)) ++off;
    }
  }
  EXPECT_LE(off, checked / 500) << off << " of " << checked << " pixels off";
}

TEST(CaptureNuisances, ExposureStepsAreSuddenAndScaleTheImage) {
  RenderOptions o;
  EXPECT_EQ(exposure_gain_at_frame(o, 99), 1.0);
  o.exposure_jump = 0.3;
  o.exposure_jump_frames = 60;
  int steps = 0, last_step = 0, shortest = 1 << 30;
  for (int f = 1; f <= 6000; ++f) {
    const double g = exposure_gain_at_frame(o, f);
    EXPECT_GE(g, std::exp(-0.3) - 1e-12);
    EXPECT_LE(g, std::exp(0.3) + 1e-12);
    if (g != exposure_gain_at_frame(o, f - 1)) {
      ++steps;
      if (last_step > 0) shortest = std::min(shortest, f - last_step);
      last_step = f;
    }
  }
  EXPECT_NEAR(steps, 100, 2);  // one per 60 frames
  EXPECT_GE(shortest, 12);     // at least 0.2 periods apart
  // A render just before and just after a step: brightness scales by the gain ratio.
  int step_frame = 1;
  while (exposure_gain_at_frame(o, step_frame) == exposure_gain_at_frame(o, step_frame - 1)) ++step_frame;
  const double ratio = exposure_gain_at_frame(o, step_frame) / exposure_gain_at_frame(o, step_frame - 1);
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions render = o;
  render.width = 256;
  render.height = 128;
  PathFrame pose{step_frame - 1, "", 4.0, 7.5, 0.3, 1.0, kFrameOk, ""};
  const cv::Mat before = render_panorama(scene, pose, render).rgb;
  pose.index = step_frame;
  const cv::Mat after = render_panorama(scene, pose, render).rgb;
  std::vector<double> ratios;
  for (int v = 0; v < before.rows; ++v)
    for (int u = 0; u < before.cols; ++u)
      for (int k = 0; k < 3; ++k) {
        const int a = before.at<cv::Vec3b>(v, u)[k], b = after.at<cv::Vec3b>(v, u)[k];
        if (a > 40 && a < 200 && b > 40 && b < 250) ratios.push_back(double(b) / a);
      }
  ASSERT_GT(ratios.size(), 1000u);
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  EXPECT_NEAR(ratios[ratios.size() / 2], ratio, 0.01);
  EXPECT_GT(std::abs(ratio - 1.0), 0.01);
}

// What check() throws (empty when it does not).
std::string check_message(const RenderOptions& o) {
  try {
    o.check();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CaptureNuisances, BadOptionsAreNamed) {
  RenderOptions o;
  o.tilt_wobble_deg = -1;
  EXPECT_NE(check_message(o).find("tilt_wobble_deg"), std::string::npos);
  o = {};
  o.exposure_jump_frames = 0;
  EXPECT_NE(check_message(o).find("exposure_jump_frames"), std::string::npos);
  o = {};
  o.operator_distance_m = 0.1;
  EXPECT_NE(check_message(o).find("operator_distance_m"), std::string::npos);
  o = {};
  o.height_wobble_m = 0.5;
  EXPECT_NE(check_message(o).find("height_wobble_m"), std::string::npos);
  o = {};
  o.height_wobble_frames = 0;
  EXPECT_NE(check_message(o).find("height_wobble_frames"), std::string::npos);
  o = {};
  o.pitch_deg = 60;
  EXPECT_THROW(render_panorama(build_synthetic_scene(box_room()), PathFrame{}, o), Error);
}

}  // namespace
}  // namespace plenopath
