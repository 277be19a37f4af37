#pragma once
// Every edit of the document is one of these QUndoCommands (one class per edit kind). Each keeps what it
// needs to go both ways and changes the project only through ProjectDocument::modify().
#include <QUndoCommand>
#include <string>

#include "model/project.h"

namespace plenopath::widgets {

class ProjectDocument;

// Replaces whole parts of the project (those named by `flags`, see ChangeFlag) with the same parts of
// `after`: the result of a task run on a snapshot, an import, a recovered autosave. One undo step.
class ReplacePartsCommand : public QUndoCommand {
 public:
  ReplacePartsCommand(ProjectDocument& document, const QString& text, const Project& after, unsigned flags);
  void undo() override;
  void redo() override;

 private:
  ProjectDocument& document_;
  Project before_;  // only the flagged parts are meaningful
  Project after_;
  unsigned flags_;
};

// New keyframes (and the sampling parameters that made them). Commands with the same non-zero
// `merge_session` merge, so dragging a slider is one undo step.
class SetKeyframesCommand : public QUndoCommand {
 public:
  SetKeyframesCommand(ProjectDocument& document, Keyframes keyframes, int merge_session,
                      const QString& text = QObject::tr("Change sampling"));
  void undo() override;
  void redo() override;
  int id() const override { return 1; }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  ProjectDocument& document_;
  Keyframes before_;
  Keyframes after_;
  int merge_session_;
};

// Whether a plan layer blocks sight.
class SetLayerOccluderCommand : public QUndoCommand {
 public:
  SetLayerOccluderCommand(ProjectDocument& document, const std::string& layer, bool occluder);
  void undo() override;
  void redo() override;

 private:
  void apply(bool occluder);
  ProjectDocument& document_;
  std::string layer_;
  bool before_;
  bool after_;
};

// The capture's frame rate (playback, GPS matching). Consecutive edits merge.
class SetFrameRateCommand : public QUndoCommand {
 public:
  SetFrameRateCommand(ProjectDocument& document, double frame_rate);
  void undo() override;
  void redo() override;
  int id() const override { return 2; }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  ProjectDocument& document_;
  double before_;
  double after_;
};

// The tour's title.
class SetTourTitleCommand : public QUndoCommand {
 public:
  SetTourTitleCommand(ProjectDocument& document, std::string title);
  void undo() override;
  void redo() override;

 private:
  ProjectDocument& document_;
  std::string before_;
  std::string after_;
};

}  // namespace plenopath::widgets
