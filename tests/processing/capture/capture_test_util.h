#pragma once
// Helpers for the capture import tests: temporary folders and frames that carry their own number, drawn as
// eight wide black/white stripes (bit k of the number in stripe k) on a tinted background, so that every
// decoded frame - even through lossy video codecs - tells which frame it is.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

namespace plenopath::test {

class TempFolder {
 public:
  TempFolder() {
    static std::atomic<int> counter{0};
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = std::filesystem::temp_directory_path() /
            ("plenopath_capture_" + std::to_string(stamp) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

constexpr int kStripes = 8;

// A w x h frame showing `number` (0..2^stripes - 1) in stripes across its upper half.
inline cv::Mat numbered_frame(int number, int width = 256, int height = 128, int stripes = kStripes) {
  cv::Mat frame(height, width, CV_8UC3, cv::Scalar(60, 90, 120));
  const int stripe = width / stripes;
  for (int k = 0; k < stripes; ++k) {
    const bool on = (number >> k) & 1;
    cv::rectangle(frame, cv::Rect(k * stripe, 0, stripe, height / 2),
                  on ? cv::Scalar(255, 255, 255) : cv::Scalar(0, 0, 0), cv::FILLED);
  }
  return frame;
}

// Reads the number back (the stripes' centres, well away from block edges).
inline int decode_frame_number(const cv::Mat& frame, int stripes = kStripes) {
  const int stripe = frame.cols / stripes;
  int number = 0;
  for (int k = 0; k < stripes; ++k) {
    const cv::Rect centre(k * stripe + stripe / 4, frame.rows / 8, stripe / 2, frame.rows / 4);
    const cv::Scalar mean = cv::mean(frame(centre));
    if ((mean[0] + mean[1] + mean[2]) / 3.0 > 128.0) number |= 1 << k;
  }
  return number;
}

}  // namespace plenopath::test
