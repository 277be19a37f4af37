#pragma once
// Undoable anchor edits (drift correction by hand). Placing or moving an anchor corrects the path in the
// same undo step: the global refinement (Ceres pose graph with every anchor as a prior and a drift model,
// processing/anchors/anchor_refinement.h; 0.1 s for 3 000 frames), or on very long paths the fast warp
// between anchors that the map previews while dragging. Removing anchors leaves the path as it is. Undo
// restores the anchors and the path together.
#include <QUndoCommand>
#include <optional>

#include "model/anchors.h"
#include "model/camera_path.h"
#include "model/visibility_cells.h"

namespace plenopath {
struct Project;
}

namespace plenopath::widgets {

class ProjectDocument;

// How an anchor edit moves the path.
enum class PathCorrection {
  kNone,    // the path stays (removing anchors, a heading-only edit)
  kWarp,    // the fast piecewise warp (what the map previews while dragging)
  kRefine,  // the global refinement; the warp instead beyond kMaxFramesRefinedAtOnce frames
};
// Longest path refined synchronously when an anchor is placed (about a second on two cores); longer paths
// get the warp and the author runs Process > Refine path with anchors (a cancellable task).
constexpr std::size_t kMaxFramesRefinedAtOnce = 20000;

// The anchors after an edit: `after` replaces them all, and the path is corrected as `correction` says
// (throws plenopath::Error when an anchor names a frame the path does not have; nothing changes then).
class SetAnchorsCommand : public QUndoCommand {
 public:
  SetAnchorsCommand(ProjectDocument& document, const QString& text, Anchors after, PathCorrection correction);
  // How the path was corrected (kNone when it was not).
  PathCorrection applied() const { return applied_; }
  void undo() override;
  void redo() override;

 private:
  ProjectDocument& document_;
  Anchors before_;
  Anchors after_;
  std::optional<CameraPath> path_before_;  // set when the path is bent
  std::optional<CameraPath> path_after_;
  std::optional<VisibilityCells> visibility_before_;  // set when the bent path's cells were recomputed
  std::optional<VisibilityCells> visibility_after_;
  PathCorrection applied_ = PathCorrection::kNone;
};

// The visibility cells for `moved_path` when the path of `project` moves: recomputed from the plan when the
// project had cells (about 15 ms on the office sample), empty when they cannot be (no occluders); nullopt
// when the project had none, so there is nothing to keep up to date. Cells of the old path would colour the
// map and drive the visibility sampler with events at the wrong places.
std::optional<VisibilityCells> cells_following_path(const Project& project, const CameraPath& moved_path);

// `anchors` with the anchor of `frame` set to `position` (added when the frame has none; an existing
// anchor keeps its heading), sorted by frame.
Anchors anchors_with(const Anchors& anchors, int frame, const Eigen::Vector2d& position);
// `anchors` without those on `frames`.
Anchors anchors_without(const Anchors& anchors, const std::vector<int>& frames);
// Distance from each anchor to its frame on `path` (metres), or -1 when the path has no such frame.
std::vector<double> anchor_residuals(const CameraPath& path, const Anchors& anchors);

}  // namespace plenopath::widgets
