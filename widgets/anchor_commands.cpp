#include "widgets/anchor_commands.h"

#include <algorithm>
#include <utility>

#include "model/error.h"
#include "model/project.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

SetAnchorsCommand::SetAnchorsCommand(ProjectDocument& document, const QString& text, AnchorEditResult edit)
    : QUndoCommand(text),
      document_(document),
      before_(document.project().anchors),
      after_(std::move(edit.anchors)),
      path_after_(std::move(edit.path)),
      visibility_after_(std::move(edit.visibility)),
      applied_(edit.applied) {
  if (path_after_) path_before_ = document.project().path;
  if (visibility_after_) visibility_before_ = document.project().visibility;
}

void SetAnchorsCommand::undo() {
  const unsigned flags =
      kAnchorsChanged | (path_before_ ? kPathChanged : 0u) | (visibility_before_ ? kVisibilityChanged : 0u);
  document_.modify(
      [this](Project& p) {
        p.anchors = before_;
        if (path_before_) p.path = *path_before_;
        if (visibility_before_) p.visibility = *visibility_before_;
      },
      flags);
}

void SetAnchorsCommand::redo() {
  const unsigned flags =
      kAnchorsChanged | (path_after_ ? kPathChanged : 0u) | (visibility_after_ ? kVisibilityChanged : 0u);
  document_.modify(
      [this](Project& p) {
        p.anchors = after_;
        if (path_after_) p.path = *path_after_;
        if (visibility_after_) p.visibility = *visibility_after_;
      },
      flags);
}

Anchors anchors_with(const Anchors& anchors, int frame, const Eigen::Vector2d& position) {
  Anchors out = anchors;
  auto it = std::find_if(out.begin(), out.end(), [frame](const Anchor& a) { return a.frame == frame; });
  if (it != out.end()) {
    it->position = position;
  } else {
    out.push_back({frame, position, std::nullopt});
  }
  std::sort(out.begin(), out.end(), [](const Anchor& l, const Anchor& r) { return l.frame < r.frame; });
  return out;
}

Anchors anchors_without(const Anchors& anchors, const std::vector<int>& frames) {
  Anchors out;
  for (const Anchor& a : anchors)
    if (std::find(frames.begin(), frames.end(), a.frame) == frames.end()) out.push_back(a);
  return out;
}

std::vector<double> anchor_residuals(const CameraPath& path, const Anchors& anchors) {
  std::vector<double> out;
  for (const Anchor& a : anchors) {
    const PathFrame* f = path.find_frame(a.frame);
    out.push_back(f ? (f->position() - a.position).norm() : -1.0);
  }
  return out;
}

}  // namespace plenopath::widgets
