#pragma once
// How far apart two BGR colours are, as the clean plate and the rig finder judge it: the largest difference
// over the channels, in grey levels.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <opencv2/core.hpp>

namespace plenopath {

inline int max_channel_difference(const cv::Vec3b& a, const cv::Vec3b& b) {
  int difference = 0;
  for (int ch = 0; ch < 3; ++ch) difference = std::max(difference, std::abs(int(a[ch]) - int(b[ch])));
  return difference;
}

// `b` brought to `a`'s exposure by a gain per channel first (rounded to grey levels).
inline int max_channel_difference(const cv::Vec3b& a, const cv::Vec3b& b, const cv::Scalar& gain) {
  int difference = 0;
  for (int ch = 0; ch < 3; ++ch)
    difference = std::max(difference, std::abs(int(a[ch]) - int(std::lround(b[ch] * gain[ch]))));
  return difference;
}

}  // namespace plenopath
