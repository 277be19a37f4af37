#pragma once
// How the walkthrough is packaged.
#include <string>
#include <vector>

#include "model/enums.h"

namespace plenopath {

// The author's correction of one keyframe's clean plate: a grey image of the frame's size (PNG), 0 where
// the clean plate decides, 255 where it must take what other frames saw (paint away), 128 where the
// keyframe stays as captured (paint back).
struct CleanPlateEdit {
  int frame = 0;     // capture index of the keyframe
  std::string mask;  // absolute in memory, relative to the project on disk
};
bool operator==(const CleanPlateEdit& l, const CleanPlateEdit& r);
constexpr unsigned char kCleanPlateRemove = 255, kCleanPlateKeep = 128;

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
  std::vector<CleanPlateEdit> clean_plate_edits;            // at most one per keyframe
  const CleanPlateEdit* clean_plate_edit(int frame) const;  // nullptr when none
};
bool operator==(const TourSettings& l, const TourSettings& r);

}  // namespace plenopath
