// The exposure gain between two frames against hand-made truths: a known gain per channel, with much of the
// image showing something else in one of them.
#include "processing/cleanplate/exposure_gain.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

namespace plenopath {
namespace {

// A textured key image: grey levels 60-200 in each channel, a little colour.
cv::Mat textured_key() {
  cv::Mat key(256, 512, CV_8UC3);
  cv::RNG rng(7);
  for (int v = 0; v < key.rows; ++v)
    for (int u = 0; u < key.cols; ++u) {
      const int base = 60 + ((u / 9 + v / 7) * 37) % 140;
      key.at<cv::Vec3b>(v, u) =
          cv::Vec3b(cv::saturate_cast<uchar>(base + rng.uniform(-6, 6)), cv::saturate_cast<uchar>(base + 10),
                    cv::saturate_cast<uchar>(base - 8));
    }
  return key;
}

TEST(ExposureGain, AKnownGainIsFoundThoughMuchOfTheImageShowsSomethingElse) {
  const cv::Mat key = textured_key();
  // The neighbour: the key's scene 20 % brighter in blue and green, 10 % in red ...
  const cv::Scalar truth(1 / 1.2, 1 / 1.2, 1 / 1.1);
  cv::Mat neighbour;
  cv::multiply(key, cv::Scalar(1.2, 1.2, 1.1), neighbour);
  // ... with 55 % of its pixels showing a dark green shirt where the key sees the brighter scene (the
  // neighbour's own operator, warped over the keyframe's view of the walls).
  neighbour(cv::Rect(0, 0, 282, 256)).setTo(cv::Scalar(50, 90, 40));
  const cv::Mat valid(key.size(), CV_8U, cv::Scalar(255));
  const cv::Scalar gain = exposure_gain(key, neighbour, valid, {});
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(gain[ch], truth[ch], 0.01) << "channel " << ch;
  // Only where `where` says, and only where the sample is valid: the scene half alone gives the same.
  cv::Mat where = cv::Mat::zeros(key.size(), CV_8U);
  where(cv::Rect(282, 0, 230, 256)).setTo(255);
  const cv::Scalar within = exposure_gain(key, neighbour, valid, where);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(within[ch], truth[ch], 0.01) << "channel " << ch;
}

TEST(ExposureGain, TooFewPixelsOrNoChangeGiveOne) {
  const cv::Mat key = textured_key();
  const cv::Mat valid(key.size(), CV_8U, cv::Scalar(255));
  EXPECT_EQ(exposure_gain(key, key, valid, {}), cv::Scalar::all(1));
  cv::Mat few = cv::Mat::zeros(key.size(), CV_8U);
  few(cv::Rect(0, 0, 30, 30)).setTo(255);  // 100 pixels on the grid
  cv::Mat brighter;
  cv::multiply(key, cv::Scalar::all(1.3), brighter);
  EXPECT_EQ(exposure_gain(key, brighter, few, {}), cv::Scalar::all(1));
  // Clipped and dark pixels are left out: a saturated neighbour compares nowhere.
  const cv::Mat white(key.size(), CV_8UC3, cv::Scalar::all(255));
  EXPECT_EQ(exposure_gain(key, white, valid, {}), cv::Scalar::all(1));
}

}  // namespace
}  // namespace plenopath
