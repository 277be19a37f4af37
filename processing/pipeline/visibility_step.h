#pragma once
// Pipeline step: visibility events, cells and critical lines along the project's path
// (processing/visibility/visibility.h). The studio's Process > Compute visibility and
// `plenopath visibility --path` both run it.
#include <memory>
#include <optional>

#include "processing/pipeline/step_result.h"
#include "processing/util/progress.h"
#include "processing/visibility/cells_following_path.h"
#include "processing/visibility/shared_visibility_index.h"
#include "processing/visibility/visibility.h"

namespace plenopath::pipeline {

struct VisibilityStepOptions {
  // The plan's index when the caller holds one (the studio's document shares one per plan revision); null:
  // built here. The cells follow from the plan's occluders and the path alone.
  std::shared_ptr<const SharedVisibilityIndex> visibility_index;
  void check() const {}
};

// Throws Error when the plan has no occluders or the path fewer than two frames; Cancelled on a cancel.
// changed: kVisibilityChanged.
StepResult run_visibility(Project project, const VisibilityStepOptions& options,
                          Progress& progress = null_progress());

}  // namespace plenopath::pipeline
