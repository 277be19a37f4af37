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
  // Files for other viewers and tools, written beside the web player (processing/export/tour_export.h).
  bool export_pannellum = false;
  bool export_geojson = false;
  bool export_multires = false;       // multi-resolution cube tiles (the player and Pannellum use them)
  bool export_marzipano = false;      // a Marzipano tour on the cube tiles
  bool export_psv = false;            // Photo Sphere Viewer virtual tour and map
  bool export_kml_gpx = true;         // path.kml and path.gpx, when the project is georeferenced
  bool export_tum = false;            // the path as a TUM trajectory
  bool export_opensfm = false;        // the keyframes as an OpenSfM reconstruction
  bool export_nerfstudio = false;     // the keyframes as a nerfstudio transforms.json
  bool export_photo_metadata = true;  // GPano XMP and EXIF GPS in each keyframe JPEG
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
