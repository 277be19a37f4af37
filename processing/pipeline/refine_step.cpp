#include "processing/pipeline/refine_step.h"

#include <algorithm>
#include <cstdio>

#include "model/error.h"
#include "processing/pipeline/visibility_step.h"

namespace plenopath::pipeline {

void RefineStepOptions::check() const { refinement.check(); }

RefineStepResult run_refine(Project project, const RefineStepOptions& options, Progress& progress) {
  options.check();
  progress.checkpoint(0.0, "refining " + std::to_string(project.path.size()) + " frames with " +
                               std::to_string(project.anchors.size()) + " anchors");
  if (project.path.empty()) throw Error("the project has no camera path to refine");
  const std::vector<GpsPrior> gps = options.preview ? std::vector<GpsPrior>{} : gps_priors_for_path(project);
  if (project.anchors.empty() && gps.size() < 2)
    throw Error("no anchors: Ctrl + drag a frame on the map to where it really was first");
  RefineStepResult out;
  out.gps_priors = static_cast<int>(gps.size());
  if (options.preview) {
    project.path = preview_path_with_anchors(project.path, project.anchors);
  } else {
    SubProgress solver_progress(progress, 0.02, 0.95, "refinement");
    project.path = refine_path_with_anchors(project.path, project.anchors, options.refinement, &out.report,
                                            solver_progress, gps);
  }
  project.path.scale_source = project.anchors.empty() ? "gps" : "anchors";
  double worst = 0.0;
  for (const AnchorResidual& r : out.report.residuals) worst = std::max(worst, r.distance_m);
  char done[160];
  if (options.preview)
    std::snprintf(done, sizeof done, "warped onto %zu anchors", project.anchors.size());
  else
    std::snprintf(done, sizeof done, "refined in %d iterations; largest anchor residual %.3f m",
                  out.report.iterations, worst);
  out.summary = done;
  out.changed = kPathChanged;
  SubProgress cells_progress(progress, 0.95, 1.0, "visibility cells along the refined path");
  if (std::optional<VisibilityCells> cells =
          cells_following_path(project, project.path, cells_progress, options.visibility_index.get())) {
    project.visibility = std::move(*cells);
    out.changed |= kVisibilityChanged;
  }
  progress.report(1.0, out.summary);
  out.project = std::move(project);
  return out;
}

}  // namespace plenopath::pipeline
