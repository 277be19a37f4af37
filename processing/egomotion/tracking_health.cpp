#include "processing/egomotion/tracking_health.h"

#include <cmath>

namespace plenopath {

TrackingHealth assess_tracking(const CameraPath& path, double max_bridged_share) {
  TrackingHealth h;
  h.frames = static_cast<int>(path.frames.size());
  for (const PathFrame& f : path.frames) {
    h.bridged += (f.flags & kFrameBridged) != 0;
    h.moving_objects += (f.flags & kFrameMovingObjects) != 0;
    h.jumps += (f.flags & kFrameJump) != 0;
    h.textureless += (f.flags & kFrameTextureless) != 0;
    h.duplicates += (f.flags & kFrameDuplicate) != 0;
    h.corrupt += (f.flags & kFrameCorrupt) != 0;
  }
  if (h.frames == 0 || h.bridged <= max_bridged_share * h.frames) return h;
  h.reliable = false;
  const long percent = std::lround(100.0 * h.bridged / h.frames);
  std::string why;
  if (h.moving_objects > max_bridged_share * h.frames)
    why += " Many frames also disagree with the static scene (" + std::to_string(h.moving_objects) +
           "): a camera that rocks on an uneven floor looks like that; the frames are levelled by themselves "
           "only when the first 40 show it, --level levels them all.";
  h.warning =
      "the path is not reliable: " + std::to_string(h.bridged) + " of " + std::to_string(h.frames) +
      " frames (" + std::to_string(percent) +
      " %) were bridged, their steps not measured, so between them the path is a guess at the last "
      "speed and its scale may be far off." +
      why +
      " Frames far apart (steps over about 20 cm) track better with every frame of the video; anchors "
      "fix what the images cannot.";
  return h;
}

}  // namespace plenopath
