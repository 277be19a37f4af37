#pragma once
// PSNR of two 8-bit colour images over the pixels of a mask, for the clean-plate tests and bench.
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace plenopath::test {

// PSNR (dB) of `a` against `b` over the non-zero pixels of `mask` (every pixel when it is empty); infinity
// when they are equal there.
inline double masked_psnr(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  diff.convertTo(diff, CV_64FC3);
  diff = diff.mul(diff);
  if (!mask.empty()) diff.setTo(0, ~mask);
  const cv::Scalar sum = cv::sum(diff);
  const double n = 3.0 * (mask.empty() ? double(a.total()) : double(cv::countNonZero(mask)));
  const double mse = (sum[0] + sum[1] + sum[2]) / std::max(1.0, n);
  return mse <= 0 ? INFINITY : 10 * std::log10(255.0 * 255.0 / mse);
}

// The same, 99 dB standing for identical (JSON holds no infinity), and 99 dB for an empty mask.
inline double masked_psnr_capped(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  if (!mask.empty() && cv::countNonZero(mask) == 0) return 99.0;
  return std::min(99.0, masked_psnr(a, b, mask));
}

// 255 where two colour images differ by more than `threshold` grey levels (the grey of their difference):
// where the people or the rig are, against a render without them.
inline cv::Mat differing_pixels(const cv::Mat& a, const cv::Mat& b, int threshold = 8) {
  cv::Mat diff, mask;
  cv::absdiff(a, b, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  cv::threshold(diff, mask, threshold, 255, cv::THRESH_BINARY);
  return mask;
}

}  // namespace plenopath::test
