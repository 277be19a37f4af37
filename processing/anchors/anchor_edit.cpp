#include "processing/anchors/anchor_edit.h"

#include <memory>
#include <utility>

#include "model/error.h"
#include "processing/anchors/anchor_refinement.h"
#include "processing/visibility/shared_visibility_index.h"
#include "processing/visibility/visibility.h"

namespace plenopath {

AnchorEditResult edit_anchors(const Project& project, Anchors after, PathCorrection correction,
                              Progress& progress, const SharedVisibilityIndex* index) {
  AnchorEditResult out;
  out.anchors = std::move(after);
  const CameraPath& path = project.path;
  if (correction == PathCorrection::kNone || path.empty() || out.anchors.empty()) return out;
  progress.checkpoint(0.0, "correcting the path");
  const bool cells = !project.visibility.empty();
  // Without cells to follow, the correction is the whole run.
  const double corrected = cells ? 0.6 : 1.0;
  if (correction == PathCorrection::kRefine && path.size() <= kMaxFramesRefinedAtOnce) {
    SubProgress refining(progress, 0.0, corrected, "refinement");
    out.path = refine_path_with_anchors(path, out.anchors, {}, nullptr, refining);
    out.path->scale_source = "anchors";
    out.applied = PathCorrection::kRefine;
  } else {
    out.path = preview_path_with_anchors(path, out.anchors);
    out.applied = PathCorrection::kWarp;
  }
  progress.checkpoint(corrected, "visibility cells along the corrected path");
  SubProgress following(progress, corrected, 1.0);
  out.visibility = cells_following_path(project, *out.path, following, index);
  progress.report(1.0);
  return out;
}

}  // namespace plenopath
