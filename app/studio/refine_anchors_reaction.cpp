#include "app/studio/refine_anchors_reaction.h"

#include <QAction>

#include "app/studio/main_window.h"
#include "app/studio/studio_tasks.h"
#include "widgets/project_document.h"
#include "widgets/task_runner.h"

namespace plenopath::studio {

RefineWithAnchorsReaction::RefineWithAnchorsReaction(QAction* action, MainWindow& window)
    : Reaction(action, window) {
  connect(&window.document(), &widgets::ProjectDocument::changed, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::started, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::finished, this, [this] { update_enabled(); });
  update_enabled();
}

void RefineWithAnchorsReaction::update_enabled() {
  const Project& p = window_.document().project();
  action()->setEnabled(!window_.tasks().is_running() && !p.path.empty() && !p.anchors.empty());
}

void RefineWithAnchorsReaction::on_triggered() {
  if (!window_.tasks().start(QObject::tr("Refine path with anchors"),
                             refine_with_anchors_task(window_.document().visibility_index())))
    window_.show_error(QObject::tr("Busy"),
                       QObject::tr("Another task is running; wait for it or cancel it first."));
}

}  // namespace plenopath::studio
