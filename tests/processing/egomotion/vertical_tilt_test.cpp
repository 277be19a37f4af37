// Pitch and roll from vertical edges against the renderer's truth (rig/synthetic_camera.h renders the
// camera tilted by exactly camera_tilt_at_frame), and the levelled KLT bearings against the true rotation.
#include "processing/egomotion/vertical_tilt.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "model/error.h"
#include "processing/egomotion/klt_tracks.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

constexpr double kDeg = M_PI / 180.0;

cv::Mat grey(const cv::Mat& bgr) {
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  return g;
}

TEST(VerticalTilt, RecoversKnownPitchAndRollFromTheRender) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions render;
  render.width = 1024;
  render.height = 512;
  render.depth = false;
  struct Case {
    PathFrame pose;
    double pitch_deg, roll_deg;
  };
  const Case cases[] = {
      {{0, "", 4.0, 7.5, 0.3, 1.0, kFrameOk, ""}, 0.0, 0.0},
      {{0, "", 4.0, 7.5, 0.3, 1.0, kFrameOk, ""}, 1.5, -1.0},
      {{0, "", 11.0, 10.0, -2.0, 1.0, kFrameOk, ""}, -2.0, 0.5},
      {{0, "", 12.6, 2.6, 3.1, 1.0, kFrameOk, ""}, 0.8, 2.0},
      {{0, "", 4.5, 1.0, 1.57, 1.0, kFrameOk, ""}, -1.0, -1.5},
  };
  double s2 = 0;
  for (const Case& c : cases) {
    render.pitch_deg = c.pitch_deg;
    render.roll_deg = c.roll_deg;
    const TiltEstimate e = estimate_tilt(grey(render_panorama(scene, c.pose, render).rgb), TiltOptions{});
    ASSERT_TRUE(e.valid);
    const double dp = e.pitch / kDeg - c.pitch_deg, dr = e.roll / kDeg - c.roll_deg;
    EXPECT_LT(std::abs(dp), 0.4) << "pitch " << c.pitch_deg;
    EXPECT_LT(std::abs(dr), 0.4) << "roll " << c.roll_deg;
    s2 += dp * dp + dr * dr;
    // The levelling rotation takes the estimated up to +z and keeps the heading.
    const Eigen::Matrix3d r = level_from_camera(e);
    EXPECT_LT((r * e.up - Eigen::Vector3d::UnitZ()).norm(), 1e-9);
    const Eigen::Vector3d forward = r * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(std::atan2(forward.y(), forward.x()), 0.0, 1e-12);
  }
  const double rms = std::sqrt(s2 / (2 * std::size(cases)));
  EXPECT_LT(rms, 0.25);  // measured 0.1 - 0.2 deg: edges on a 0.35 deg pixel grid
  RecordProperty("tilt_rms_error_deg", std::to_string(rms));
}

TEST(VerticalTilt, LevelledBearingsFollowTheTrueRotation) {
  // For a tilted camera, KLT's levelled bearing of a pixel is the pixel's true direction in the level frame
  // (up to the estimate's error); the raw camera-frame bearing is off by the tilt.
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions render;
  render.width = 1024;
  render.height = 512;
  render.depth = false;
  render.pitch_deg = 2.0;
  render.roll_deg = -1.2;
  const PathFrame pose{0, "", 4.0, 7.5, 0.0, 1.0, kFrameOk, ""};
  KltOptions options;
  options.level_bearings = true;
  KltTracker klt(options);
  klt.add_frame(render_panorama(scene, pose, render).rgb);
  ASSERT_EQ(klt.tilts().size(), 1u);
  const Eigen::Matrix3d truth = world_from_tilted_camera(0.0, camera_tilt_at_frame(render, 0));
  double worst = 0, raw_worst = 0;
  for (int v = 100; v < 412; v += 37)
    for (int u = 0; u < 1024; u += 61) {
      const TrackObservation o{0, static_cast<float>(u), static_cast<float>(v)};
      const Eigen::Vector3d b = klt.bearing(o);
      // The pixel's bearing in the camera frame (centres at u + 0.5) and its true level direction.
      const double x = (u + 0.5) / 1024 * 2 * M_PI - M_PI, e = M_PI / 2 - (v + 0.5) / 512 * M_PI;
      const Eigen::Vector3d pixel(std::cos(e) * std::cos(x), -std::cos(e) * std::sin(x), std::sin(e));
      const Eigen::Vector3d world = truth * pixel;
      worst = std::max(worst, std::acos(std::clamp(b.dot(world), -1.0, 1.0)) / kDeg);
      raw_worst = std::max(raw_worst, std::acos(std::clamp(pixel.dot(world), -1.0, 1.0)) / kDeg);
    }
  EXPECT_GT(raw_worst, 1.5);  // uncorrected: off by up to the tilt (2.3 deg)
  EXPECT_LT(worst, 0.4);
}

// KltOptions::auto_level: the spread of the first frames' tilt estimates, against the spread of the tilt
// the renderer applied (camera_tilt_at_frame), decides whether bearings are levelled.
struct AutoLevelRun {
  bool levelling = false;
  double spread_deg = 0, true_spread_deg = 0;
  std::size_t tilts = 0;
};
AutoLevelRun run_auto_level(double wobble_deg, int frames_added) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions render;
  render.width = 1024;
  render.height = 512;
  render.depth = false;
  render.tilt_wobble_deg = wobble_deg;
  render.tilt_wobble_frames = 6;  // the tilt changes within a few frames (a rocking trolley, subsampled)
  KltOptions options;
  options.auto_level_frames = 12;
  KltTracker klt(options);
  std::vector<double> pitch, roll;
  for (int i = 0; i < frames_added; ++i) {
    const PathFrame pose{i, "", 3.0 + 0.1 * i, 6.0, 0.0, 1.0, kFrameOk, ""};
    klt.add_frame(render_panorama(scene, pose, render).rgb);
    const CameraTilt t = camera_tilt_at_frame(render, i);
    pitch.push_back(t.pitch);
    roll.push_back(t.roll);
  }
  // The true spread as auto_level measures its estimates' (1.4826 x the median absolute deviation of pitch
  // and of roll, together), over the 12 frames it judges.
  auto median_of = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  auto robust_sigma = [&](std::vector<double> v) {
    v.resize(std::min<std::size_t>(v.size(), 12));
    const double m = median_of(v);
    for (double& x : v) x = std::abs(x - m);
    return 1.4826 * median_of(v);
  };
  const double true_spread = std::hypot(robust_sigma(pitch), robust_sigma(roll)) / kDeg;
  return {klt.levelling(), klt.tilt_spread_deg(), true_spread, klt.tilts().size()};
}

TEST(VerticalTilt, TheTrackerLevelsARockingCameraByItself) {
  const AutoLevelRun rocking = run_auto_level(1.0, 14);
  std::printf("rocking: spread %.3f deg estimated, %.3f true\n", rocking.spread_deg, rocking.true_spread_deg);
  EXPECT_GT(rocking.true_spread_deg, 0.5);
  EXPECT_NEAR(rocking.spread_deg, rocking.true_spread_deg, 0.25);
  EXPECT_TRUE(rocking.levelling);
  EXPECT_EQ(rocking.tilts, 14u);  // levelling on: every frame's tilt is estimated
  const AutoLevelRun level = run_auto_level(0.0, 14);
  std::printf("level: spread %.3f deg estimated\n", level.spread_deg);
  EXPECT_LT(level.spread_deg, 0.15);
  EXPECT_FALSE(level.levelling);
  EXPECT_EQ(level.tilts, 12u);  // judged on the first 12, then no more estimates
  // Fewer frames than it judges on: not levelled, not judged.
  const AutoLevelRun short_capture = run_auto_level(1.0, 5);
  EXPECT_FALSE(short_capture.levelling);
  EXPECT_EQ(short_capture.spread_deg, 0.0);
}

TEST(VerticalTilt, BadInputIsReported) {
  TiltOptions o;
  o.max_tilt_deg = 0;
  try {
    o.check();
    ADD_FAILURE() << "no throw";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "TiltOptions.max_tilt_deg must be in (0, 45), got 0");
  }
  KltOptions klt;
  klt.auto_level_frames = 1;
  try {
    klt.check();
    ADD_FAILURE() << "no throw";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "KltOptions.auto_level_frames must be >= 2, got 1");
  }
  EXPECT_THROW(estimate_tilt(cv::Mat(4, 8, CV_32F), TiltOptions{}), Error);
  EXPECT_THROW(estimate_tilt(cv::Mat(4, 8, CV_8U, cv::Scalar(0)), TiltOptions{}, cv::Mat(2, 2, CV_8U)),
               Error);
  EXPECT_FALSE(estimate_tilt(cv::Mat(256, 512, CV_8U, cv::Scalar(90)), TiltOptions{}).valid);  // no edges
}

}  // namespace
}  // namespace plenopath
