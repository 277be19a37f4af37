#pragma once
// Pipeline step: the path refined with the author's anchors as priors (Ceres pose graph with a drift model,
// processing/anchors/anchor_refinement.h), plus the capture's GPS fixes as weak priors when there are any;
// the visibility cells follow the refined path when the project has cells. The studio's Process > Refine
// with anchors and `plenopath refine` both run it.
#include <memory>
#include <vector>

#include "processing/anchors/anchor_refinement.h"
#include "processing/pipeline/step_result.h"
#include "processing/util/progress.h"
#include "processing/visibility/shared_visibility_index.h"

namespace plenopath::pipeline {

struct RefineStepOptions {
  AnchorRefinementOptions refinement;  // the solver's weights and iterations
  bool preview = false;                // only the fast warp between anchors (no solver, no GPS priors)
  std::shared_ptr<const SharedVisibilityIndex> visibility_index;  // for the cells that follow; null: built
  void check() const;                                             // throws Error naming the field
};

struct RefineStepResult : StepResult {
  AnchorRefinementReport report;  // iterations and residuals (empty for a preview)
  int gps_priors = 0;             // frames with a GPS fix used as weak priors
};

// Throws Error when the project has no path, or neither anchors nor two GPS fixes; Cancelled on a cancel
// (the solver stops at its next iteration). changed: kPathChanged, and kVisibilityChanged when the cells
// were recomputed.
RefineStepResult run_refine(Project project, const RefineStepOptions& options,
                            Progress& progress = null_progress());

}  // namespace plenopath::pipeline
