#pragma once
// Writes a capture's frames (any FrameSource) to a video file through OpenCV's FFmpeg backend: for turning a
// rendered or stitched image sequence into the 360° video a camera would have produced, and for tests.
#include <functional>
#include <string>

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

// Throws Error naming the file when the container/codec cannot be written. `progress(done, total)` may
// return false to stop early (the video then holds the frames written so far).
VideoEncodeResult encode_video(FrameSource& source, const std::string& file,
                               const VideoEncodeOptions& options = {},
                               const std::function<bool(int, int)>& progress = {});

}  // namespace plenopath
