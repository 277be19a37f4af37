#pragma once
// One conversion of a frame to single-channel grey, shared by the trackers and the image measures.
#include <opencv2/core.hpp>
#include <string>

namespace plenopath {

// `frame` as one channel of its own depth (BGR and BGRA by luma; grey as is, not copied). Throws Error
// "<who>: empty frame" or "<who>: expected a 1-, 3- or 4-channel frame".
cv::Mat grey_image(const cv::Mat& frame, const std::string& who);

// grey_image() at 8 bits (other depths converted as values, as OpenCV's convertTo does).
cv::Mat grey_image_8u(const cv::Mat& frame, const std::string& who);

// `grey` shrunk by area averaging to `width` x width/2 when 0 < width < its width; otherwise as is.
cv::Mat equirect_at_width(const cv::Mat& grey, int width);

}  // namespace plenopath
