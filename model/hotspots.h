#pragma once
// Hotspots: movie textures (media warped onto a planar quad) and events (a region that reacts).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace plenopath {

enum class HotspotKind { kMovieTexture, kEvent };
const char* to_string(HotspotKind kind);
HotspotKind hotspot_kind_from_string(const std::string& text);

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
  std::string trigger = "click";  // click | proximity
  double trigger_distance_m = 0.0;
  std::string action;         // swap_image | play_video | play_sound | jump | open_url | show_text
  std::string action_target;  // media file (absolute in memory, like media), frame index, URL or text
};
// True for the actions whose target is a media file (swap_image, play_video, play_sound).
bool hotspot_action_uses_media(const std::string& action);
bool operator==(const Hotspot& l, const Hotspot& r);

}  // namespace plenopath
