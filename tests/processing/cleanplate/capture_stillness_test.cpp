// What stays in the same pixels over a capture: the operator and trolley of the project's renderer, against
// the same walk rendered without them (their pixels known exactly).
#include "processing/cleanplate/capture_stillness.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/cleanplate/masked_psnr.h"

namespace plenopath {
namespace {

TEST(CaptureStillness, TheOperatorStaysAndTheSceneDoesNot) {
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan);
  AutoWalkOptions walk;
  walk.max_frames = 120;
  const CameraPath path = auto_walk(plan, walk);
  RenderOptions with_rig;
  with_rig.width = 512;
  with_rig.height = 256;
  with_rig.depth = false;
  with_rig.trolley = with_rig.operator_person = true;
  RenderOptions without = with_rig;
  without.trolley = without.operator_person = false;
  auto frame = [&](int k) { return render_panorama(scene, path.frames[k], with_rig).rgb; };
  const CaptureStillness still = capture_stillness(frame, static_cast<int>(path.size()));
  ASSERT_FALSE(still.empty());
  EXPECT_EQ(still.frames, 32);
  ASSERT_EQ(still.median.cols, 256);
  // The rig's pixels in frame 0, away from its outline (the operator sways), at the working width.
  cv::Mat rig = test::differing_pixels(frame(0), render_panorama(scene, path.frames[0], without).rgb, 8);
  cv::resize(rig, rig, still.share.size(), 0, 0, cv::INTER_AREA);
  const cv::Mat inner = rig > 250, scene_pixels = rig == 0;
  ASSERT_GT(cv::countNonZero(inner), 200);
  const double rig_share = cv::mean(still.share, inner)[0] / 255,
               scene_share = cv::mean(still.share, scene_pixels)[0] / 255;
  std::printf("share of frames at the median: rig %.2f, scene %.2f\n", rig_share, scene_share);
  EXPECT_GT(rig_share, 0.85);
  EXPECT_LT(scene_share, 0.5);
  // The keyframe's own rig pixels agree with the median; its scene does far less often.
  const cv::Mat key = at_stillness_scale(frame(60), still);
  cv::Mat difference;
  cv::absdiff(key, still.median, difference);
  cv::Mat close = difference.reshape(1, difference.rows * difference.cols);
  cv::reduce(close, close, 1, cv::REDUCE_MAX);
  close = close.reshape(1, difference.rows) <= still.tolerance;
  EXPECT_GT(cv::countNonZero(close & inner), 0.8 * cv::countNonZero(inner));
}

TEST(CaptureStillness, FewFramesGiveNothingAndBadInputIsNamed) {
  auto grey = [](int) { return cv::Mat(64, 128, CV_8UC3, cv::Scalar(90, 90, 90)); };
  EXPECT_TRUE(capture_stillness(grey, 7).empty());
  CaptureStillnessOptions o;
  o.frames = 4;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.width = 31;
  EXPECT_THROW(o.check(), Error);
  auto changing = [](int k) { return cv::Mat(k < 5 ? 64 : 32, 128, CV_8UC3, cv::Scalar::all(90)); };
  EXPECT_THROW(capture_stillness(changing, 40), Error);
  auto bad = [](int) { return cv::Mat(64, 128, CV_8U, cv::Scalar(90)); };
  EXPECT_THROW(capture_stillness(bad, 40), Error);
}

}  // namespace
}  // namespace plenopath
