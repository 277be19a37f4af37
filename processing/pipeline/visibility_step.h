#pragma once
// Pipeline step: visibility events, cells and critical lines along the project's path
// (processing/visibility/visibility.h). The studio's Process > Compute visibility and
// `plenopath visibility --path` both run it.
#include <optional>

#include "processing/pipeline/step_result.h"
#include "processing/util/progress.h"
#include "processing/visibility/visibility.h"

namespace plenopath::pipeline {

struct VisibilityStepOptions {
  // Nothing to choose yet: the cells follow from the plan's occluders and the path alone. Kept so that the
  // step has the shape of the others.
  void check() const {}
};

// Throws Error when the plan has no occluders or the path fewer than two frames; Cancelled on a cancel.
// changed: kVisibilityChanged.
StepResult run_visibility(Project project, const VisibilityStepOptions& options,
                          Progress& progress = null_progress());

// The visibility cells for `moved_path` when the path of `project` moves: recomputed from the plan when the
// project had cells, empty when they cannot be (no occluders); nullopt when the project had none, so there is
// nothing to keep up to date. Cells of the old path would drive the sampler with events at the wrong places.
std::optional<VisibilityCells> cells_following_path(const Project& project, const CameraPath& moved_path,
                                                    Progress& progress = null_progress());

}  // namespace plenopath::pipeline
