#pragma once
// An anchor edit, computed (issue 17: undo commands record results, they compute nothing): the anchors
// after the edit, the path they correct and the visibility cells that follow the corrected path. Qt-free;
// the studio runs it on a worker with a snapshot of the project (widgets/anchor_editor.h) and records the
// result in one SetAnchorsCommand (widgets/anchor_commands.h).
#include <cstddef>
#include <optional>

#include "model/anchors.h"
#include "model/camera_path.h"
#include "model/project.h"
#include "model/visibility_cells.h"
#include "processing/util/progress.h"
#include "processing/visibility/cells_following_path.h"

namespace plenopath {

class SharedVisibilityIndex;

// How an anchor edit moves the path.
enum class PathCorrection {
  kNone,    // the path stays (removing anchors, a heading-only edit)
  kWarp,    // the fast piecewise warp (what the map previews while dragging)
  kRefine,  // the global refinement; the warp instead beyond kMaxFramesRefinedAtOnce frames
};
// Longest path an anchor edit refines (about a second on two cores, on a worker); longer paths get the warp
// and the author runs Process > Refine path with anchors (a task with progress).
constexpr std::size_t kMaxFramesRefinedAtOnce = 20000;

struct AnchorEditResult {
  Anchors anchors;                                 // after the edit
  std::optional<CameraPath> path;                  // the corrected path; unset when the path stays
  std::optional<VisibilityCells> visibility;       // the corrected path's cells; unset when not recomputed
  PathCorrection applied = PathCorrection::kNone;  // how the path was corrected
};

// `after` replaces the project's anchors and the path is corrected as `correction` says (the refinement
// without GPS priors, scale_source "anchors"; nothing when the path or `after` is empty). Throws
// plenopath::Error when an anchor names a frame the path does not have, Cancelled when `progress` is.
// `index`: the visibility index of project.plan when the caller shares one (null: built here if needed).
AnchorEditResult edit_anchors(const Project& project, Anchors after, PathCorrection correction,
                              Progress& progress = null_progress(),
                              const SharedVisibilityIndex* index = nullptr);

}  // namespace plenopath
