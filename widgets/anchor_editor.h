#pragma once
// Anchor edits computed off the GUI thread (issue 17). An edit (the anchors after it and how to correct the
// path) is computed on a worker by edit_anchors() (processing/anchors/anchor_edit.h) from a snapshot of the
// project and the plan's shared visibility index; when it lands, one SetAnchorsCommand records it. One
// editor per document (of()), so the map's drags and the Anchors panel's edits share it: the newest request
// wins (an older running one is cancelled, an older waiting one never runs). A result whose project changed
// meanwhile (path, anchors, cells or plan) is dropped, never applied to a document it was not computed for.
// Removing anchors (kNone) computes nothing: it is pushed at once, and cancels a pending edit.
#include <QObject>
#include <QPointer>
#include <QString>
#include <functional>
#include <optional>

#include "model/anchors.h"
#include "processing/anchors/anchor_edit.h"

namespace plenopath::widgets {

class CoalescingRunner;
class ProjectDocument;

class AnchorEditor : public QObject {
  Q_OBJECT
 public:
  // The document's editor (made on first use, a child of the document).
  static AnchorEditor& of(ProjectDocument& document);
  explicit AnchorEditor(ProjectDocument& document);
  ~AnchorEditor() override;

  // What the requester hears back, on the GUI thread, as long as `context` lives.
  struct Callbacks {
    QPointer<QObject> context;
    std::function<void(PathCorrection applied)> landed;  // the undo step was pushed
    std::function<void(const QString& why)> refused;     // failed or dropped: nothing changed
  };
  // Replaces the anchors by `after`, correcting the path as `correction` says; `text` names the undo step.
  void request(const QString& text, Anchors after, PathCorrection correction, Callbacks callbacks = {});

  // An edit is being computed (or waits).
  bool busy() const;
  // Lets events run until no edit is pending (tests).
  void wait();
  // The anchors of the newest pending edit, else the document's: what a new edit starts from.
  const Anchors& anchors() const;
  CoalescingRunner& runner() { return *runner_; }

 signals:
  void landed(const QString& text, PathCorrection applied);
  void refused(const QString& text, const QString& why);

 private:
  void refuse(const QString& text, const QString& why, const Callbacks& callbacks);

  ProjectDocument& document_;
  CoalescingRunner* runner_;
  std::optional<Anchors> pending_anchors_;
};

}  // namespace plenopath::widgets
