#pragma once
// Process > Refine path with anchors: the global refinement (Ceres pose graph with the anchors as priors)
// on a worker with progress and Cancel; its result is one undo step.
#include "app/studio/reactions.h"

namespace plenopath::studio {

class RefineWithAnchorsReaction : public Reaction {
 public:
  RefineWithAnchorsReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
};

}  // namespace plenopath::studio
