#pragma once
// Hotspots: movie textures (media warped onto a planar quad) and events (a region that reacts).
// HotspotKind, HotspotTrigger and HotspotAction are defined in resources/schema/enums.json (model/enums.h).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/enums.h"

namespace plenopath {

struct Hotspot {
  std::string id;
  HotspotKind kind = HotspotKind::kMovieTexture;
  std::string title;  // plain text, never markup
  std::string media;  // image or video; absolute in memory, relative to the project on disk
  int frame = -1;     // frame it was authored in
  // Corners as (azimuth, elevation) in radians in the authoring frame, in order around the quad/polygon.
  std::vector<Eigen::Vector2d> image_corners;
  // The same corners lifted to the plan frame (x, y, z metres; z up from the floor), when known.
  std::vector<Eigen::Vector3d> world_corners;
  HotspotTrigger trigger = HotspotTrigger::kClick;  // events: click, or walking within the distance
  double trigger_distance_m = 0.0;
  HotspotAction action = HotspotAction::kNone;  // events: what a trigger does
  std::string action_target;  // media file (absolute in memory, like media), frame index, URL or text
};
// True for the actions whose target is a media file (swap_image, play_video, play_sound).
bool hotspot_action_uses_media(HotspotAction action);
bool operator==(const Hotspot& l, const Hotspot& r);

}  // namespace plenopath
