#include "widgets/anchor_editor.h"

#include <QUndoStack>
#include <memory>
#include <utility>

#include "processing/visibility/shared_visibility_index.h"
#include "widgets/anchor_commands.h"
#include "widgets/coalescing_runner.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {

// Whether the document still holds what an edit was computed from (the parts edit_anchors reads).
bool same_inputs(const Project& snapshot, unsigned plan_revision, const ProjectDocument& document) {
  const Project& p = document.project();
  return plan_revision == document.plan_revision() && snapshot.anchors == p.anchors &&
         snapshot.path == p.path && snapshot.visibility == p.visibility;
}

}  // namespace

AnchorEditor& AnchorEditor::of(ProjectDocument& document) {
  if (auto* editor = document.findChild<AnchorEditor*>(QString(), Qt::FindDirectChildrenOnly)) return *editor;
  return *new AnchorEditor(document);
}

AnchorEditor::AnchorEditor(ProjectDocument& document)
    : QObject(&document), document_(document), runner_(new CoalescingRunner(this)) {}

AnchorEditor::~AnchorEditor() = default;

bool AnchorEditor::busy() const { return runner_->busy(); }

void AnchorEditor::wait() { runner_->wait(); }

const Anchors& AnchorEditor::anchors() const {
  return pending_anchors_ ? *pending_anchors_ : document_.project().anchors;
}

void AnchorEditor::refuse(const QString& text, const QString& why, const Callbacks& callbacks) {
  if (callbacks.context && callbacks.refused) callbacks.refused(why);
  emit refused(text, why);
}

void AnchorEditor::request(const QString& text, Anchors after, PathCorrection correction,
                           Callbacks callbacks) {
  const Project& p = document_.project();
  if (correction == PathCorrection::kNone || p.path.empty() || after.empty()) {
    // Nothing to compute: at once (the newest request; a pending one is dropped).
    runner_->cancel();
    pending_anchors_.reset();
    AnchorEditResult edit = edit_anchors(p, std::move(after), PathCorrection::kNone);
    document_.undo_stack()->push(new SetAnchorsCommand(document_, text, std::move(edit)));
    if (callbacks.context && callbacks.landed) callbacks.landed(PathCorrection::kNone);
    emit landed(text, PathCorrection::kNone);
    return;
  }
  pending_anchors_ = after;
  // The worker's inputs: a snapshot of what the edit reads and the plan's shared index (never the document).
  auto snapshot = std::make_shared<Project>();
  snapshot->path = p.path;
  snapshot->anchors = p.anchors;
  snapshot->visibility = p.visibility;
  snapshot->plan = p.plan;
  const unsigned plan_revision = document_.plan_revision();
  std::shared_ptr<const SharedVisibilityIndex> index =
      p.visibility.empty() ? nullptr : document_.visibility_index();
  runner_->request([this, text, snapshot, plan_revision, index, after = std::move(after), correction,
                    callbacks](Progress& progress) -> CoalescingRunner::Delivery {
    auto edit =
        std::make_shared<AnchorEditResult>(edit_anchors(*snapshot, after, correction, progress, index.get()));
    // On the GUI thread, if still the newest request.
    return [this, text, snapshot, plan_revision, edit, callbacks] {
      pending_anchors_.reset();
      if (!same_inputs(*snapshot, plan_revision, document_)) {
        refuse(text, tr("%1: not applied, the project changed while the path was being corrected").arg(text),
               callbacks);
        return;
      }
      const PathCorrection applied = edit->applied;
      document_.undo_stack()->push(new SetAnchorsCommand(document_, text, std::move(*edit)));
      if (callbacks.context && callbacks.landed) callbacks.landed(applied);
      emit landed(text, applied);
    };
  });
  // Failures of this request (the newest): an anchor off the path, a solver that gave up.
  disconnect(runner_, &CoalescingRunner::failed, this, nullptr);
  connect(runner_, &CoalescingRunner::failed, this, [this, text, callbacks](const QString& message) {
    pending_anchors_.reset();
    refuse(text, message, callbacks);
  });
}

}  // namespace plenopath::widgets
