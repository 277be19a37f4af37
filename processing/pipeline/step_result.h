#pragma once
// What every pipeline step returns (issue 17): the project it was given, changed, which parts changed
// (project_parts.h), and one line for a status bar or a console. Steps add their own extras by deriving.
#include <string>

#include "model/project.h"
#include "processing/pipeline/project_parts.h"

namespace plenopath::pipeline {

struct StepResult {
  Project project;       // the snapshot the step was given, with its result in it
  unsigned changed = 0;  // ProjectPart bits
  std::string summary;   // one line ("refined in 12 iterations; ...")
};

}  // namespace plenopath::pipeline
