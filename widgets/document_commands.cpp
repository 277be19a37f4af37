#include "widgets/document_commands.h"

#include <utility>

#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {

// Copies the parts named by `flags` from `from` into `to`.
void copy_parts(const Project& from, Project& to, unsigned flags) {
  if (flags & kPlanChanged) to.plan = from.plan;
  if (flags & kCaptureChanged) to.capture = from.capture;
  if (flags & kPathChanged) {
    to.path = from.path;
    to.path_points = from.path_points;
  }
  if (flags & kVisibilityChanged) to.visibility = from.visibility;
  if (flags & kKeyframesChanged) to.keyframes = from.keyframes;
  if (flags & kHotspotsChanged) to.hotspots = from.hotspots;
  if (flags & kAnchorsChanged) to.anchors = from.anchors;
  if (flags & kSettingsChanged) {
    to.geo = from.geo;
    to.tour = from.tour;
  }
}

}  // namespace

ReplacePartsCommand::ReplacePartsCommand(ProjectDocument& document, const QString& text, const Project& after,
                                         unsigned flags)
    : QUndoCommand(text), document_(document), flags_(flags) {
  copy_parts(document.project(), before_, flags);
  copy_parts(after, after_, flags);
}

void ReplacePartsCommand::undo() {
  document_.modify([this](Project& p) { copy_parts(before_, p, flags_); }, flags_);
}

void ReplacePartsCommand::redo() {
  document_.modify([this](Project& p) { copy_parts(after_, p, flags_); }, flags_);
}

SetKeyframesCommand::SetKeyframesCommand(ProjectDocument& document, Keyframes keyframes, int merge_session,
                                         const QString& text)
    : QUndoCommand(text),
      document_(document),
      before_(document.project().keyframes),
      after_(std::move(keyframes)),
      merge_session_(merge_session) {}

void SetKeyframesCommand::undo() {
  document_.modify([this](Project& p) { p.keyframes = before_; }, kKeyframesChanged);
}

void SetKeyframesCommand::redo() {
  document_.modify([this](Project& p) { p.keyframes = after_; }, kKeyframesChanged);
}

bool SetKeyframesCommand::mergeWith(const QUndoCommand* other) {
  const auto* o = static_cast<const SetKeyframesCommand*>(other);
  if (merge_session_ == 0 || o->merge_session_ != merge_session_) return false;
  after_ = o->after_;
  return true;
}

SetLayerOccluderCommand::SetLayerOccluderCommand(ProjectDocument& document, const std::string& layer,
                                                 bool occluder)
    : QUndoCommand(occluder ? QObject::tr("Make layer %1 an occluder").arg(QString::fromStdString(layer))
                            : QObject::tr("Make layer %1 see-through").arg(QString::fromStdString(layer))),
      document_(document),
      layer_(layer),
      after_(occluder) {
  const PlanLayer* l = document.project().plan.find_layer(layer);
  before_ = l ? l->occluder : false;
}

void SetLayerOccluderCommand::apply(bool occluder) {
  document_.modify([&](Project& p) { p.plan.set_layer_occluder(layer_, occluder); }, kPlanChanged);
}
void SetLayerOccluderCommand::undo() { apply(before_); }
void SetLayerOccluderCommand::redo() { apply(after_); }

SetFrameRateCommand::SetFrameRateCommand(ProjectDocument& document, double frame_rate)
    : QUndoCommand(QObject::tr("Set frame rate")),
      document_(document),
      before_(document.project().capture.frame_rate),
      after_(frame_rate) {}

void SetFrameRateCommand::undo() {
  document_.modify([this](Project& p) { p.capture.frame_rate = before_; }, kCaptureChanged);
}
void SetFrameRateCommand::redo() {
  document_.modify([this](Project& p) { p.capture.frame_rate = after_; }, kCaptureChanged);
}
bool SetFrameRateCommand::mergeWith(const QUndoCommand* other) {
  after_ = static_cast<const SetFrameRateCommand*>(other)->after_;
  return true;
}

SetTourTitleCommand::SetTourTitleCommand(ProjectDocument& document, std::string title)
    : QUndoCommand(QObject::tr("Rename tour")),
      document_(document),
      before_(document.project().tour.title),
      after_(std::move(title)) {}

void SetTourTitleCommand::undo() {
  document_.modify([this](Project& p) { p.tour.title = before_; }, kSettingsChanged);
}
void SetTourTitleCommand::redo() {
  document_.modify([this](Project& p) { p.tour.title = after_; }, kSettingsChanged);
}

}  // namespace plenopath::widgets
