#pragma once
// Writes a capture's frames (any FrameSource) to a video file through OpenCV's FFmpeg backend: for turning a
// rendered or stitched image sequence into the 360° video a camera would have produced, and for tests.
#include <functional>
#include <string>

#include "processing/util/progress.h"

namespace plenopath {

class FrameSource;

struct VideoEncodeOptions {
  std::string codec = "h264";  // h264, hevc, mp4v or mjpg
  double frame_rate = 0.0;     // frames per second; 0 = the source's rate
  void check() const;          // throws Error saying what is wrong
};

struct VideoEncodeResult {
  int frames_written = 0;
  int frames_failed = 0;  // frames the source could not read (left out of the video)
  std::string fourcc;
};

// Throws Error naming the file when the container/codec cannot be written. Reports per frame; a cancel
// ends it with Cancelled and removes the unfinished file.
VideoEncodeResult encode_video(FrameSource& source, const std::string& file,
                               const VideoEncodeOptions& options = {}, Progress& progress = null_progress());

}  // namespace plenopath
