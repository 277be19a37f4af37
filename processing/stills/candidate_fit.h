#pragma once
// Which placement of a group of stills is right, by what the stills see (issue 20). Registration places a
// group by its triangulated points on the plan's walls; repeated rooms fit those points equally well (the
// same desks in two offices side by side: on the POV-Ray stills scene the open office's group landed 6 m
// off, in the room next door). The doors, corners and floor-wall boundary the stills see differ between
// the rooms: each candidate of a piece is scored by the stills' fit to the plan at the poses it gives
// (still_on_plan.h, no search), and the candidates are re-ordered by that fit.
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "processing/registration/registration.h"
#include "processing/stills/still_on_plan.h"
#include "processing/util/progress.h"

namespace plenopath {

struct CandidateFitOptions {
  StillOnPlanOptions fit;        // camera height, resolution, truncation
  int max_stills_per_piece = 6;  // spread over the piece
  int max_candidates = 5;        // scored per piece
  // The best candidate's fit must be within this, or the piece is not placed (its points found a place
  // its stills do not agree with). Oriented fits of right placements on the POV-Ray stills scenes reach
  // 3.1 px; a pair pointing into the walls in the along-pairs test fits 3.46.
  double max_fit_px = 3.25;
  void check() const;
};

struct CandidateFitReport {
  int pieces_scored = 0;
  int pieces_reordered = 0;                  // a candidate other than registration's first won
  int pieces_refused = 0;                    // no candidate fits within max_fit_px: not placed
  std::vector<std::vector<double>> fits_px;  // per piece, per candidate scored (mean over its stills)
};

// Re-orders each ok piece's candidates of `result` (registration of `path`, as the stills pipeline gives it)
// by the stills' fit; read(frame_index) gives the still of a frame (its capture index). A piece whose best
// candidate fits worse than max_fit_px is marked not ok, with the reason. Cancel through progress.
CandidateFitReport rerank_by_still_fit(RegistrationResult* result, const CameraPath& path,
                                       const std::function<cv::Mat(int)>& read, const FloorPlan& plan,
                                       const CandidateFitOptions& options = {},
                                       Progress& progress = null_progress());

}  // namespace plenopath
