#include "processing/pipeline/visibility_step.h"

#include "model/error.h"

namespace plenopath::pipeline {

StepResult run_visibility(Project project, const VisibilityStepOptions& options, Progress& progress) {
  options.check();
  progress.checkpoint(0.0, "checking the plan and the path");
  if (project.plan.occluder_segments().empty())
    throw Error("the plan has no occluder layer: mark the walls' layer as blocking sight first");
  if (project.path.size() < 2) throw Error("the project has no camera path yet");
  progress.checkpoint(0.1, "building the visibility index");
  std::shared_ptr<const VisibilityIndex> index =
      options.visibility_index ? options.visibility_index->get() : nullptr;
  if (!index) index = std::make_shared<const VisibilityIndex>(project.plan);  // throws why it cannot
  progress.checkpoint(0.3, "events and cells along " + std::to_string(project.path.size()) + " frames");
  // Cancel reaches inside: the visibility workers stop at their next report.
  SubProgress cells_progress(progress, 0.3, 1.0);
  project.visibility = index->cells_along_path(project.path, cells_progress);
  StepResult out;
  out.summary = std::to_string(project.visibility.cells.size()) + " cells, " +
                std::to_string(project.visibility.events.size()) + " events along " +
                std::to_string(project.path.size()) + " frames";
  progress.report(1.0);
  out.project = std::move(project);
  out.changed = kVisibilityChanged;
  return out;
}

}  // namespace plenopath::pipeline
