#pragma once
// Re-opens a published tour for editing (issue 21): tour.json -> a project with the tour's plan, path,
// keyframes, cells, hotspots, geo-anchor and settings. The package's keyframe images and hotspot media are
// copied into a folder beside the new project, and the keyframe images become its capture: a capture of the
// keyframes alone, where a frame between two keyframes shows the nearer one. Exporting the project again
// gives the same tour.json.
#include <string>
#include <vector>

#include "model/project.h"
#include "processing/util/progress.h"

namespace plenopath {

struct TourImportOptions {
  std::string package;       // a tour folder, its tour.json, or a .zip
  std::string project_file;  // the project to make (*.plenopath); its media go to <stem>_tour/ beside it
  void check() const;        // throws Error naming the bad field
};

struct TourImportResult {
  Project project;                    // paths absolute, as load_project gives them; not yet saved
  std::string media_folder;           // where the images and media were copied
  int keyframes = 0;                  // keyframes whose image was found
  int media_files = 0;                // hotspot media copied
  std::vector<std::string> warnings;  // what was skipped, and why
};

// The folder an import into `project_file` copies its images to.
std::string tour_media_folder(const std::string& project_file);

// Throws Error naming the package when it is not a tour or holds no keyframe image, and when the media
// folder already exists and is not empty (nothing already there is ever overwritten). A keyframe whose
// image is missing is dropped with a warning; a missing hotspot medium leaves the hotspot without it.
// Cancel ends it with Cancelled and removes the media folder it made.
TourImportResult import_tour(const TourImportOptions& options, Progress& progress = null_progress());

}  // namespace plenopath
