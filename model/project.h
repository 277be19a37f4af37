#pragma once
// The document: everything an author makes. Processing reads a snapshot and returns results; the GUI
// applies each result as one undoable command.
#include "model/anchors.h"
#include "model/camera_path.h"
#include "model/capture.h"
#include "model/floor_plan.h"
#include "model/geo_anchor.h"
#include "model/hotspots.h"
#include "model/keyframes.h"
#include "model/path_points.h"
#include "model/tour_settings.h"
#include "model/visibility_cells.h"

namespace plenopath {

struct Project {
  FloorPlan plan;
  Capture capture;
  CameraPath path;
  // The tracker's points, in the frame of the path as tracked or placed on the plan (model/path_points.h):
  // what registration fits to the walls. Not in the project file: the studio keeps them in the sidecar
  // PROJECT.points.json (points_file_beside), as `plenopath track --out` writes it. They go with the path
  // (kPathChanged).
  std::vector<PathPoint> path_points;
  Anchors anchors;
  VisibilityCells visibility;
  Keyframes keyframes;
  std::vector<Hotspot> hotspots;
  GeoAnchor geo;
  TourSettings tour;
};
bool operator==(const Project& l, const Project& r);
inline bool operator!=(const Project& l, const Project& r) { return !(l == r); }

}  // namespace plenopath
