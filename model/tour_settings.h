#pragma once
// How the walkthrough is packaged.
#include <string>

namespace plenopath {

struct TourSettings {
  std::string title = "Untitled tour";
  std::string description;
  int max_size = 4096;      // full-resolution keyframe width, pixels
  int preview_size = 1024;  // preview keyframe width, pixels
  int jpeg_quality = 85;
  int start_frame = -1;  // -1 = first keyframe
  bool export_pannellum = false;
  bool export_geojson = false;
  bool export_clean_plates =
      false;  // keyframes without the people who walked through (processing/cleanplate)
};
bool operator==(const TourSettings& l, const TourSettings& r);

}  // namespace plenopath
