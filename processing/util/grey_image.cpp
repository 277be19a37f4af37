#include "processing/util/grey_image.h"

#include <opencv2/imgproc.hpp>

#include "model/error.h"

namespace plenopath {

cv::Mat grey_image(const cv::Mat& frame, const std::string& who) {
  if (frame.empty()) throw Error(who + ": empty frame");
  cv::Mat grey;
  switch (frame.channels()) {
    case 1:
      return frame;
    case 3:
      cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
      return grey;
    case 4:
      cv::cvtColor(frame, grey, cv::COLOR_BGRA2GRAY);
      return grey;
    default:
      throw Error(who + ": expected a 1-, 3- or 4-channel frame");
  }
}

cv::Mat grey_image_8u(const cv::Mat& frame, const std::string& who) {
  cv::Mat grey = grey_image(frame, who);
  if (grey.depth() != CV_8U) grey.convertTo(grey, CV_8U);
  return grey;
}

cv::Mat equirect_at_width(const cv::Mat& grey, int width) {
  if (width <= 0 || width >= grey.cols) return grey;
  cv::Mat small;
  cv::resize(grey, small, cv::Size(width, width / 2), 0, 0, cv::INTER_AREA);
  return small;
}

}  // namespace plenopath
