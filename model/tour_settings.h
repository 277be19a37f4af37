#pragma once
// How the walkthrough is packaged.
#include <string>

#include "model/enums.h"

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
  // Keyframes without the people who walked through and without the rig (processing/cleanplate).
  bool export_clean_plates = false;
  NadirPatch nadir_patch = NadirPatch::kBlur;  // with clean plates: what covers the rig nothing saw behind
  std::string nadir_image;                     // kImage: the picture (absolute in memory, relative on disk)
  bool blur_faces = false;                     // faces of the people who remain, blurred
};
bool operator==(const TourSettings& l, const TourSettings& r);

}  // namespace plenopath
