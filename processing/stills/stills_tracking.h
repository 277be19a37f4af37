#pragma once
// One road from a capture to a path for the command line and the studio alike: whether a capture is
// tracked as video (processing/egomotion) or solved as still panoramas (stills.h), and the stills' result
// in the tracker's shape, so that registration, anchors, keyframes and export treat both alike.
#include <functional>
#include <opencv2/core.hpp>
#include <string>

#include "processing/egomotion/egomotion.h"
#include "processing/stills/stills.h"
#include "processing/stills/stills_detection.h"

namespace plenopath {

struct StillsChoice {
  bool stills = false;
  bool detected = false;      // decided by detect_stills (otherwise by the author or the kind of capture)
  StillsDetection detection;  // when detected
  std::string reason;         // one sentence for the user when stills, e.g. "imported as still panoramas"
};

// marked_stills: the author said so (Capture::stills, `track --stills`); plain_folder: an image folder of
// panoramas (videos and rigs are never stills); automatic: judge a plain folder by detect_stills.
StillsChoice choose_stills(int count, const std::function<cv::Mat(int)>& read, bool marked_stills,
                           bool plain_folder, bool automatic = true);

// Every still a keyframe; the unconnected stills are the flagged frames.
EgomotionResult tracker_result_from_stills(const StillsResult& stills);

}  // namespace plenopath
