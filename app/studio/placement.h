#pragma once
// Placing the project's path on its plan (issue 19): the pipeline's step (processing/pipeline/place_step.h),
// shared by Process > Place path on plan and the tracking task. What a task that placed the path hands back
// to the GUI thread is the studio's own.
#include <string>

#include "processing/pipeline/place_step.h"

namespace plenopath::studio {

using pipeline::apply_placement;
using pipeline::placement_precondition;
using pipeline::PlacementChoices;

// What a task that placed the path hands back to the GUI thread (filled on the worker).
struct PlacementOutcome {
  PlacementChoices choices;  // empty: nothing was registered
  std::string summary;       // for the status bar ("placed 1 of 1 piece(s) ...", or why not)
};

}  // namespace plenopath::studio
