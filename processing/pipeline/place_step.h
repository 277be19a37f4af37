#pragma once
// Pipeline step: the project's path placed on its plan (issue 19; `plenopath register`, the studio's
// Process > Place path on plan, and the end of `track` when there is a plan). Registration
// (processing/registration) finds the candidate placements of every piece; per piece the author's pick,
// else an anchor on it, else the best candidate is applied. For still panoramas what the stills see re-ranks
// the candidates (processing/stills/candidate_fit.h), and a group of stills registration cannot place is left
// unplaced. The placed pieces are then refined on the walls (plan_refinement.h), which takes out the
// tracker's drift. What registration found is kept (PlacementChoices) so that the map can show the runners-up
// and the author can pick another one.
#include <memory>
#include <string>
#include <vector>

#include "processing/pipeline/step_result.h"
#include "processing/registration/plan_refinement.h"
#include "processing/registration/registration.h"
#include "processing/stills/candidate_fit.h"
#include "processing/util/progress.h"
#include "processing/visibility/shared_visibility_index.h"

namespace plenopath::pipeline {

struct PlacementChoices {
  CameraPath unplaced_path;  // the path registration ran on (each piece in the frame of its points)
  std::vector<PathPoint> unplaced_points;
  RegistrationResult result;
  std::vector<int> choice;  // candidate applied per piece (-1: left as it was)
  FloorPlan plan;           // the plan registration ran on (the refinement's walls)
  PlanRefinementOptions refinement_options;
  bool refine_on_walls = true;
  // Stills: a piece registration cannot place is left where the stills pipeline put it, which is not on
  // the plan: apply_placement marks it unplaced.
  bool unplace_failed = false;
  PlanRefinementReport refinement;  // of the choice applied last by run_place_on_plan
  bool empty() const { return result.pieces.empty(); }
};

struct PlaceStepOptions {
  double camera_height_m = 0.0;  // above the floor; 0 = the capture's (registration needs one)
  bool refine_on_walls = true;   // refine the placed pieces on the walls (false: one similarity per piece)
  // What must fit for the step to succeed (else it throws Error naming the pieces that did not):
  // kAny: at least one piece (the others stay as they were); kEvery: every piece (`plenopath register`
  // writes nothing otherwise); kNone: nothing (the end of tracking: the tracked path is worth having).
  enum class Require { kNone, kAny, kEvery } require = Require::kAny;
  std::vector<int> pick;  // candidate per piece (0 = best), one per piece; empty = by anchors, else the best
  std::shared_ptr<const SharedVisibilityIndex> visibility_index;  // for the cells that follow; null: built
  void check() const;                                             // throws Error naming the field
};

struct PlaceStepResult : StepResult {
  PlacementChoices choices;
  CandidateFitReport still_fit;  // stills: how what they see re-ranked the candidates
  int pieces_placed = 0;
};

// The path and points with `choice` applied (apply_registration), then refined on the walls when
// refine_on_walls (`report` gets how); throws Error on a choice out of range.
void apply_placement(const PlacementChoices& choices, const std::vector<int>& choice, CameraPath* path,
                     std::vector<PathPoint>* points, PlanRefinementReport* report = nullptr,
                     Progress& progress = null_progress());

// Why `project` cannot be placed on its plan ("the plan has no sight-blocking segments ..."), or "" when it
// can.
std::string placement_precondition(const Project& project, double camera_height_m = 0.0);

// Registers the project's path with its points (Project::path_points) on its plan and places path and
// points (pieces that fit; visibility cells follow the moved path when the project has any). Throws Error
// when the precondition fails or what options.require asks for does not fit (one line per piece,
// registration.h describe()); Cancelled on a cancel. changed: kPathChanged | kVisibilityChanged.
PlaceStepResult run_place_on_plan(Project project, const PlaceStepOptions& options,
                                  Progress& progress = null_progress());

}  // namespace plenopath::pipeline
