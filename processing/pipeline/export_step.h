#pragma once
// Pipeline step: the packaged walkthrough (processing/export/tour_export.h). The studio's File > Export
// tour and `plenopath export` both run it; an export writes files and changes nothing in the project.
#include "processing/export/tour_export.h"
#include "processing/pipeline/step_result.h"
#include "processing/util/progress.h"

namespace plenopath::pipeline {

struct ExportStepOptions {
  // Where and how: TourExportOptions::from_project(project, out) gives the project's own choices.
  TourExportOptions tour;
  void check() const;  // throws Error naming the field
};

struct ExportStepResult : StepResult {
  TourExportReport report;
};

// Throws Error when the project cannot be exported (no keyframes, unplaced pieces, ...); Cancelled on a
// cancel (the package is then not left half-written as the output). changed: 0.
ExportStepResult run_export(Project project, const ExportStepOptions& options,
                            Progress& progress = null_progress());

}  // namespace plenopath::pipeline
