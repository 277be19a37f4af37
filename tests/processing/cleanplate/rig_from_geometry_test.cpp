// The rig over a capture from the scene's geometry: a plain-shirted operator right behind the camera (a
// flat patch at the same pixels of every frame, round the backward direction, where the scene behind shows
// little parallax) on the project's renderer's walk; the truth is the walk rendered without it.
#include "processing/cleanplate/rig_from_geometry.h"

#include <gtest/gtest.h>

#include <map>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "processing/cleanplate/clean_plate.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/cleanplate/masked_psnr.h"

namespace plenopath {
namespace {

struct PatchedWalk {
  FloorPlan plan = make_office_sample_plan();
  SyntheticScene scene = build_synthetic_scene(plan);
  CameraPath path;
  RenderOptions render;
  cv::Mat patch;  // CV_8U, 255 where the operator stands
  std::map<int, RenderedPanorama> cache;
  PatchedWalk() {
    AutoWalkOptions walk;
    walk.max_frames = 150;
    walk.seed = 3;
    path = auto_walk(plan, walk);
    render.width = 1024;
    render.height = 512;
    render.depth = true;
    // Azimuth 180 +- 16 deg (both image edges), from 5 to 60 deg below the horizon, and a floor-standing
    // column down to the nadir: the operator's legs.
    patch = cv::Mat::zeros(render.height, render.width, CV_8U);
    const int half_width = render.width * 16 / 360, top = render.height * 95 / 180;
    patch(cv::Rect(0, top, half_width, render.height * 150 / 180 - top)).setTo(255);
    patch(cv::Rect(render.width - half_width, top, half_width, render.height * 150 / 180 - top)).setTo(255);
    patch(cv::Rect(0, top, render.width / 90, render.height - top)).setTo(255);
  }
  const RenderedPanorama& rendered(int i) {
    auto it = cache.find(i);
    if (it == cache.end()) it = cache.emplace(i, render_panorama(scene, path.frames[i], render)).first;
    return it->second;
  }
  cv::Mat frame(int i) {
    cv::Mat image = rendered(i).rgb.clone();
    image.setTo(cv::Scalar(90, 140, 100), patch);
    return image;
  }
  cv::Mat depth(int i) {
    cv::Mat d;
    rendered(i).depth.convertTo(d, CV_32F);
    return d;
  }
};

TEST(RigFromGeometry, APlainOperatorBehindTheCameraIsFoundAndFilled) {
  PatchedWalk walk;
  auto frame = [&](int i) { return walk.frame(i); };
  auto depth = [&](int i) { return walk.depth(i); };
  const CaptureStillness still = capture_stillness(frame, static_cast<int>(walk.path.size()));
  const cv::Mat rig = rig_from_geometry(walk.path, frame, depth, {}, still);
  ASSERT_FALSE(rig.empty());
  const double covered = double(cv::countNonZero(rig & walk.patch)) / cv::countNonZero(walk.patch);
  const double beyond = double(cv::countNonZero(rig & ~walk.patch)) / rig.total();
  std::printf("rig found: %.0f %% of the operator, %.1f %% of the image beyond it\n", 100 * covered,
              100 * beyond);
  EXPECT_GT(covered, 0.8);
  EXPECT_LT(beyond, 0.04);
  // With it, the clean plate fills the operator with the scene behind (the truth: the walk without it).
  CleanPlateOptions options;
  options.camera_height_m = SceneOptions{}.camera_height;
  // How much of it frames 0.5-5 m away saw depends on the walk; what they saw is the scene.
  int filled_px = 0;
  for (int k : {60, 100}) {
    const CleanPlate without = clean_plate(walk.path, k, frame, depth, {}, options);
    const CleanPlate with = clean_plate(walk.path, k, frame, depth, rig, options);
    const cv::Mat& truth = walk.rendered(k).rgb;
    const cv::Mat filled = with.rig_filled & walk.patch;
    filled_px += cv::countNonZero(filled);
    const double before = test::masked_psnr(without.image, truth, walk.patch),
                 after = test::masked_psnr(with.image, truth, walk.patch),
                 where_filled = test::masked_psnr(with.image, truth, filled);
    std::printf(
        "keyframe %d: operator %.1f dB without the rig found, %.1f dB with it (%.0f %% filled, at %.1f dB)\n",
        k, before, after, 100.0 * cv::countNonZero(filled) / cv::countNonZero(walk.patch), where_filled);
    EXPECT_GE(where_filled, 23.0);
    EXPECT_GE(after, before - 0.5);
    // Nothing else of the keyframe is worse for it.
    EXPECT_GE(test::masked_psnr(with.image, truth, ~walk.patch),
              test::masked_psnr(without.image, truth, ~walk.patch) - 0.5);
  }
  EXPECT_GT(filled_px, cv::countNonZero(walk.patch));  // over half of it, over the two keyframes
}

TEST(RigFromGeometry, NoStillnessKeepsTheRigGivenAndOptionsAreChecked) {
  CameraPath path;
  for (int i = 0; i < 5; ++i) {
    PathFrame f;
    f.index = i;
    f.x = 0.2 * i;
    path.frames.push_back(f);
  }
  cv::Mat given = cv::Mat::zeros(32, 64, CV_8U);
  given(cv::Rect(0, 20, 10, 12)).setTo(255);
  auto frame = [](int) { return cv::Mat(32, 64, CV_8UC3, cv::Scalar::all(100)); };
  auto depth = [](int) { return cv::Mat(32, 64, CV_32F, cv::Scalar(3.0f)); };
  const cv::Mat kept = rig_from_geometry(path, frame, depth, given, CaptureStillness{});
  EXPECT_EQ(cv::countNonZero(kept != given), 0);
  EXPECT_TRUE(rig_from_geometry(path, frame, depth, {}, CaptureStillness{}).empty());
  // A frame that is not a colour image is an error naming it, not a crash.
  CaptureStillness still;
  still.median = cv::Mat(32, 64, CV_8UC3, cv::Scalar::all(100));
  still.share = cv::Mat(32, 64, CV_8U, cv::Scalar(255));
  still.frames = 8;
  auto grey = [](int) { return cv::Mat(32, 64, CV_8U, cv::Scalar(100)); };
  try {
    rig_from_geometry(path, grey, depth, {}, still);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not a colour image"), std::string::npos) << e.what();
  }
  // No depth anywhere: nothing to compare, the rig given is kept.
  const cv::Mat no_depth = rig_from_geometry(
      path, frame, [](int) { return cv::Mat(); }, given, still);
  EXPECT_EQ(cv::countNonZero(no_depth != given), 0);
  RigFromGeometryOptions o;
  o.max_baseline_m = o.min_baseline_m;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.max_agree_share = 1.0;
  EXPECT_THROW(o.check(), Error);
}

}  // namespace
}  // namespace plenopath
