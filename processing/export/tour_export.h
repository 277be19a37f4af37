#pragma once
// Exports a project as a packaged walkthrough: a folder (or .zip) holding tour.json (schema:
// resources/schema/tour.schema.json), keyframe images (a full JPEG, a small preview script), hotspot
// media, the plan as SVG and the web player, which works offline from file:// or from any static server.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/project.h"
#include "processing/export/geo_tracks.h"
#include "processing/export/keyframe_cleaner.h"
#include "processing/export/keyframe_images.h"
#include "processing/util/progress.h"

namespace plenopath {

constexpr int kTourFormatVersion = 1;
constexpr const char* kTourFormatName = "plenopath-tour";

struct TourExportOptions {
  std::string output;       // a folder, or a file whose name ends in .zip
  int max_size = 4096;      // full keyframe width cap, pixels (never upscaled)
  int preview_size = 1024;  // preview keyframe width, pixels (loads first)
  int jpeg_quality = 85;    // 1..100
  bool pannellum = false;   // also write pannellum.json (one scene per keyframe, linked along the path)
  bool geojson = false;     // also write path.geojson in WGS84 (needs a valid geo-anchor)
  // path.kml and path.gpx in WGS84 (geo_tracks.h): by default whenever the project is georeferenced.
  GeoTrackFiles kml_gpx = GeoTrackFiles::kAuto;
  bool tum = false;         // also write trajectory.tum, the whole path (trajectory_formats.h)
  bool opensfm = false;     // also write reconstruction.json, the keyframes (opensfm_reconstruction.h)
  bool nerfstudio = false;  // also write transforms.json, the keyframes (nerfstudio_transforms.h)
  // GPano XMP and, when georeferenced, EXIF GPS in every keyframe JPEG (keyframe_metadata.h).
  bool photo_metadata = true;
  // Multi-resolution cube tiles of each keyframe under tiles/ (processing/export/cube_tiles.h), described in
  // tour.json's "tiles" and used by pannellum.json's multiRes.
  bool multires = false;
  int tile_size = 512;     // the largest tile, pixels (16..4096); smaller when the faces need it
  bool marzipano = false;  // also write a Marzipano tour (marzipano.html, marzipano-data.js; implies tiles)
  bool psv = false;        // also write psv.json (Photo Sphere Viewer virtual-tour and map plugins)
  bool writes_cube_tiles() const { return multires || marzipano; }
  // Browsers refuse file:// media as WebGL textures; the player then loads each hotspot's media from a
  // script holding it as a data URI (keyframes always have their preview as such a script, their full
  // image once as a JPEG). Off only for packages that will always be served over http.
  bool offline_images = true;
  // The preview's JPEG quality, 1..100 (keyframe_images.h says why it is lower).
  int preview_quality = KeyframeImageEncoding{}.preview_quality;
  // Each keyframe as the tour shows it (keyframe_cleaner.h): its clean plate, its faces blurred.
  KeyframeCleaning cleaning;
  void check() const;  // throws Error naming the bad field
  // The project's tour settings (the nadir image read here: Error naming it when unreadable).
  static TourExportOptions from_project(const Project& project, const std::string& output);
};

struct TourExportReport {
  std::string output;
  int keyframes = 0;
  int capture_frames = 0;
  std::uintmax_t package_bytes = 0;   // total size of the folder's files, or of the .zip
  std::vector<std::string> files;     // package-relative paths written
  std::vector<std::string> warnings;  // e.g. missing hotspot media
  int clean_plates = 0;               // keyframes exported as clean plates
  double replaced_pct = 0.0;          // their mean share of pixels replaced
  double rig_pct = 0.0;               // share of the image the rig covers (0: no rig found)
  double rig_filled_pct = 0.0;        // mean share of the rig filled by what other frames saw behind it
  int faces_blurred = 0;
  // The full keyframe JPEGs' bytes, and the package's size over them (what previews, player, media add).
  std::uintmax_t full_image_bytes = 0;
  double package_ratio = 0.0;
};

// Throws Error with a clear message: no path or keyframes, unreadable frames, unwritable output, ...
// Reports the fraction done and a short stage name; a cancel ends it with Cancelled and leaves no partial
// package behind.
TourExportReport export_tour(const Project& project, const TourExportOptions& options,
                             Progress& progress = null_progress());

// The parts a tour.json holds, read back into a Project (plan lines, path, keyframes, cells, hotspots,
// geo-anchor, title). For round-trip tests and for re-importing a published tour.
Project project_from_tour_json(const nlohmann::json& tour, const std::string& file_for_errors);

// The SVG of the plan (y flipped so that +Y is up on screen), one <g> per layer, occluders drawn heavier.
std::string plan_svg(const FloorPlan& plan);

}  // namespace plenopath
