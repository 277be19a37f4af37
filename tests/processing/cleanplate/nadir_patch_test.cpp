// The nadir patch against hand-computed truth: a region on a known background, a logo of known colours.
#include "processing/cleanplate/nadir_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "tests/processing/cleanplate/masked_psnr.h"

namespace plenopath {
namespace {

// A panorama whose lower half is a smooth floor (grey rising towards the horizon) and upper half a wall
// texture; the region is the bottom rows (a trolley's footprint) plus a blob behind the camera (the seam).
struct Scene {
  cv::Mat image = cv::Mat(512, 1024, CV_8UC3);
  cv::Mat region = cv::Mat::zeros(512, 1024, CV_8U);
  Scene() {
    for (int v = 0; v < image.rows; ++v)
      for (int u = 0; u < image.cols; ++u)
        image.at<cv::Vec3b>(v, u) = v < 256
                                        ? cv::Vec3b(((u / 16 + v / 16) % 2) ? 200 : 60, 120, 90)
                                        : cv::Vec3b(static_cast<std::uint8_t>(40 + (511 - v) / 4), 80, 100);
    region.rowRange(470, 512).setTo(255);
    cv::circle(region, {0, 400}, 15, cv::Scalar(255), cv::FILLED);
    cv::circle(region, {1023, 400}, 15, cv::Scalar(255), cv::FILLED);
    // The rig itself: something bright that must not survive.
    image.setTo(cv::Scalar(255, 255, 255), region);
  }
};

TEST(NadirPatch, BlurredFillCarriesTheSurroundingsIn) {
  Scene scene;
  NadirPatchOptions options;
  const cv::Mat out = apply_nadir_patch(scene.image, scene.region, options);
  // The floor's grey at the region's rows is 40 + (511 - v) / 4 in blue: the fill must be close to what lies
  // round it (the rows just above), never the rig's white.
  double worst = 0;
  for (int v = 470; v < 512; ++v)
    for (int u = 0; u < 1024; u += 7) {
      const cv::Vec3b c = out.at<cv::Vec3b>(v, u);
      worst = std::max(
          {worst, std::abs(c[0] - (40.0 + (511 - 469) / 4)), std::abs(c[1] - 80.0), std::abs(c[2] - 100.0)});
    }
  EXPECT_LT(worst, 12.0);
  // Across the seam too: the blob at column 0 and 1023 is filled like the floor round it.
  const cv::Vec3b seam = out.at<cv::Vec3b>(400, 0);
  EXPECT_NEAR(seam[0], 40 + (511 - 400) / 4, 6);
  EXPECT_NEAR(seam[1], 80, 6);
  // Away from the region (beyond the feather), nothing changes.
  cv::Mat away;
  cv::dilate(scene.region, away, cv::Mat(), cv::Point(-1, -1), 6);
  EXPECT_TRUE(std::isinf(test::masked_psnr(out, scene.image, ~away)));
}

TEST(NadirPatch, AnImageIsADiscRoundTheNadirWithItsTopForward) {
  Scene scene;
  NadirPatchOptions options;
  options.kind = NadirPatch::kImage;
  // The logo: red top half, blue bottom half, a green centre dot.
  options.image = cv::Mat(200, 200, CV_8UC3, cv::Scalar(0, 0, 255));
  options.image.rowRange(100, 200).setTo(cv::Scalar(255, 0, 0));
  cv::circle(options.image, {100, 100}, 12, cv::Scalar(0, 255, 0), cv::FILLED);
  const double radius = nadir_disc_radius_deg(scene.region, options);
  // The bottom 42 rows of 512 reach 42 * 180 / 512 = 14.8 deg from the nadir; the blob behind the camera
  // (rows 385-415) lies 34-45 deg from it, under 1 % of the region's pixels below 40 deg: the disc covers
  // the footprint, not the blob.
  EXPECT_GT(radius, 14.7);
  EXPECT_LT(radius, 17.0);
  const cv::Mat out = apply_nadir_patch(scene.image, scene.region, options);
  // At the nadir row, looking forward (centre column) is the logo's top: red; looking back: blue; the
  // centre dot fills the last rows all round.
  const cv::Vec3b forward = out.at<cv::Vec3b>(500, 512), back = out.at<cv::Vec3b>(500, 2);
  EXPECT_GT(forward[2], 200);
  EXPECT_LT(forward[0], 50);
  EXPECT_GT(back[0], 200);
  EXPECT_LT(back[2], 50);
  EXPECT_GT(out.at<cv::Vec3b>(511, 300)[1], 200);
  // The blob outside the disc gets the blurred fill, not the rig's white nor the logo.
  const cv::Vec3b blob = out.at<cv::Vec3b>(400, 5);
  EXPECT_NEAR(blob[1], 80, 8);
}

TEST(NadirPatch, NoneAndAnEmptyRegionLeaveTheImage) {
  Scene scene;
  NadirPatchOptions none;
  none.kind = NadirPatch::kNone;
  EXPECT_TRUE(
      std::isinf(test::masked_psnr(apply_nadir_patch(scene.image, scene.region, none), scene.image, {})));
  EXPECT_TRUE(std::isinf(test::masked_psnr(apply_nadir_patch(scene.image, {}, {}), scene.image, {})));
}

TEST(NadirPatch, BadInputIsAClearError) {
  Scene scene;
  NadirPatchOptions image_without_picture;
  image_without_picture.kind = NadirPatch::kImage;
  EXPECT_THROW(apply_nadir_patch(scene.image, scene.region, image_without_picture), Error);
  EXPECT_THROW(apply_nadir_patch(scene.image, cv::Mat(10, 10, CV_8U), {}), Error);
  NadirPatchOptions bad;
  bad.max_image_radius_deg = 90;
  EXPECT_THROW(bad.check(), Error);
}

}  // namespace
}  // namespace plenopath
