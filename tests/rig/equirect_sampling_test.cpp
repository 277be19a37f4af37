#include "rig/equirect_sampling.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "model/error.h"

namespace plenopath {
namespace {

TEST(EquirectSampling, PixelCentresReturnPixelValues) {
  cv::Mat img(4, 8, CV_32FC1);
  for (int v = 0; v < 4; ++v)
    for (int u = 0; u < 8; ++u) img.at<float>(v, u) = float(10 * v + u);
  float out = 0;
  for (int v = 0; v < 4; ++v)
    for (int u = 0; u < 8; ++u) {
      sample_equirect_bilinear(img, u + 0.5, v + 0.5, &out);
      EXPECT_FLOAT_EQ(out, 10 * v + u);
    }
}

TEST(EquirectSampling, WrapsAcrossTheSeam) {
  cv::Mat img(2, 8, CV_8UC3, cv::Scalar(0, 0, 0));
  img.at<cv::Vec3b>(0, 0) = {200, 100, 0};
  img.at<cv::Vec3b>(0, 7) = {0, 100, 200};
  // x = 0 lies halfway between the last column's centre (7.5) and the first's (0.5 + 8).
  const cv::Vec3f mid = sample_equirect_bilinear_bgr(img, 0.0, 0.5);
  EXPECT_FLOAT_EQ(mid[0], 100);
  EXPECT_FLOAT_EQ(mid[1], 100);
  EXPECT_FLOAT_EQ(mid[2], 100);
  // The same point reached from the other side, and one turn further.
  const cv::Vec3f same = sample_equirect_bilinear_bgr(img, 8.0, 0.5);
  const cv::Vec3f turn = sample_equirect_bilinear_bgr(img, -8.0, 0.5);
  EXPECT_EQ(mid, same);
  EXPECT_EQ(mid, turn);
}

TEST(EquirectSampling, ClampsAtThePoles) {
  cv::Mat img(2, 4, CV_32FC1, cv::Scalar(5));
  img.row(1).setTo(9);
  float out = 0;
  sample_equirect_bilinear(img, 1.0, 0.0, &out);
  EXPECT_FLOAT_EQ(out, 5);
  sample_equirect_bilinear(img, 1.0, 2.0, &out);
  EXPECT_FLOAT_EQ(out, 9);
}

TEST(EquirectSampling, RejectsBadInput) {
  float out = 0;
  EXPECT_THROW(sample_equirect_bilinear(cv::Mat(), 0, 0, &out), Error);
  EXPECT_THROW(sample_equirect_bilinear(cv::Mat(2, 4, CV_32FC1), NAN, 0, &out), Error);
  EXPECT_THROW(sample_equirect_bilinear(cv::Mat(2, 4, CV_64FC1), 0, 0, &out), Error);
}

}  // namespace
}  // namespace plenopath
