#include "processing/visibility/cells_following_path.h"

#include "model/error.h"
#include "processing/visibility/shared_visibility_index.h"
#include "processing/visibility/visibility.h"

namespace plenopath {

std::optional<VisibilityCells> cells_following_path(const Project& project, const CameraPath& moved_path,
                                                    Progress& progress, const SharedVisibilityIndex* index) {
  if (project.visibility.empty()) return std::nullopt;
  try {
    if (index) {
      const std::shared_ptr<const VisibilityIndex> shared = index->get();
      if (!shared) return VisibilityCells{};  // no occluders left, or a plan CGAL cannot take
      return shared->cells_along_path(moved_path, progress);
    }
    return VisibilityIndex(project.plan).cells_along_path(moved_path, progress);
  } catch (const Cancelled&) {
    throw;
  } catch (const Error&) {
    return VisibilityCells{};  // e.g. the plan has no occluders left: no cells rather than stale ones
  }
}

}  // namespace plenopath
