#pragma once
// Inside FrameSource: its state and the backend interface, shared by frame_source.cpp (generators),
// frame_source_folder.cpp, frame_source_video.cpp and multi_head_capture.cpp. Not for use outside
// processing/frame_source*.cpp.
#include <filesystem>
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

// File names (frame_source.cpp).
std::string lower(std::string s);
bool is_frame_extension(const std::string& ext);
bool is_depth_extension(const std::string& ext);
// The last run of digits in a file stem, as a number (-1 if none or absurdly long); `pattern` gets the stem
// with that run replaced by '#', `digits` its length.
long long trailing_number(const std::string& stem, std::string* pattern = nullptr, int* digits = nullptr);
std::string stem_of(const std::string& name);
// Throws naming `where` unless the frames have a size and, when required, are 2:1.
void check_aspect(int width, int height, bool require_2to1, const std::string& where);

// The backends: a folder of frames (frame_source_folder.cpp), optionally only `given_names` (a project's
// list); a video (frame_source_video.cpp).
std::unique_ptr<FrameSource::Impl> open_folder(const std::filesystem::path& folder,
                                               const FrameSourceOptions& options,
                                               const std::vector<std::string>* given_names);
std::unique_ptr<FrameSource::Impl> open_video(const std::string& path, const FrameSourceOptions& options);
bool looks_like_video(const std::string& path);
}  // namespace frame_source_detail

}  // namespace plenopath
