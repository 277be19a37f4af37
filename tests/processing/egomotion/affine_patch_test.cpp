// Affine patch alignment against warps made independently with cv::warpAffine (known centre and deformation).
#include "processing/egomotion/affine_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <vector>

#include "model/error.h"

namespace plenopath {
namespace {

// A texture with corners at several scales (blurred noise).
cv::Mat texture(int seed) {
  cv::RNG rng(seed);
  cv::Mat noise(240, 320, CV_32F);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::Mat blurred;
  cv::GaussianBlur(noise, blurred, cv::Size(0, 0), 2.0);
  cv::normalize(blurred, blurred, 0, 255, cv::NORM_MINMAX);
  cv::Mat out;
  blurred.convertTo(out, CV_8U);
  return out;
}

// The image whose content at `from` (in `source`) appears at `to`, deformed by `linear`, with gain and bias.
cv::Mat warped(const cv::Mat& source, cv::Point2d from, cv::Point2d to, const cv::Matx22d& linear,
               double gain, double bias) {
  const cv::Matx22d inv = linear.inv();
  const cv::Vec2d offset = cv::Vec2d(from.x, from.y) - inv * cv::Vec2d(to.x, to.y);
  const cv::Matx23d map(inv(0, 0), inv(0, 1), offset[0], inv(1, 0), inv(1, 1), offset[1]);
  cv::Mat out;
  cv::warpAffine(source, out, map, source.size(), cv::INTER_CUBIC | cv::WARP_INVERSE_MAP, cv::BORDER_REFLECT);
  out.convertTo(out, CV_8U, gain, bias);
  return out;
}

cv::Matx22d similarity(double scale, double angle_deg, double shear = 0.0) {
  const double a = angle_deg * M_PI / 180.0;
  return cv::Matx22d(scale * std::cos(a), -scale * std::sin(a), scale * std::sin(a), scale * std::cos(a)) *
         cv::Matx22d(1.0, shear, 0.0, 1.0);
}

TEST(AffinePatch, RecoversTheCentreOfADeformedPatch) {
  const cv::Mat first = texture(3);
  AffinePatchOptions options;
  int aligned = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const cv::Point2d from(100.3 + 7 * trial, 90.7 + 3 * trial);
    const cv::Point2d to = from + cv::Point2d(2.37 - 0.2 * trial, -1.61 + 0.1 * trial);
    const cv::Matx22d linear = similarity(1.0 + 0.004 * trial, 0.5 * trial - 4, 0.002 * trial);
    const cv::Mat second = warped(first, from, to, linear, 0.9, 12.0);
    const AffinePatch patch = make_affine_patch(first, from, options);
    ASSERT_TRUE(patch.valid);
    AffineWarp warp;
    warp.centre = to + cv::Point2d(0.7, -0.5);  // where a translation tracker might leave it
    double residual = 0;
    ASSERT_TRUE(align_affine_patch(patch, second, &warp, options, &residual)) << "trial " << trial;
    // Bilinear sampling of template and frame at different sub-pixel phases leaves a few hundredths.
    EXPECT_LT(std::hypot(warp.centre.x - to.x, warp.centre.y - to.y), 0.05) << "trial " << trial;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) EXPECT_NEAR(warp.linear(i, j), linear(i, j), 0.01) << "trial " << trial;
    EXPECT_LT(residual, 0.1);
    ++aligned;
  }
  EXPECT_EQ(aligned, 20);
}

TEST(AffinePatch, ChainedFramesDoNotDrift) {
  // A patch growing by 3 % a frame for 15 frames (a wall being approached), its gradients off-centre in the
  // window: aligning each frame against the first patch keeps the centre within a few hundredths of a pixel,
  // while translation-only Lucas-Kanade from frame to frame (OpenCV's, same window) adds up its bias.
  const cv::Mat first = texture(5);
  AffinePatchOptions options;
  const cv::Point2d from(160.4, 120.2);
  const AffinePatch patch = make_affine_patch(first, from, options);
  ASSERT_TRUE(patch.valid);
  AffineWarp warp;
  warp.centre = from;
  std::vector<cv::Point2f> lk = {cv::Point2f(static_cast<float>(from.x), static_cast<float>(from.y))};
  cv::Mat previous = first;
  double affine_error = 0, lk_error = 0;
  for (int frame = 1; frame <= 15; ++frame) {
    const double scale = std::pow(1.03, frame);
    const cv::Point2d to = from + cv::Point2d(0.83 * frame, 0.21 * frame);
    const cv::Mat image = warped(first, from, to, similarity(scale, 0.3 * frame), 1.0, 0.0);
    warp.centre += cv::Point2d(0.83, 0.21);  // the previous position plus the true step (as from LK)
    ASSERT_TRUE(align_affine_patch(patch, image, &warp, options)) << "frame " << frame;
    affine_error = std::hypot(warp.centre.x - to.x, warp.centre.y - to.y);
    EXPECT_LT(affine_error, 0.05) << "frame " << frame;
    std::vector<cv::Point2f> next;
    std::vector<unsigned char> status;
    std::vector<float> error;
    cv::calcOpticalFlowPyrLK(previous, image, lk, next, status, error, cv::Size(21, 21), 3);
    ASSERT_TRUE(status[0]);
    lk = next;
    previous = image;
    lk_error = std::hypot(lk[0].x - to.x, lk[0].y - to.y);
  }
  EXPECT_LT(3 * affine_error, lk_error)
      << "affine " << affine_error << " px, Lucas-Kanade " << lk_error << " px";
}

TEST(AffinePatch, RefusesWhatItCannotAlign) {
  AffinePatchOptions options;
  const cv::Mat flat(100, 100, CV_8U, cv::Scalar(128));
  EXPECT_FALSE(make_affine_patch(flat, {50, 50}, options).valid);
  cv::Mat edge(100, 100, CV_8U, cv::Scalar(40));
  edge.colRange(50, 100).setTo(200);
  cv::GaussianBlur(edge, edge, cv::Size(0, 0), 1.5);
  EXPECT_FALSE(make_affine_patch(edge, {50, 50}, options).valid)
      << "a straight edge has no position along it";
  const cv::Mat first = texture(7);
  EXPECT_FALSE(make_affine_patch(first, {5, 5}, options).valid) << "too near the border";
  const AffinePatch patch = make_affine_patch(first, {150, 100}, options);
  ASSERT_TRUE(patch.valid);
  const cv::Mat other = texture(8);
  AffineWarp warp;
  warp.centre = {150, 100};
  EXPECT_FALSE(align_affine_patch(patch, other, &warp, options)) << "an unrelated image";
  AffinePatchOptions bad;
  bad.window_px = 20;
  EXPECT_THROW(bad.check(), Error);
}

}  // namespace
}  // namespace plenopath

namespace plenopath {
namespace {

TEST(AffinePatch, LinearStretchByHand) {
  const LinearStretch d = linear_stretch(cv::Matx22d(2.0, 0.0, 0.0, 0.5));
  EXPECT_NEAR(d.largest, 2.0, 1e-12);
  EXPECT_NEAR(d.smallest, 0.5, 1e-12);
  EXPECT_NEAR(d.rotation, 0.0, 1e-12);
  const double a = 30 * M_PI / 180;
  const LinearStretch r =
      linear_stretch(1.1 * cv::Matx22d(std::cos(a), -std::sin(a), std::sin(a), std::cos(a)));
  EXPECT_NEAR(r.largest, 1.1, 1e-12);
  EXPECT_NEAR(r.smallest, 1.1, 1e-12);
  EXPECT_NEAR(r.rotation, a, 1e-12);
  const LinearStretch shear =
      linear_stretch(cv::Matx22d(1.0, 1.0, 0.0, 1.0));  // singular values golden ratio
  EXPECT_NEAR(shear.largest, (1 + std::sqrt(5.0)) / 2, 1e-12);
  EXPECT_NEAR(shear.smallest, (std::sqrt(5.0) - 1) / 2, 1e-12);
}

}  // namespace
}  // namespace plenopath
