#pragma once
// Undoable anchor edits (drift correction by hand). Placing or moving an anchor bends the path with the fast
// warp between anchors (processing/anchors/anchor_refinement.h) so the frame sits where the author put it;
// removing anchors leaves the path as it is. Undo restores the anchors and the path together.
#include <QUndoCommand>
#include <optional>

#include "model/anchors.h"
#include "model/camera_path.h"

namespace plenopath::widgets {

class ProjectDocument;

// The anchors after an edit: `after` replaces them all. With `bend_path`, the path is warped onto them too
// (throws plenopath::Error when an anchor names a frame the path does not have; nothing is changed then).
class SetAnchorsCommand : public QUndoCommand {
 public:
  SetAnchorsCommand(ProjectDocument& document, const QString& text, Anchors after, bool bend_path);
  void undo() override;
  void redo() override;

 private:
  ProjectDocument& document_;
  Anchors before_;
  Anchors after_;
  std::optional<CameraPath> path_before_;  // set when the path is bent
  std::optional<CameraPath> path_after_;
};

// `anchors` with the anchor of `frame` set to `position` (added when the frame has none; an existing
// anchor keeps its heading), sorted by frame.
Anchors anchors_with(const Anchors& anchors, int frame, const Eigen::Vector2d& position);
// `anchors` without those on `frames`.
Anchors anchors_without(const Anchors& anchors, const std::vector<int>& frames);
// Distance from each anchor to its frame on `path` (metres), or -1 when the path has no such frame.
std::vector<double> anchor_residuals(const CameraPath& path, const Anchors& anchors);

}  // namespace plenopath::widgets
