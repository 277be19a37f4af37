// Tracking under real-capture nuisances (issue 18) on short renders of the office walk against the
// renderer's ground truth: the trolley and its operator in every frame on plain painted walls (masked
// automatically, or by the author's mask), and a camera rocking on an uneven floor (bearings levelled per
// frame). Bounds leave room over what the tracker measured on these renders (noted at each); the long runs
// with every nuisance are in tests/bench/bench_nuisances.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "processing/egomotion/egomotion.h"
#include "processing/egomotion/path_evaluation.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

struct Rendered {
  CameraPath truth;
  std::vector<cv::Mat> frames;
  cv::Mat rig;  // truth: 255 where the trolley or the operator is seen
};

// The first `frames` frames of the office walk, or those from frame `first` on.
Rendered render_walk(const SceneOptions& scene_options, const RenderOptions& render, int frames,
                     double step_m = AutoWalkOptions().step, int first = 0) {
  Rendered out;
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan, scene_options);
  AutoWalkOptions walk;
  walk.max_frames = first + frames;
  walk.step = step_m;
  out.truth = auto_walk(plan, walk);
  out.truth.frames.erase(out.truth.frames.begin(), out.truth.frames.begin() + first);
  for (std::size_t i = 0; i < out.truth.frames.size(); ++i) out.truth.frames[i].index = static_cast<int>(i);
  for (const PathFrame& f : out.truth.frames) out.frames.push_back(render_panorama(scene, f, render).rgb);
  RenderOptions with = render, without = render;
  with.depth = without.depth = true;
  without.trolley = without.operator_person = false;
  cv::compare(render_panorama(scene, out.truth.frames[0], with).depth,
              render_panorama(scene, out.truth.frames[0], without).depth, out.rig, cv::CMP_NE);
  return out;
}

EgomotionResult track(const Rendered& r, const EgomotionOptions& options) {
  return EgomotionTracker::run(
      static_cast<int>(r.frames.size()), [&](int i) { return r.frames[i]; }, options);
}

RenderOptions small() {
  RenderOptions render;
  render.width = 512;
  render.height = 256;
  render.depth = false;
  return render;
}

const Rendered& trolley_walk() {
  static const Rendered walk = [] {
    SceneOptions scene;
    scene.wall_finish = WallFinish::kPlainPaint;
    scene.posters = false;
    RenderOptions render = small();
    render.trolley = render.operator_person = true;
    render.noise_sigma = 2.0;
    return render_walk(scene, render, 80);
  }();
  return walk;
}

TEST(NuisanceTracking, TrolleyAndOperatorOnPlainWallsAreMaskedAutomatically) {
  const Rendered& walk = trolley_walk();
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  const EgomotionResult r = track(walk, options);
  ASSERT_EQ(r.path.size(), walk.frames.size());
  // The mask covers the rig: hardly any rig pixel in the tracked band left usable.
  ASSERT_FALSE(r.mask.empty());
  cv::Mat rig;
  cv::resize(walk.rig, rig, r.mask.size(), 0, 0, cv::INTER_NEAREST);
  const cv::Range band(r.mask.rows / 10, r.mask.rows * 9 / 10);
  cv::Mat left;
  cv::bitwise_and(rig.rowRange(band), r.mask.rowRange(band), left);
  EXPECT_LT(cv::countNonZero(left), 0.01 * cv::countNonZero(rig.rowRange(band)));
  EXPECT_GT(r.static_mask_fraction, 0.1);
  EXPECT_LT(r.static_mask_fraction, 0.4);
  const PathErrors e = evaluate_path(r.path, walk.truth);
  EXPECT_EQ(e.frames_matched, static_cast<int>(walk.frames.size()));
  // Measured on this render: heading 0.043 deg, ATE 0.018 %, scale 0.23 %.
  EXPECT_LT(e.rot_rms_deg, 0.1);
  EXPECT_LT(e.ate_pct, 0.06);
  EXPECT_LT(e.scale_error_pct, 1.0);
  RecordProperty("heading_rms_deg", std::to_string(e.rot_rms_deg));
  RecordProperty("ate_pct", std::to_string(e.ate_pct));
  RecordProperty("scale_error_pct", std::to_string(e.scale_error_pct));
}

TEST(NuisanceTracking, TheAuthorsMaskIsUsedAsDrawn) {
  const Rendered& walk = trolley_walk();
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  options.static_mask.frames = 0;  // only the author's mask: the rig region grown by 3 pixels, inverted
  cv::Mat grown;
  cv::dilate(walk.rig, grown, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(7, 7)));
  options.mask = 255 - grown;
  const EgomotionResult r = track(walk, options);
  ASSERT_FALSE(r.mask.empty());
  EXPECT_NEAR(r.static_mask_fraction, cv::countNonZero(grown) / double(grown.total()), 0.01);
  const PathErrors e = evaluate_path(r.path, walk.truth);
  // Measured: heading 0.032 deg, ATE 0.016 %.
  EXPECT_LT(e.rot_rms_deg, 0.1);
  EXPECT_LT(e.ate_pct, 0.06);
  EXPECT_LT(e.scale_error_pct, 1.0);
  RecordProperty("heading_rms_deg", std::to_string(e.rot_rms_deg));
  RecordProperty("ate_pct", std::to_string(e.ate_pct));
}

TEST(NuisanceTracking, ARockingCameraIsLevelledPerFrame) {
  RenderOptions render = small();
  render.tilt_wobble_deg = 1.0;
  render.bump_deg = 1.5;
  const Rendered walk = render_walk(SceneOptions{}, render, 60);
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  options.klt.level_bearings = true;
  const EgomotionResult r = track(walk, options);
  const PathErrors e = evaluate_path(r.path, walk.truth);
  EXPECT_EQ(e.frames_matched, 60);
  // Measured: heading 0.23 deg, ATE 0.22 %, scale 0.87 % (the tilt estimate's error, 0.1-0.2 deg per frame
  // at 512 wide, is what is left: the 0.05 deg is not reached yet).
  EXPECT_LT(e.rot_rms_deg, 0.35);
  EXPECT_LT(e.ate_pct, 0.35);
  EXPECT_LT(e.scale_error_pct, 1.5);
  RecordProperty("heading_rms_deg", std::to_string(e.rot_rms_deg));
  RecordProperty("ate_pct", std::to_string(e.ate_pct));
  RecordProperty("scale_error_pct", std::to_string(e.scale_error_pct));
}

// Video subsampled to 26 cm steps takes the office's corners at up to 42 deg a frame: beyond the rings'
// search (18 deg around no turn) and beyond Lucas-Kanade's reach from a wrong guess. With the rig in view on
// plain walls the rings read such a turn as none. Now the rings search around the turn the tracks made into
// the frame before, Lucas-Kanade tries that turn too when the rings' guess loses its tracks
// (KltOptions::retry_share), and across such long steps the two-view turn is taken, not the median azimuth
// change that the parallax biases (bench_nuisances corridor_like: 17.4 deg -> 1.2 deg). Frames 190-249 of
// the walk at 26 cm steps, plain paint, the rig, a tilt changing within 6 frames, noise. Measured: heading
// 0.028 deg, ATE 0.005 %, scale 0.10 %; before (ad87347) 8.9 deg, 2.9 %, 3.1 %.
TEST(NuisanceTracking, FastTurnsOfSubsampledVideoWithTheRigInView) {
  SceneOptions scene;
  scene.wall_finish = WallFinish::kPlainPaint;
  scene.posters = false;
  RenderOptions render;  // at 512 wide the pyramid reaches such turns from any guess
  render.width = 1024;
  render.height = 512;
  render.depth = false;
  render.trolley = render.operator_person = true;
  render.noise_sigma = 3.0;
  render.tilt_wobble_deg = 0.7;
  render.tilt_wobble_frames = 6;
  const Rendered walk = render_walk(scene, render, 60, 0.26, 190);
  double fastest_deg = 0.0;
  for (std::size_t i = 1; i < walk.truth.size(); ++i)
    fastest_deg = std::max(fastest_deg,
                           std::abs(degrees(std::remainder(
                               walk.truth.frames[i].heading - walk.truth.frames[i - 1].heading, 2 * M_PI))));
  EXPECT_GT(fastest_deg, 25.0);  // the premise: turns faster than the rings once searched
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  const PathErrors e = evaluate_path(track(walk, options).path, walk.truth);
  RecordProperty("fastest_turn_deg", std::to_string(fastest_deg));
  RecordProperty("heading_rms_deg", std::to_string(e.rot_rms_deg));
  RecordProperty("ate_pct", std::to_string(e.ate_pct));
  RecordProperty("scale_error_pct", std::to_string(e.scale_error_pct));
  EXPECT_EQ(e.frames_matched, 60);
  EXPECT_LT(e.rot_rms_deg, 0.2);
  EXPECT_LT(e.ate_pct, 0.1);
  EXPECT_LT(e.scale_error_pct, 1.0);
}

// A corridor corner taken at 18-20 deg a frame (video subsampled to every second frame) by a POV-Ray
// trolley capture (tests/data/povray-corner/README.md), the operator and the trolley in view, with no mask
// (as where the static mask misses them): they stay put in the image while the scene turns, and the
// frame-to-frame turns must not count them. Truth: the render's headings.
TEST(NuisanceTracking, TheRigDoesNotHoldBackAFastTurn) {
  const std::string dir = std::string(PLENOPATH_TEST_DATA_DIR) + "/povray-corner/";
  const double truth_deg[] = {0.627838,  0.581936,  0.458043,  18.488396, 37.619644,
                              56.869315, 76.606877, 89.513611, 89.541372};
  Rendered capture;
  for (int i = 0; i < 9; ++i) {
    const std::string name = dir + "frame_000" + std::to_string(116 + 2 * i) + ".jpg";
    capture.frames.push_back(cv::imread(name, cv::IMREAD_COLOR));
    ASSERT_FALSE(capture.frames.back().empty()) << name;
  }
  auto worst_turn_error_deg = [&](bool ignore_still) {
    EgomotionOptions options;
    options.camera_height_m = 1.5;
    options.static_mask.frames = 0;
    options.turns_ignore_still_tracks = ignore_still;
    const EgomotionResult result = track(capture, options);
    double worst = 0.0;
    for (int i = 1; i < 9; ++i) {
      const double tracked = degrees(result.tracked_headings[i] - result.tracked_headings[i - 1]);
      worst = std::max(worst, std::abs(tracked - (truth_deg[i] - truth_deg[i - 1])));
    }
    return worst;
  };
  const double counted = worst_turn_error_deg(false), ignored = worst_turn_error_deg(true);
  RecordProperty("worst_turn_error_deg_with_rig", std::to_string(counted));
  RecordProperty("worst_turn_error_deg", std::to_string(ignored));
  EXPECT_GT(counted, 1.0);  // the premise: the rig's tracks hold the turn back
  EXPECT_LT(ignored, 1.0);
}

TEST(NuisanceTracking, BadMasksAreReported) {
  EgomotionOptions options;
  options.mask = cv::Mat(8, 16, CV_32F);
  try {
    options.check();
    ADD_FAILURE() << "no throw";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("EgomotionOptions.mask must be 8-bit"), std::string::npos)
        << error.what();
  }
  options.mask = cv::Mat(8, 16, CV_8U, cv::Scalar(0));  // nothing left
  options.static_mask.frames = 0;
  EgomotionTracker tracker(options);
  EXPECT_THROW(tracker.add_frame(cv::Mat(128, 256, CV_8UC3, cv::Scalar(50, 60, 70))), Error);
}

}  // namespace
}  // namespace plenopath
