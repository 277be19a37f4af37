#pragma once
// Pipeline step: the camera path from the capture's frames alone (processing/egomotion), or for still
// panoramas by wide-baseline matching (processing/stills: as the author imported them, or because KLT cannot
// follow neighbouring images); the tracker's points are kept with the path (Project::path_points), frames
// numbered by the Capture's mapping (Capture::frame_index_of_kept). When the project has a plan, the path is
// then placed on it by itself (place_step.h) and, for stills, the stills with a pair but no length placed
// along their pairs. The studio's Process > Track and `plenopath track` both run it.
#include <optional>
#include <string>
#include <vector>

#include "processing/anchors/anchor_refinement.h"
#include "processing/capture/stills_folder.h"
#include "processing/egomotion/egomotion.h"
#include "processing/pipeline/place_step.h"
#include "processing/stills/stills.h"
#include "processing/stills/stills_along_pairs.h"
#include "processing/stills/stills_by_capture_order.h"
#include "processing/stills/stills_tracking.h"

namespace plenopath::pipeline {

struct TrackStepOptions {
  // The tracker's options; camera_height_m 0 = the capture's. scale_frame_a/b are kept frames.
  EgomotionOptions egomotion;
  // The stills pipeline's options; its camera height is the capture's when the capture knows it.
  StillsOptions stills;
  bool force_stills = false;  // solve the folder as stills whatever the capture says (`track --stills`)
  bool auto_stills = true;    // judge a plain folder by how well KLT follows neighbours
  bool place_on_plan = true;  // when the project has a plan: place the path on it afterwards
  PlaceStepOptions place{0.0, true, PlaceStepOptions::Require::kNone, {}, nullptr};
  // Afterwards, the path aligned to the project's anchors and refined with them as priors (no GPS), the
  // scale from them with two or more (`track --anchors`).
  bool refine_with_anchors = false;
  void check() const;  // throws Error naming the field
};

struct TrackStepResult : StepResult {
  StillsChoice choice;                 // stills or video, and why
  EgomotionResult tracking;            // the tracker's figures (its path and points are in `project`)
  std::optional<StillsResult> stills;  // when solved as stills (its path and points moved out too)
  std::optional<StillsFolder> order;   // when the capture was found to be stills here: order, GPS, notes
  std::optional<PlaceStepResult> placement;  // when it was placed on the plan (its project moved out)
  std::string placement_error;               // why it was not placed although the project has a plan
  CaptureOrderReport capture_order;          // stills placed next to their neighbours in capture order
  PairPlacementReport along_pairs;           // stills placed along their pairs
  AnchorRefinementReport anchors;            // with refine_with_anchors
};

// Throws Error when the project has no capture or fewer than two frames; Cancelled on a cancel (Ceres stops
// at its next iteration). A placement that fails leaves the tracked path unplaced and says why
// (placement_error, summary). changed: kPathChanged | kVisibilityChanged (the cells belong to the old path),
// plus kCaptureChanged when the capture was found to be stills and kKeyframesChanged for stills (every still
// is a keyframe).
TrackStepResult run_track(Project project, const TrackStepOptions& options,
                          Progress& progress = null_progress());

}  // namespace plenopath::pipeline
