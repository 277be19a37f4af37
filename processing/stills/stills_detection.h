#pragma once
// Telling still panoramas from video frames (issue 20), so that `plenopath track` on a folder of tripod
// stills switches to the stills pipeline by itself. The video tracker follows corners from frame to frame
// with KLT; the decision asks exactly that: on a few consecutive pairs spread over the capture, the share
// of corners that KLT follows there and back (forward-backward error under a pixel). Video frames a few
// centimetres apart keep most of them (0.8-1.0 on the renders); stills metres apart at unrelated headings
// keep almost none (under 0.1). Below min_followed_fraction (median over the pairs) the capture is stills.
// A folder of fewer than min_frames images is not judged (it is tracked unless the author says --stills):
// a handful of panoramas says too little, and tests of the tracker use such tiny captures.
// Timestamps are not used: a folder of frames extracted from a video carries no capture times, and
// stills copied off a camera often lose theirs.
#include <functional>
#include <opencv2/core.hpp>
#include <string>

namespace plenopath {

struct StillsDetectionOptions {
  int min_frames = 5;                   // fewer frames: not judged, not stills
  int sample_pairs = 6;                 // consecutive pairs looked at, spread evenly over the capture
  int work_width = 512;                 // frames are shrunk to this width first
  int corners = 400;                    // corners sought in the first frame of a pair
  double max_fb_error_px = 1.0;         // a corner is followed when it comes back this close
  double min_followed_fraction = 0.35;  // median share of followed corners below this: stills
  void check() const;                   // throws Error naming the bad field
};

struct StillsDetection {
  bool stills = false;
  double followed_fraction = 1.0;  // median over the pairs looked at
  int pairs = 0;                   // pairs looked at
  std::string reason;              // one sentence for the user
};

// read(i): frame i (BGR or grey equirectangular).
StillsDetection detect_stills(int count, const std::function<cv::Mat(int)>& read,
                              const StillsDetectionOptions& options = {});

}  // namespace plenopath
