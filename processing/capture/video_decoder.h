#pragma once
// One video stream decoded frame-exactly through libavformat/libavcodec (FrameSource's video backend).
//
// Opening scans the stream's packets once (reading, not decoding) and records each frame's presentation
// time stamp (PTS); frame i is the i-th in presentation order and its time is its PTS. read(i) decodes on
// from where the decoder is when frame i lies ahead in the same group of pictures; otherwise it seeks to the
// keyframe at or before frame i and decodes forward to exactly that frame. A decoded frame is known by its
// PTS, never by counting, so seeking is exact with B-frames and open GOPs, unlike seeking by frame number
// through cv::VideoCapture (OpenCV #9053). When packets carry no usable PTS (AVI with B-frames, raw
// streams) the index is built by decoding every frame instead.
//
// Not thread-safe: FrameSource serialises the calls.
#include <memory>
#include <opencv2/core.hpp>
#include <string>

namespace plenopath {

struct VideoDecoderStats {
  long long frames_decoded = 0;  // frames the decoder produced, returned or not
  long long seeks = 0;           // seeks in the container
};

class VideoDecoder {
 public:
  // Opens the file's main video stream and indexes its frames; throws Error naming the file when it is not
  // a video, holds no video stream, or its codec cannot be decoded.
  explicit VideoDecoder(const std::string& path);
  ~VideoDecoder();
  VideoDecoder(const VideoDecoder&) = delete;
  VideoDecoder& operator=(const VideoDecoder&) = delete;

  const std::string& path() const;
  int frame_count() const;
  int width() const;  // from the stream header; the decoded frames tell the truth
  int height() const;
  double frame_rate() const;       // nominal frames per second as FFmpeg guesses it; 0 if unknown
  double time_s(int frame) const;  // the frame's PTS in seconds after frame 0's
  // What the container says it holds (0 = not said), and whether reading its packets stopped early: on a
  // read error, or with fewer packets than the container lists (a recording cut short).
  long long container_frame_count() const;
  bool packets_end_early() const;
  bool indexed_by_decoding() const;
  // Rebuilds the index from the frames that actually decode (slow: every frame is decoded). For files whose
  // packets promise frames the stream does not deliver (truncated or damaged files).
  void index_by_decoding();

  cv::Mat read(int frame);  // BGR 8-bit; throws Error naming the file and the frame
  const VideoDecoderStats& stats() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace plenopath
