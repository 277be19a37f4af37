#pragma once
// How far a tracked path can be trusted, said from its frames' flags (model/camera_path.h FrameFlag). A
// path whose steps could mostly not be measured is still written (the author may want to anchor it), but
// the author must hear that it is a guess: the POV-Ray trolley corridor (1 deg of shake, 26 cm steps) came
// back 6 m long instead of 97 m, with 43 % of its frames bridged at the last speed, and the summary said
// only "277 frames flagged".
#include <string>

#include "model/camera_path.h"

namespace plenopath {

struct TrackingHealth {
  int frames = 0;
  // Frames carrying each flag (a frame may carry several).
  int bridged = 0, moving_objects = 0, jumps = 0, textureless = 0, duplicates = 0, corrupt = 0;
  bool reliable = true;
  std::string warning;  // for the author; empty when reliable
};

// Unreliable when more than max_bridged_share of the frames were bridged (their steps not measured).
TrackingHealth assess_tracking(const CameraPath& path, double max_bridged_share = 0.2);

}  // namespace plenopath
