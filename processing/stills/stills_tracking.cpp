#include "processing/stills/stills_tracking.h"

#include <cmath>

namespace plenopath {

StillsChoice choose_stills(int count, const std::function<cv::Mat(int)>& read, bool marked_stills,
                           bool plain_folder, bool automatic) {
  StillsChoice choice;
  if (marked_stills) {
    choice.stills = true;
    choice.reason = "marked as still panoramas";
    return choice;
  }
  if (!plain_folder || !automatic) return choice;
  choice.detected = true;
  choice.detection = detect_stills(count, read);
  choice.stills = choice.detection.stills;
  if (choice.stills) choice.reason = "looks like still panoramas, not video: " + choice.detection.reason;
  return choice;
}

EgomotionResult tracker_result_from_stills(const StillsResult& s) {
  EgomotionResult r;
  r.path = s.path;
  r.tracked_points = s.points;
  for (int i = 0; i < static_cast<int>(s.path.size()); ++i) r.keyframes.push_back(i);
  r.points = s.refinement.points;
  r.observations = s.refinement.observations;
  r.refinement.final_rms = s.refinement.final_rms_deg * M_PI / 180.0;
  r.scale_source = s.scale_source;
  r.scale_factor = s.scale_factor;
  r.floor_points = s.floor_points;
  r.flagged_frames = static_cast<int>(s.unconnected.size());
  r.seconds_geometry = s.seconds;
  return r;
}

}  // namespace plenopath
