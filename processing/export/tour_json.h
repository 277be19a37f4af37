#pragma once
// Builds the tour.json document of a package (internal to the exporter, shared with its tests).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/project.h"

namespace plenopath {

struct KeyframeImageFiles {
  int frame = 0;
  std::string preview;  // package-relative script holding the small preview JPEG (keyframe_images.h)
  std::string full;     // package-relative full-resolution JPEG
  std::string tiles;    // package-relative folder of its cube tiles ("" when none)
};

struct HotspotMediaFile {
  std::string id;            // hotspot id
  std::string media;         // package-relative path ("" when the media is missing)
  std::string action_media;  // package-relative path of the action's media (swap image, video, sound)
};

nlohmann::json make_tour_json(const Project& project, const std::vector<KeyframeImageFiles>& images,
                              const std::vector<HotspotMediaFile>& media, int full_width, int preview_width);

}  // namespace plenopath
