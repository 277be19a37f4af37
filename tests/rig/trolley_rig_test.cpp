// The trolley and its operator in every frame: they cover the same pixels with the same colours wherever the
// camera is (without tilt), the trolley stays put under tilt while the operator (upright) moves by it, and
// they sit where their hand-placed geometry says (the head behind the lens, the mast at the nadir).
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "rig/spherical.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

// Pixels where the rig is nearer than the scene: the depth differs from the render without it.
cv::Mat rig_pixels(const SyntheticScene& scene, const PathFrame& pose, RenderOptions with) {
  RenderOptions without = with;
  without.trolley = without.operator_person = false;
  const cv::Mat a = render_panorama(scene, pose, with).depth, b = render_panorama(scene, pose, without).depth;
  cv::Mat mask;
  cv::compare(a, b, mask, cv::CMP_NE);
  return mask;
}

// Poses at least a metre from any wall behind, in different rooms and headings.
const PathFrame kPoses[] = {
    {0, "", 4.0, 7.5, 0.3, 1.0, kFrameOk, ""},
    {40, "", 11.0, 10.0, -2.0, 1.0, kFrameOk, ""},
    {95, "", 12.6, 2.6, 3.1, 1.0, kFrameOk, ""},
};

TEST(TrolleyRig, OccupiesTheSameRegionWithTheSameColoursInEveryFrame) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions options;
  options.width = 512;
  options.height = 256;
  options.trolley = true;
  options.operator_person = true;
  const cv::Mat first = rig_pixels(scene, kPoses[0], options);
  const double share = cv::countNonZero(first) / double(first.total());
  EXPECT_GT(share, 0.04);
  EXPECT_LT(share, 0.25);
  const cv::Mat first_rgb = render_panorama(scene, kPoses[0], options).rgb;
  for (const PathFrame& pose : kPoses) {
    const cv::Mat mask = rig_pixels(scene, pose, options);
    cv::Mat differ;
    cv::bitwise_xor(mask, first, differ);
    EXPECT_EQ(cv::countNonZero(differ), 0) << "frame " << pose.index;
    const cv::Mat rgb = render_panorama(scene, pose, options).rgb;
    EXPECT_EQ(cv::norm(rgb, first_rgb, cv::NORM_INF, first), 0.0) << "frame " << pose.index;
  }
  // The head: a 0.11 m sphere 0.7 m behind the lens, 2 cm above it (azimuth 180 deg, elevation 1.6 deg).
  const Eigen::Vector2d head = bearing_to_equirect(Eigen::Vector3d(-0.7, 0.0, 0.02), 512, 256);
  EXPECT_TRUE(first.at<uchar>(static_cast<int>(head.y()), static_cast<int>(head.x()) % 512));
  // 9 deg (0.11 m at 0.7 m) above the head's centre is beyond the head.
  const Eigen::Vector2d above =
      bearing_to_equirect(Eigen::Vector3d(-0.7, 0.0, 0.02 + 0.7 * std::tan(0.16)), 512, 256);
  EXPECT_FALSE(first.at<uchar>(static_cast<int>(above.y()), static_cast<int>(above.x()) % 512));
  // The mast: the whole bottom row looks straight down it. Straight ahead at the horizon: the scene.
  EXPECT_EQ(cv::countNonZero(first.row(255)), 512);
  EXPECT_FALSE(first.at<uchar>(128, 256));
  // The depth at the bottom row: the camera mount's top face, 5 cm under the lens, seen almost straight down.
  const cv::Mat depth = render_panorama(scene, kPoses[0], options).depth;
  EXPECT_NEAR(depth.at<float>(255, 100), 0.05, 0.0005);
}

TEST(TrolleyRig, TheTrolleyTiltsWithTheCameraTheOperatorDoesNot) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions options;
  options.width = 512;
  options.height = 256;
  options.trolley = true;
  const cv::Mat level = rig_pixels(scene, kPoses[0], options);
  RenderOptions tilted = options;
  tilted.pitch_deg = 2.0;
  tilted.roll_deg = -1.5;
  cv::Mat differ;
  cv::bitwise_xor(level, rig_pixels(scene, kPoses[1], tilted), differ);
  EXPECT_EQ(cv::countNonZero(differ), 0);  // rigid with the camera
  // The operator stays upright: under a 2 deg pitch the head moves up in the image by 2 deg (behind the
  // camera, a nose-up pitch raises what is behind), about 2.8 rows at 256.
  RenderOptions person = options;
  person.trolley = false;
  person.operator_person = true;
  RenderOptions person_tilted = person;
  person_tilted.pitch_deg = 2.0;
  auto top_row = [](const cv::Mat& mask, int u) {
    for (int v = 0; v < mask.rows; ++v)
      if (mask.at<uchar>(v, u)) return v;
    return -1;
  };
  const cv::Mat a = rig_pixels(scene, kPoses[0], person), b = rig_pixels(scene, kPoses[0], person_tilted);
  const int u = 0;  // azimuth -180: straight behind
  ASSERT_GT(top_row(a, u), 0);
  EXPECT_NEAR(top_row(a, u) - top_row(b, u), 2.0 * 256 / 180.0, 1.01);
}

}  // namespace
}  // namespace plenopath
