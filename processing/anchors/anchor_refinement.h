#pragma once
// Correcting path drift with the author's anchors ("frame i was really here"):
// - align_path_to_anchors: one similarity (scale, rotation, translation; least squares beyond two anchors)
//   that brings the whole path onto the plan;
// - preview_path_with_anchors: a fast warp for interactive dragging: between consecutive anchors, the
//   similarity that fixes both ends, blended along the arc length, so the path bends smoothly;
// - refine_path_with_anchors: the global refinement: a pose graph (Ceres) whose edges keep every step's
//   relative motion as recovered and whose priors pull the anchored frames onto their anchors, so a
//   correction spreads smoothly along the path instead of moving single frames.
#include <functional>
#include <string>
#include <vector>

#include "model/anchors.h"
#include "model/camera_path.h"
#include "model/project.h"
#include "processing/capture/gps_track.h"
#include "processing/egomotion/path_evaluation.h"
#include "processing/util/progress.h"

namespace plenopath {

// The similarity taking the path's anchored frames onto their anchors (one anchor: a translation; two:
// exact; more: least squares). Throws Error when an anchor names a frame the path does not have.
Similarity2 similarity_to_anchors(const CameraPath& path, const Anchors& anchors);
// The path with that similarity applied (positions and headings).
CameraPath align_path_to_anchors(const CameraPath& path, const Anchors& anchors);

// Interactive preview (microseconds per frame): piecewise similarities between consecutive anchors,
// interpolated by arc length; before the first and after the last anchor, the nearest piece.
CameraPath preview_path_with_anchors(const CameraPath& path, const Anchors& anchors);

struct AnchorRefinementOptions {
  double step_sigma_fraction =
      0.05;  // std. dev. of a step's recovered translation, as a fraction of its length
  double step_sigma_min_m = 0.003;  // ... but at least this, metres
  double turn_sigma_rad = 0.005;    // std. dev. of a step's recovered heading change
  double anchor_sigma_m = 0.005;    // how tightly an anchored frame sits on its anchor
  double anchor_heading_sigma_rad = 0.01;
  double drift_scale_sigma = 0.2;      // prior on the path's scale error (1 = none)
  double drift_bias_sigma_rad = 0.01;  // prior on the path's heading bias per step
  int max_iterations = 100;
  void check() const;  // throws Error naming the bad field
};

struct AnchorResidual {
  int frame = 0;
  double distance_m = 0.0;         // refined position to anchor
  double heading_error_deg = 0.0;  // when the anchor fixes the heading, else 0
};

struct AnchorRefinementReport {
  std::vector<AnchorResidual> residuals;
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0;
  std::string message;  // Ceres' summary line
};

// Needs at least one anchor (two or more to fix rotation and scale), or GPS priors on at least two frames.
// GPS priors (processing/capture/gps_track.h) are weak position priors with a robust loss, so a few bad fixes
// do not drag the path. Frames keep their flags. Throws Error on unusable input (empty path, anchors off the
// path). Reports once per solver iteration ("iteration 3"); a cancel stops the solver and ends with
// Cancelled, `report` untouched.
CameraPath refine_path_with_anchors(const CameraPath& path, const Anchors& anchors,
                                    const AnchorRefinementOptions& options = {},
                                    AnchorRefinementReport* report = nullptr,
                                    Progress& progress = null_progress(),
                                    const std::vector<GpsPrior>& gps = {});

// The project's GPS fixes as priors on its path's frames (capture index in GpsPrior::frame): the capture's
// GPS track matched by frame time and placed on the plan through the geo-anchor. Empty without a track or
// without a valid geo-anchor.
std::vector<GpsPrior> gps_priors_for_path(const Project& project);

}  // namespace plenopath
