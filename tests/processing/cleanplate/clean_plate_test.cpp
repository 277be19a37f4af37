// Clean plates (issue 24) against the truth of the same walk rendered without people: the project's
// renderer draws both from one scene, so the people's pixels and what is behind them are known exactly.
#include "processing/cleanplate/clean_plate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
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
        walk.path, k, [&](int i) { return walk.rendered(i, true).rgb; },
        [&](int i) { return walk.depth(i); });
    const cv::Mat& truth = walk.rendered(k, false).rgb;
    const cv::Mat& original = walk.rendered(k, true).rgb;
    // Where the people are in the keyframe: it differs from the render without them.
    cv::Mat diff, people;
    cv::absdiff(original, truth, diff);
    cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
    cv::threshold(diff, people, 8, 255, cv::THRESH_BINARY);
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
      walk.path, 30, [&](int i) { return walk.rendered(i, false).rgb; },
      [&](int i) { return walk.depth(i); });
  EXPECT_LT(plate.moving_share, 0.002);
  EXPECT_GE(masked_psnr(plate.image, walk.rendered(30, false).rgb, {}), 45.0);
}

TEST(CleanPlate, BadInputIsAClearError) {
  Walk walk(20, 0);
  auto image = [&](int i) { return walk.rendered(i, false).rgb; };
  auto depth = [&](int i) { return walk.depth(i); };
  EXPECT_THROW(clean_plate(walk.path, 99, image, depth), Error);
  EXPECT_THROW(clean_plate(walk.path, 5, image, [](int) { return cv::Mat(); }), Error);
  CleanPlateOptions o;
  o.max_baseline_m = 0.1;
  EXPECT_THROW(o.check(), Error);
  struct CancelAtOnce : CancellableProgress {
    void report(double, const std::string&) override { cancel(); }
  } cancel;
  EXPECT_THROW(clean_plate(walk.path, 10, image, depth, {}, cancel), Cancelled);
}

}  // namespace
}  // namespace plenopath
