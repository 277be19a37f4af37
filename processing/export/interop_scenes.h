#pragma once
// The tour as other viewers see it (Pannellum, Marzipano, Photo Sphere Viewer): one scene per keyframe,
// linked to its neighbours along the path, with the author's hotspots placed in each scene that sees them.
// Angles are those of the keyframe's equirectangular image (ARCHITECTURE.md): yaw = azimuth in degrees,
// growing to the right; pitch = elevation in degrees, up positive.
#include <string>
#include <vector>

#include "model/project.h"
#include "processing/export/tour_json.h"

namespace plenopath {

struct InteropLink {
  int target_frame = 0;
  std::string target_id;
  double yaw_deg = 0.0, pitch_deg = 0.0;  // where the neighbour stands: the floor under it
  std::string label;                      // "Forward" or "Back"
};

struct InteropSpot {
  std::string id, title;
  std::string text;                       // show_text: what it shows ("" otherwise)
  std::string url;                        // open_url: the address ("" otherwise)
  int jump_frame = -1;                    // jump to a keyframe: its frame (-1 otherwise)
  double yaw_deg = 0.0, pitch_deg = 0.0;  // the centre of its quad
};

struct InteropScene {
  int frame = 0;
  std::string id;  // "k<frame>"
  std::string title;
  const KeyframeImageFiles* images = nullptr;
  double x = 0.0, y = 0.0, heading_deg = 0.0;
  // Compass bearing of the image's centre column, clockwise from north: north from the geo-anchor, else
  // the plan's +Y. A viewer that keeps bearing + yaw across a scene change keeps the world direction.
  double north_offset_deg = 0.0;
  std::vector<InteropLink> links;
  std::vector<InteropSpot> spots;
};

// In frame order. A hotspot with world corners appears in every scene whose line of sight to its centre
// crosses no occluder of the plan; one with image corners only, in the scene nearest its authoring frame.
// Throws Error for a keyframe without a pose.
std::vector<InteropScene> interop_scenes(const Project& project,
                                         const std::vector<KeyframeImageFiles>& images);

std::string interop_scene_id(int frame);

}  // namespace plenopath
