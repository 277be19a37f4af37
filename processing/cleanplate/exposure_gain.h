#pragma once
// The gain that brings one frame to another's exposure, from the pixels both see (issue 24: a warped
// neighbour brought to the keyframe's exposure before the consensus and the rig fill). Many of the pixels
// compared may show different things in the two: a person, the operator in the neighbour where the keyframe
// sees a wall, a warp through the wrong depth. On the POV-Ray `people` walk the neighbour's operator covered
// so many of them that per-channel medians gave (1.20, 1.00, 1.25) where the truth was about 0.95 each:
// the frame came out pink. Here the gain is the most common brightness ratio (a histogram mode, which holds
// however many pixels disagree as long as they disagree in many ways), then per channel the median ratio
// over the pixels within 4 % of that brightness ratio (the same surface in both: the colour balance).
#include <opencv2/core.hpp>

namespace plenopath {

// `key`, `image`: CV_8UC3 of one size; `valid` (CV_8U): where `image` holds a sample; `where` (CV_8U, may be
// empty = everywhere): the pixels to compare. Pixels dark (<= 24) or clipped (>= 240) in either are left
// out; compared on a grid of every third pixel. Returns the per-channel gain (image * gain ~ key), clamped
// to [0.5, 2]; 1 when fewer than 200 pixels compare or no channel changes by more than 1 %.
cv::Scalar exposure_gain(const cv::Mat& key, const cv::Mat& image, const cv::Mat& valid,
                         const cv::Mat& where);

}  // namespace plenopath
