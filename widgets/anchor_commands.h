#pragma once
// Undoable anchor edits (drift correction by hand). Placing or moving an anchor corrects the path in the
// same undo step: the global refinement (Ceres pose graph with every anchor as a prior and a drift model,
// processing/anchors/anchor_refinement.h; 0.1 s for 3 000 frames), or on very long paths the fast warp
// between anchors that the map previews while dragging. Removing anchors leaves the path as it is. Undo
// restores the anchors and the path together.
//
// The command records; it computes nothing. The correction and the cells that follow the corrected path
// are computed on a worker (processing/anchors/anchor_edit.h, run by widgets/anchor_editor.h, which also
// drops a result whose project changed meanwhile) and the command stores before and after.
#include <QUndoCommand>
#include <optional>

#include "model/anchors.h"
#include "model/camera_path.h"
#include "model/visibility_cells.h"
#include "processing/anchors/anchor_edit.h"

namespace plenopath::widgets {

class ProjectDocument;

using plenopath::cells_following_path;
using plenopath::kMaxFramesRefinedAtOnce;
using plenopath::PathCorrection;

// The anchors after an edit, as computed by edit_anchors() from the document's present project: `edit`
// replaces the anchors, and the path and its cells when it has them. The "before" is read from the
// document when the command is made.
class SetAnchorsCommand : public QUndoCommand {
 public:
  SetAnchorsCommand(ProjectDocument& document, const QString& text, AnchorEditResult edit);
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

// `anchors` with the anchor of `frame` set to `position` (added when the frame has none; an existing
// anchor keeps its heading), sorted by frame.
Anchors anchors_with(const Anchors& anchors, int frame, const Eigen::Vector2d& position);
// `anchors` without those on `frames`.
Anchors anchors_without(const Anchors& anchors, const std::vector<int>& frames);
// Distance from each anchor to its frame on `path` (metres), or -1 when the path has no such frame.
std::vector<double> anchor_residuals(const CameraPath& path, const Anchors& anchors);

}  // namespace plenopath::widgets
