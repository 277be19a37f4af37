#pragma once
// Placing the project's path on its plan (issue 19), shared by Process > Place path on plan and the
// tracking task (which places the path by itself when the project has a plan). Registration
// (processing/registration) finds the candidate placements of every piece; per piece an anchor on it picks
// the candidate, else the best is applied. What registration found is kept (PlacementChoices) so that the
// map can show the runners-up and the author can pick another one. The placed pieces are then refined on the
// walls (processing/registration/plan_refinement.h), which takes out the tracker's drift; a piece whose fit
// does not improve stays as the similarity placed it.
#include <string>
#include <vector>

#include "model/project.h"
#include "processing/registration/plan_refinement.h"
#include "processing/registration/registration.h"
#include "processing/util/progress.h"

namespace plenopath::studio {

struct PlacementChoices {
  CameraPath unplaced_path;  // the path registration ran on (each piece in the frame of its points)
  std::vector<PathPoint> unplaced_points;
  RegistrationResult result;
  std::vector<int> choice;  // candidate applied per piece (-1: left as it was)
  FloorPlan plan;           // the plan registration ran on (the refinement's walls)
  PlanRefinementOptions refinement_options;
  bool refine_on_walls = true;
  PlanRefinementReport refinement;  // of the choice applied last by place_project_on_plan
  bool empty() const { return result.pieces.empty(); }
};

// What a task that placed the path hands back to the GUI thread (filled on the worker).
struct PlacementOutcome {
  PlacementChoices choices;  // empty: nothing was registered
  std::string summary;       // for the status bar ("placed 1 of 1 piece(s) ...", or why not)
};

// The path and points with `choice` applied (apply_registration), then refined on the walls when
// refine_on_walls (`report` gets how); throws Error on a choice out of range.
void apply_placement(const PlacementChoices& choices, const std::vector<int>& choice, CameraPath* path,
                     std::vector<PathPoint>* points, PlanRefinementReport* report = nullptr,
                     Progress& progress = null_progress());

// Why `project` cannot be placed on its plan ("the plan has no sight-blocking layer ..."), or "" when it can.
std::string placement_precondition(const Project& project);

// Registers the project's path with its points on its plan and places path and points (pieces that fit;
// visibility cells follow the moved path when the project has any). Throws Error when the precondition
// fails or, with require_fit, when no piece fits (one line per piece, registration.h describe()).
// `summary` (optional) gets one line for the status bar.
PlacementChoices place_project_on_plan(Project& project, Progress& progress, bool require_fit,
                                       std::string* summary = nullptr);

}  // namespace plenopath::studio
