#pragma once
// Inside FrameSource: its state and the backend interface, shared by frame_source.cpp (folders, videos,
// generators) and multi_head_capture.cpp. Not for use outside processing/frame_source*.cpp.
#include <memory>
#include <string>
#include <vector>

#include "model/error.h"
#include "processing/capture/frame_source.h"

namespace plenopath {
namespace frame_source_detail {

// Any decoded image -> 8-bit BGR: grey and alpha handled, 16-bit scaled, float (EXR) clamped and
// gamma-encoded.
cv::Mat to_bgr8(const cv::Mat& image);
cv::Mat shrink_to_width(const cv::Mat& image, int max_width);

// Where frames come from. read() must be thread-safe.
struct Backend {
  virtual ~Backend() = default;
  virtual cv::Mat read(int i) = 0;
  virtual cv::Mat read_thumbnail(int i, int max_width) { return shrink_to_width(read(i), max_width); }
};

}  // namespace frame_source_detail

struct FrameSource::Impl {
  CaptureKind kind = CaptureKind::kNone;
  std::string source;
  FrameSourceOptions options;
  int width = 0, height = 0;
  double frame_rate = 30.0;
  int head_count = 0;              // multi-head captures: number of heads, else 0
  std::vector<std::string> names;  // per kept frame
  std::vector<long long> numbers;  // per kept frame: number in the name / video frame number (-1)
  std::vector<double> timestamps;  // per kept frame
  std::vector<SkippedFrame> skipped;
  std::vector<std::string> depth_names;  // per kept frame, "" if none
  int depth_matches = 0;
  std::unique_ptr<frame_source_detail::Backend> backend;

  void check_index(int i) const {
    if (i < 0 || i >= static_cast<int>(names.size()))
      throw file_error(source, "frame index " + std::to_string(i) + " is out of range (0.." +
                                   std::to_string(static_cast<long long>(names.size()) - 1) + ")");
  }
};

namespace frame_source_detail {
// Matches options.depth_folder's files to impl's frames (by stem, else by number).
void match_depth(FrameSource::Impl& impl);
}  // namespace frame_source_detail

}  // namespace plenopath
