#include "processing/pipeline/export_step.h"

#include "model/option_check.h"

namespace plenopath::pipeline {

void ExportStepOptions::check() const {
  require_option(!tour.output.empty(), "ExportStepOptions.tour.output", "must name a folder or a .zip file",
                 tour.output);
  tour.check();
}

ExportStepResult run_export(Project project, const ExportStepOptions& options, Progress& progress) {
  options.check();
  progress.checkpoint(0.0, "exporting " + std::to_string(project.keyframes.indices.size()) + " keyframes");
  ExportStepResult out;
  out.report = export_tour(project, options.tour, progress);
  out.summary = "exported " + std::to_string(out.report.keyframes) + " keyframes, " +
                std::to_string(out.report.package_bytes / 1024) + " KiB";
  progress.report(1.0, out.summary);
  out.project = std::move(project);
  out.changed = 0;  // an export changes nothing in the document
  return out;
}

}  // namespace plenopath::pipeline
