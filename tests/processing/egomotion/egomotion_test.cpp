// Egomotion stages against independent truth: the cost functor's derivatives (Ceres GradientChecker),
// planar two-view geometry on synthetic bearings, KLT across the seam on exact rolls of a real panorama,
// and the whole pipeline on a short render of the synthetic surround camera (ground-truth poses).
#include "processing/egomotion/egomotion.h"

#include <ceres/ceres.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "model/error.h"
#include "processing/egomotion/bearing_cost.h"
#include "processing/egomotion/klt_tracks.h"
#include "processing/egomotion/path_evaluation.h"
#include "processing/egomotion/planar_two_view.h"
#include "rig/spherical.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

Eigen::Vector3d camera_bearing(const Eigen::Vector3d& pose, const Eigen::Vector3d& point) {
  return (world_from_camera_rotation(pose.z()).transpose() * (point - Eigen::Vector3d(pose.x(), pose.y(), 0)))
      .normalized();
}

TEST(BearingCost, ZeroAtTruthAndGradientsMatchNumeric) {
  const Eigen::Vector3d pose(0.3, -0.2, 0.7), point(2.0, 1.5, -1.2);
  const PlanarBearingCost cost(camera_bearing(pose, point));
  double r[3];
  cost(pose.data(), point.data(), r);
  EXPECT_NEAR(std::hypot(r[0], std::hypot(r[1], r[2])), 0.0, 1e-12);

  // Away from the truth the residual is the chord to the observation: 2 sin(angle / 2).
  const Eigen::Vector3d moved(0.5, -0.1, 0.75);
  cost(moved.data(), point.data(), r);
  const Eigen::Vector3d predicted = camera_bearing(moved, point);
  const double angle = std::acos(predicted.dot(cost.bearing));
  EXPECT_NEAR(std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]), 2 * std::sin(angle / 2), 1e-12);

  std::unique_ptr<ceres::CostFunction> function(PlanarBearingCost::Create(camera_bearing(pose, point)));
  ceres::NumericDiffOptions numeric;
  const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
  ceres::GradientChecker checker(function.get(), no_manifolds, numeric);
  ceres::GradientChecker::ProbeResults results;
  std::vector<const double*> parameters = {moved.data(), point.data()};
  EXPECT_TRUE(checker.Probe(parameters.data(), 1e-7, &results)) << results.error_log;
}

TEST(PlanarTwoView, RecoversTurnAndDirectionFromNoisyBearingsWithOutliers) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> noise(0, 0.0005);
  const Eigen::Vector3d pose_a(1.0, 2.0, 0.4), pose_b(1.25, 2.1, 0.47);  // 0.27 m, turn 4 deg
  std::vector<Eigen::Vector3d> a, b;
  for (int k = 0; k < 300; ++k) {
    const double angle = M_PI * u(rng), distance = 2.0 + 2.0 * (u(rng) + 1);
    const Eigen::Vector3d p(1.0 + distance * std::cos(angle), 2.0 + distance * std::sin(angle), 1.2 * u(rng));
    Eigen::Vector3d ba = camera_bearing(pose_a, p), bb = camera_bearing(pose_b, p);
    bb += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    if (k % 10 == 0) bb = Eigen::Vector3d(u(rng), u(rng), u(rng));  // 10 % outliers
    a.push_back(ba);
    b.push_back(bb.normalized());
  }
  PlanarTwoViewOptions options;
  std::mt19937 ransac(1);
  const PlanarRelativePose rel = estimate_planar_relative_pose(a, b, 0.07 + 0.01, options, ransac);
  ASSERT_TRUE(rel.valid);
  EXPECT_NEAR(rel.turn, 0.07, 0.002);
  // Direction of B from A in A's frame.
  const Eigen::Vector2d t = pose_b.head<2>() - pose_a.head<2>();
  const double truth_direction = std::atan2(t.y(), t.x()) - pose_a.z();
  EXPECT_NEAR(wrap_angle(rel.direction - truth_direction), 0.0, 0.01);
  EXPECT_GT(rel.inliers, 250);
}

TEST(KltTracks, FollowAnExactRollAcrossTheSeam) {
  const cv::Mat image = cv::imread(std::string(PLENOPATH_TEST_DATA_DIR) + "/convention/pano_heading0.png");
  ASSERT_FALSE(image.empty());
  KltOptions options;
  options.work_width = 0;
  options.quality_level = 0.01;
  KltTracker tracker(options);
  const int step = 7;  // columns per frame: a turn of 7 * 360 / 512 deg
  for (int i = 0; i < 12; ++i) {
    const int shift = (i * step) % image.cols;
    cv::Mat rolled;
    if (shift == 0) {
      rolled = image.clone();
    } else {
      cv::hconcat(image.colRange(image.cols - shift, image.cols), image.colRange(0, image.cols - shift),
                  rolled);
    }
    tracker.add_frame(rolled);
  }
  int checked = 0, crossed = 0;
  for (const FeatureTrack& t : tracker.tracks()) {
    for (size_t k = 1; k < t.observations.size(); ++k) {
      double dx = t.observations[k].x - t.observations[k - 1].x;
      if (dx < -image.cols / 2) {
        dx += image.cols;
        ++crossed;
      }
      EXPECT_NEAR(dx, step, 0.05);
      EXPECT_NEAR(t.observations[k].y, t.observations[k - 1].y, 0.05);
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
  EXPECT_GT(crossed, 0) << "no track crossed the seam";
}

// A short walk through the office sample, rendered once for the pipeline tests.
struct Walk {
  CameraPath truth;
  std::vector<cv::Mat> frames;
};
// Renders `truth` frame by frame as the tracker asks (512 x 256 unless `render` says otherwise) and tracks it
// with the camera-height scale (1.6 m, the scene's).
EgomotionResult track_rendered(const SyntheticScene& scene, const CameraPath& truth,
                               const RenderOptions& render) {
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  return EgomotionTracker::run(
      static_cast<int>(truth.size()),
      [&](int i) { return render_panorama(scene, truth.frames[i], render).rgb; }, options);
}

RenderOptions small_render() {
  RenderOptions render;
  render.width = 512;
  render.height = 256;
  render.depth = false;
  return render;
}

const Walk& short_walk() {
  static const Walk walk = [] {
    Walk w;
    const FloorPlan plan = make_office_sample_plan();
    const SyntheticScene scene = build_synthetic_scene(plan);
    AutoWalkOptions walk_options;
    walk_options.max_frames = 60;
    w.truth = auto_walk(plan, walk_options);
    const RenderOptions render = small_render();
    for (const PathFrame& f : w.truth.frames) w.frames.push_back(render_panorama(scene, f, render).rgb);
    return w;
  }();
  return walk;
}

TEST(Egomotion, ShortRenderedWalkAgainstGroundTruth) {
  const Walk& walk = short_walk();
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  std::vector<std::string> stages;
  std::vector<double> fractions;
  FunctionProgress progress([&](double f, const std::string& stage) {
    fractions.push_back(f);
    if (!stage.empty() && (stages.empty() || stages.back() != stage)) stages.push_back(stage);
  });
  const EgomotionResult r = EgomotionTracker::run(
      static_cast<int>(walk.frames.size()), [&](int i) { return walk.frames[i]; }, options, progress);
  // One progress for the whole run: never backwards, from the first frame to the end.
  ASSERT_FALSE(fractions.empty());
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_NEAR(fractions.back(), 1.0, 1e-12);
  ASSERT_EQ(r.path.size(), walk.frames.size());
  const PathErrors e = evaluate_path(r.path, walk.truth);
  EXPECT_EQ(e.frames_matched, 60);
  // Measured on this render: ATE 0.026 %, heading 0.027 deg, scale 0.39 %; the bounds leave room for
  // platform noise.
  EXPECT_LT(e.ate_pct, 0.2);
  EXPECT_LT(e.rot_rms_deg, 0.15);
  EXPECT_EQ(r.scale_source, "camera_height");
  EXPECT_LT(e.scale_error_pct, 2.0);
  EXPECT_EQ(r.path.scale_source, "camera_height");
  // Step 1 on its own is coarse indoors but must follow the turns.
  double s2 = 0;
  for (size_t i = 0; i < walk.truth.size(); ++i) {
    const double truth_turn = wrap_angle(walk.truth.frames[i].heading - walk.truth.frames[0].heading);
    s2 += std::pow(wrap_angle(r.ring_headings[i] - truth_turn), 2);
  }
  EXPECT_LT(degrees(std::sqrt(s2 / walk.truth.size())), 25.0);  // measured ~16 deg: coarse, as expected
  EXPECT_NE(std::find(stages.begin(), stages.end(), "refinement"), stages.end());
}

// Same input, same output, bit for bit: twice in a row, and once more with OpenCV on a single thread (its
// thread pool must not change what the KLT stage finds).
TEST(Egomotion, SameInputGivesTheSameResultBitForBit) {
  const Walk& walk = short_walk();
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  auto track = [&] {
    return EgomotionTracker::run(
        48, [&](int i) { return walk.frames[i]; }, options);
  };
  const EgomotionResult first = track();
  const EgomotionResult second = track();
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  const EgomotionResult single = track();
  cv::setNumThreads(threads);
  ASSERT_EQ(first.path.size(), 48u);
  for (const EgomotionResult* other : {&second, &single}) {
    ASSERT_EQ(other->path.size(), first.path.size());
    EXPECT_EQ(other->points, first.points);
    EXPECT_EQ(other->observations, first.observations);
    EXPECT_EQ(other->scale_factor, first.scale_factor);
    for (size_t i = 0; i < first.path.size(); ++i) {
      const PathFrame &a = first.path.frames[i], &b = other->path.frames[i];
      EXPECT_TRUE(a.x == b.x && a.y == b.y && a.heading == b.heading && a.flags == b.flags)
          << "frame " << i << ": " << a.x << " " << a.y << " " << a.heading << " vs " << b.x << " " << b.y
          << " " << b.heading;
    }
  }
}

// Sensor noise, a slow exposure drift and people walking through the scene (the renderer's realism
// switches): no crash, every frame placed, and the path within the 2 % of its length.
TEST(Egomotion, NoiseAndMovingPeopleStayWithinTwoPercent) {
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan);
  AutoWalkOptions walk_options;
  walk_options.max_frames = 60;
  const CameraPath truth = auto_walk(plan, walk_options);
  RenderOptions render = small_render();
  render.noise_sigma = 3.0;
  render.exposure_drift = 0.1;
  render.people = 8;
  const EgomotionResult r = track_rendered(scene, truth, render);
  ASSERT_EQ(r.path.size(), truth.size());
  for (const PathFrame& f : r.path.frames)
    ASSERT_TRUE(std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.heading));
  const PathErrors e = evaluate_path(r.path, truth);
  EXPECT_EQ(e.frames_matched, 60);
  EXPECT_LT(e.ate_pct, 2.0);
  EXPECT_LT(e.rot_rms_deg, 2.0);
  EXPECT_LT(e.scale_error_pct, 10.0);
}

// Forward, a half turn on the spot, and back along the same way: the turn has no translation to measure, so
// only points seen before, during and after it carry the scale across. Both legs must keep one scale.
TEST(Egomotion, TurnOnTheSpotKeepsOneScale) {
  const Walk& walk = short_walk();
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan);
  CameraPath truth;
  for (int i = 0; i < 40; ++i) truth.frames.push_back(walk.truth.frames[i]);
  for (int k = 1; k <= 30; ++k) {
    PathFrame f = walk.truth.frames[39];
    f.heading = wrap_angle(f.heading + M_PI * k / 30);
    truth.frames.push_back(f);
  }
  for (int i = 38; i >= 0; --i) {
    PathFrame f = walk.truth.frames[i];
    f.heading = wrap_angle(f.heading + M_PI);
    truth.frames.push_back(f);
  }
  for (size_t i = 0; i < truth.size(); ++i) truth.frames[i].index = static_cast<int>(i);
  const EgomotionResult r = track_rendered(scene, truth, small_render());
  ASSERT_EQ(r.path.size(), truth.size());
  const PathErrors e = evaluate_path(r.path, truth);
  EXPECT_LT(e.ate_pct, 1.0);
  EXPECT_LT(e.scale_error_pct, 5.0);
  // The way back retraces the way out: each return frame lies where its outbound twin was.
  double worst = 0.0;
  for (int i = 0; i < 39; ++i) {
    const PathFrame& out = r.path.frames[i];
    const PathFrame& back = r.path.frames[108 - i];  // 40 out, 30 turning, then 38 down to 0
    worst = std::max(worst, std::hypot(out.x - back.x, out.y - back.y));
  }
  EXPECT_LT(worst, 0.05 * e.truth_length_m / 2) << "outbound and return legs disagree";
}

TEST(Egomotion, CancelDuringRefinementStopsCleanly) {
  const Walk& walk = short_walk();
  EgomotionOptions options;
  std::vector<std::string> stages_after_cancel;
  FunctionProgress progress([&](double, const std::string& stage) {
    if (progress.is_cancelled()) stages_after_cancel.push_back(stage);
    if (stage.find("refinement") != std::string::npos) progress.cancel();
  });
  EXPECT_THROW(EgomotionTracker::run(
                   40, [&](int i) { return walk.frames[i]; }, options, progress),
               Cancelled);
  // It stopped inside the refinement: no later stage (resection) was reached.
  for (const std::string& s : stages_after_cancel) EXPECT_EQ(s.find("resection"), std::string::npos) << s;
}

// Cancelled right after its first report (while reading frames), the run ends with Cancelled at once.
TEST(Egomotion, CancelAfterTheFirstReportEndsTheRun) {
  const Walk& walk = short_walk();
  int reads = 0, reports = 0;
  FunctionProgress progress([&](double, const std::string&) {
    ++reports;
    progress.cancel();
  });
  EXPECT_THROW(EgomotionTracker::run(
                   40,
                   [&](int i) {
                     ++reads;
                     return walk.frames[i];
                   },
                   EgomotionOptions{}, progress),
               Cancelled);
  EXPECT_EQ(reports, 1);
  EXPECT_EQ(reads, 1) << "the first report comes after frame 0; nothing more is read";
}

TEST(Egomotion, StopsAndBlankFramesAreFlaggedNotSilentlyUsed) {
  const Walk& walk = short_walk();
  std::vector<cv::Mat> frames(walk.frames.begin(), walk.frames.begin() + 30);
  // The trolley stops for three frames after frame 10; frames 20 and 21 are blank (lens cap, corrupt).
  frames.insert(frames.begin() + 11, 3, frames[10]);
  const cv::Mat blank(frames[0].size(), CV_8UC3, cv::Scalar(128, 128, 128));
  frames[23] = blank;
  frames[24] = blank;
  EgomotionOptions options;
  const EgomotionResult r = EgomotionTracker::run(
      static_cast<int>(frames.size()), [&](int i) { return frames[i]; }, options);
  ASSERT_EQ(r.path.size(), frames.size());
  for (int i = 11; i <= 13; ++i) {
    EXPECT_TRUE(r.path.frames[i].flags & kFrameDuplicate) << i;
    EXPECT_FALSE(r.path.frames[i].reason.empty());
  }
  EXPECT_TRUE(r.path.frames[23].flags & kFrameTextureless);
  EXPECT_TRUE(r.path.frames[24].flags & kFrameTextureless);
  EXPECT_EQ(r.path.frames[5].flags, kFrameOk);
  for (const PathFrame& f : r.path.frames) {
    EXPECT_TRUE(std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.heading));
  }
}

// A crowd (or a passing vehicle) sliding across most of the view for 20 frames: those frames are flagged
// as moving objects with the share in the reason, the others are not, and the path stays whole.
TEST(Egomotion, AMovingCrowdIsFlagged) {
  const Walk& walk = short_walk();
  std::vector<cv::Mat> frames;
  for (const cv::Mat& f : walk.frames) frames.push_back(f.clone());
  cv::RNG rng(17);
  cv::Mat crowd(256, 512, CV_8UC3);
  rng.fill(crowd, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(crowd, crowd, cv::Size(0, 0), 1.5);
  const int w = frames[0].cols, h = frames[0].rows;
  const cv::Rect band(0, 3 * h / 20, 3 * w / 5, 7 * h / 10);
  for (int f = 20; f < 40; ++f) {
    const int shift = 20 + 4 * (f - 20);  // 4 px (2.8 deg) a frame, whatever the camera does
    crowd(cv::Rect(0, 0, band.width, band.height)).copyTo(frames[f](band + cv::Point(shift, 0)));
  }
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  const EgomotionResult r = EgomotionTracker::run(
      static_cast<int>(frames.size()), [&](int i) { return frames[i]; }, options);
  ASSERT_EQ(r.path.size(), frames.size());
  int flagged_inside = 0;
  for (int f = 0; f < static_cast<int>(frames.size()); ++f) {
    const bool moving = r.path.frames[f].flags & kFrameMovingObjects;
    if (f >= 24 && f < 40) {
      flagged_inside += moving;
      if (moving) {
        EXPECT_NE(r.path.frames[f].reason.find("moving objects"), std::string::npos);
        EXPECT_LE(r.path.frames[f].confidence, 1.0 - options.moving_outlier_fraction);
      }
    } else if (f < 20 || f > 41) {
      EXPECT_FALSE(moving) << "frame " << f << ": " << r.path.frames[f].reason;
    }
  }
  EXPECT_GE(flagged_inside, 12);  // seen: 15 of 16 (the share ramps up as new corners land on the crowd)
  // The crowd hides most of the scene for a third of this short walk (bridged frames): measured ATE 2.9 %.
  for (const PathFrame& f : r.path.frames) EXPECT_TRUE(std::isfinite(f.x) && std::isfinite(f.y));
  EXPECT_LT(evaluate_path(r.path, walk.truth).ate_pct, 5.0);
}

// An auto-exposure jump (the whole image x0.7 for 20 frames, as a camera does walking under a window): one
// piece, and the path as good as without it. Truth: the render's poses. Measured: heading RMS 0.027 deg,
// ATE 0.027 %; with normalise_exposure off (PLENOPATH_TEST_NO_EXPOSURE=1) 0.147 deg, 0.135 %, and the
// POV-Ray corridor walk broke in three pieces at its two jumps.
TEST(Egomotion, AnExposureJumpDoesNotBreakTheCapture) {
  const Walk& walk = short_walk();
  std::vector<cv::Mat> frames;
  for (const cv::Mat& f : walk.frames) frames.push_back(f.clone());
  for (int f = 20; f < 40; ++f) frames[f].convertTo(frames[f], -1, 0.7);
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  if (std::getenv("PLENOPATH_TEST_NO_EXPOSURE")) options.klt.normalise_exposure = false;
  const EgomotionResult r = EgomotionTracker::run(
      static_cast<int>(frames.size()), [&](int i) { return frames[i]; }, options);
  ASSERT_EQ(r.path.size(), frames.size());
  EXPECT_LE(r.path.pieces.size(), 1u);  // one piece (a path in one piece lists none)
  const PathErrors e = evaluate_path(r.path, walk.truth);
  std::printf("exposure jump: %zu pieces, heading RMS %.3f deg, ATE %.3f %%\n", r.path.pieces.size(),
              e.rot_rms_deg, e.ate_pct);
  EXPECT_LT(e.rot_rms_deg, 0.08);
  EXPECT_LT(e.ate_pct, 0.08);
}

TEST(Egomotion, BadOptionsAndInputsAreReported) {
  EgomotionOptions options;
  options.keyframe_parallax_deg = -1;
  try {
    options.check();
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "EgomotionOptions.keyframe_parallax_deg must be > 0, got -1");
  }
  EXPECT_THROW(EgomotionTracker{options}, Error);
  auto refused = [](const std::function<void(EgomotionOptions&)>& set, const std::string& field) {
    EgomotionOptions o;
    set(o);
    try {
      o.check();
      ADD_FAILURE() << field << ": no throw";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("EgomotionOptions." + field), std::string::npos) << e.what();
    }
  };
  refused([](EgomotionOptions& o) { o.step_map_check_factor = 0.5; }, "step_map_check_factor");
  refused([](EgomotionOptions& o) { o.step_map_check_deg = 0; }, "step_map_check_deg");
  refused([](EgomotionOptions& o) { o.step_direction_prior_share = 1.5; }, "step_direction_prior_share");
  refused([](EgomotionOptions& o) { o.step_direction_prior_share = -0.1; }, "step_direction_prior_share");
  refused([](EgomotionOptions& o) { o.floor_step_min_points = -1; }, "floor_step_min_points");
  refused([](EgomotionOptions& o) { o.floor_step_max_spread = 0; }, "floor_step_max_spread");
  EgomotionTracker tracker{EgomotionOptions{}};
  EXPECT_THROW(tracker.finish(), Error);                               // no frames
  EXPECT_THROW(tracker.add_frame(cv::Mat(100, 100, CV_8UC3)), Error);  // not 2:1
}

}  // namespace
}  // namespace plenopath
