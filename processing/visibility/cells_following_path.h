#pragma once
// The visibility cells that follow a moved path (an anchor edit, a refinement, a placement on the plan).
#include <optional>

#include "model/camera_path.h"
#include "model/project.h"
#include "model/visibility_cells.h"
#include "processing/util/progress.h"

namespace plenopath {

class SharedVisibilityIndex;

// The visibility cells for `moved_path` when the path of `project` moves: recomputed from the plan when the
// project had cells, empty when they cannot be (no occluders); nullopt when the project had none, so there
// is nothing to keep up to date. Cells of the old path would colour the map and drive the visibility
// sampler with events at the wrong places. `index`: the plan's shared index (the studio's document hands
// one out per plan revision), or null to build one here.
std::optional<VisibilityCells> cells_following_path(const Project& project, const CameraPath& moved_path,
                                                    Progress& progress = null_progress(),
                                                    const SharedVisibilityIndex* index = nullptr);

}  // namespace plenopath
