// Clean plates (issue 24) against the truth of the same walk rendered without people: the project's
// renderer draws both from one scene, so the people's pixels and what is behind them are known exactly.
#include "processing/cleanplate/clean_plate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "processing/egomotion/static_mask.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/cleanplate/masked_psnr.h"

namespace plenopath {
namespace {

using test::masked_psnr;

struct Walk {
  FloorPlan plan = make_office_sample_plan();
  SyntheticScene scene = build_synthetic_scene(plan);
  CameraPath path;
  RenderOptions with_people, without;
  std::map<int, RenderedPanorama> people_cache, clean_cache;

  explicit Walk(int frames, int people) {
    AutoWalkOptions walk;
    walk.max_frames = frames;
    walk.seed = 3;
    path = auto_walk(plan, walk);
    // 1024 wide: at 512 the renderer's textures alias, so that no warp of another view matches them (the
    // consensus reaches ~29 dB there, 33-37 dB at 1024).
    with_people.width = 1024;
    with_people.height = 512;
    with_people.people = people;
    with_people.frame_rate = 10;  // 8 cm steps at 10 frames/s: people walk as fast as the camera
    with_people.depth = true;
    without = with_people;
    without.people = 0;
  }
  const RenderedPanorama& rendered(int i, bool people) {
    auto& cache = people ? people_cache : clean_cache;
    auto it = cache.find(i);
    if (it == cache.end())
      it = cache.emplace(i, render_panorama(scene, path.frames[i], people ? with_people : without)).first;
    return it->second;
  }
  cv::Mat depth(int i) {
    cv::Mat d;
    rendered(i, false).depth.convertTo(d, CV_32F);
    return d;
  }
};

TEST(CleanPlate, PeopleWalkingThroughAreReplacedByWhatIsBehindThem) {
  Walk walk(80, 12);
  double worst_people = INFINITY, worst_elsewhere = INFINITY;
  int keyframes_with_people = 0;
  for (int k : {20, 40, 60}) {
    const CleanPlate plate = clean_plate(
        walk.path, k, [&](int i) { return walk.rendered(i, true).rgb; }, [&](int i) { return walk.depth(i); },
        {});
    const cv::Mat& truth = walk.rendered(k, false).rgb;
    const cv::Mat& original = walk.rendered(k, true).rgb;
    // Where the people are in the keyframe: it differs from the render without them.
    const cv::Mat people = test::differing_pixels(original, truth, 8);
    const int people_px = cv::countNonZero(people);
    const double before = masked_psnr(original, truth, people),
                 after = masked_psnr(plate.image, truth, people);
    const double elsewhere = masked_psnr(plate.image, truth, ~people);
    std::printf("  consensus PSNR: people %.1f dB, elsewhere %.1f dB; replaced pixels %.1f dB\n",
                masked_psnr(plate.consensus, truth, people), masked_psnr(plate.consensus, truth, ~people),
                masked_psnr(plate.image, truth, plate.moving_mask));
    std::printf(
        "keyframe %d: %d people pixels, PSNR there %.1f -> %.1f dB, elsewhere %.1f dB; %zu neighbours, "
        "%.2f %% replaced, %.1f %% of it unsupported\n",
        k, people_px, before, after, elsewhere, plate.neighbours_used.size(), 100 * plate.moving_share,
        100 * plate.unsupported_share);
    if (people_px > 200) {
      ++keyframes_with_people;
      worst_people = std::min(worst_people, after);
    }
    worst_elsewhere = std::min(worst_elsewhere, elsewhere);
  }
  ASSERT_GE(keyframes_with_people, 2) << "the walk should meet people";
  EXPECT_GE(worst_people, 30.0);
  EXPECT_GE(worst_elsewhere, 40.0);  // the original is exact there: replacing nothing keeps it infinite
}

TEST(CleanPlate, AWalkWithoutPeopleStaysAsItWas) {
  Walk walk(60, 0);
  const CleanPlate plate = clean_plate(
      walk.path, 30, [&](int i) { return walk.rendered(i, false).rgb; }, [&](int i) { return walk.depth(i); },
      {});
  EXPECT_LT(plate.moving_share, 0.002);
  EXPECT_GE(masked_psnr(plate.image, walk.rendered(30, false).rgb, {}), 45.0);
}

// The trolley and the operator, in every frame: the rig mask is the tracker's own estimate (the static
// mask of the first 60 frames, inverted); the depth is the capture's depth map, which sees the rig; the
// truth is the same walk rendered without them.
TEST(CleanPlate, TheTrolleyAndOperatorAreFilledFromFramesFurtherAlong) {
  Walk walk(150, 0);
  walk.with_people.trolley = walk.with_people.operator_person = true;
  StaticMaskEstimator estimator{StaticMaskOptions{}};
  for (int i = 0; i < 60 && !estimator.ready(); ++i) estimator.add(walk.rendered(i, true).rgb);
  const cv::Mat usable = estimator.mask(walk.rendered(0, true).rgb.size());
  ASSERT_FALSE(usable.empty()) << "the static mask should find the rig";
  const cv::Mat rig_mask = usable == 0;
  CleanPlateOptions options;
  options.camera_height_m = SceneOptions{}.camera_height;
  double worst_filled = INFINITY, worst_elsewhere = INFINITY, least_filled_share = 1;
  for (int k : {60, 100}) {
    const CleanPlate plate = clean_plate(
        walk.path, k, [&](int i) { return walk.rendered(i, true).rgb; },
        [&](int i) {
          cv::Mat d;
          walk.rendered(i, true).depth.convertTo(d, CV_32F);
          return d;
        },
        rig_mask, options);
    const cv::Mat& truth = walk.rendered(k, false).rgb;
    const cv::Mat& original = walk.rendered(k, true).rgb;
    const cv::Mat rig_truth = test::differing_pixels(original, truth, 8);
    const cv::Mat filled = rig_truth & plate.rig_filled;
    const double filled_share = double(cv::countNonZero(filled)) / cv::countNonZero(rig_truth);
    const double psnr_filled = masked_psnr(plate.image, truth, filled);
    cv::Mat near_rig;
    cv::dilate(rig_truth, near_rig, cv::Mat(), cv::Point(-1, -1), 2);
    const double elsewhere = masked_psnr(plate.image, truth, ~near_rig);
    std::printf(
        "keyframe %d: rig %.1f %% of the image (mask %.1f %%), %.1f %% of it filled at %.1f dB (before %.1f "
        "dB); "
        "%.1f %% of the mask unfilled; elsewhere %.1f dB; %zu rig neighbours\n",
        k, 100.0 * cv::countNonZero(rig_truth) / rig_truth.total(), 100 * plate.rig_share, 100 * filled_share,
        psnr_filled, masked_psnr(original, truth, filled), 100 * plate.rig_unfilled_share, elsewhere,
        plate.rig_neighbours_used.size());
    worst_filled = std::min(worst_filled, psnr_filled);
    worst_elsewhere = std::min(worst_elsewhere, elsewhere);
    least_filled_share = std::min(least_filled_share, filled_share);
    EXPECT_EQ(cv::countNonZero(plate.rig_filled & plate.rig_unfilled), 0);
  }
  EXPECT_GE(worst_filled, 25.0);
  EXPECT_GE(least_filled_share, 0.5);
  EXPECT_GE(worst_elsewhere, 35.0);
}

TEST(CleanPlate, BadInputIsAClearError) {
  Walk walk(20, 0);
  auto image = [&](int i) { return walk.rendered(i, false).rgb; };
  auto depth = [&](int i) { return walk.depth(i); };
  EXPECT_THROW(clean_plate(walk.path, 99, image, depth, {}), Error);
  EXPECT_THROW(clean_plate(walk.path, 5, image, [](int) { return cv::Mat(); }, {}), Error);
  EXPECT_THROW(clean_plate(walk.path, 5, image, depth, cv::Mat(10, 10, CV_8U, cv::Scalar(255))), Error);
  CleanPlateOptions o;
  o.max_baseline_m = 0.1;
  EXPECT_THROW(o.check(), Error);
  struct CancelAtOnce : CancellableProgress {
    void report(double, const std::string&) override { cancel(); }
  } cancel;
  EXPECT_THROW(clean_plate(walk.path, 10, image, depth, {}, {}, cancel), Cancelled);
}

}  // namespace
}  // namespace plenopath
