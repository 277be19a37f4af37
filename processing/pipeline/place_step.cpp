#include "processing/pipeline/place_step.h"

#include <algorithm>
#include <cstdio>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/capture/frame_source.h"
#include "processing/pipeline/visibility_step.h"

namespace plenopath::pipeline {

// A group of stills registers on the plan by its own points from this many stills up.
constexpr long kMinStillsToRegister = 3;

void PlaceStepOptions::check() const {
  require_option(camera_height_m >= 0, "PlaceStepOptions.camera_height_m", "must be >= 0 (0: the capture's)",
                 camera_height_m);
  for (int k : pick) require_option(k >= 0, "PlaceStepOptions.pick", "must be >= 0 per piece", k);
}

void apply_placement(const PlacementChoices& choices, const std::vector<int>& choice, CameraPath* path,
                     std::vector<PathPoint>* points, PlanRefinementReport* report, Progress& progress) {
  std::vector<PathPoint> moved = choices.unplaced_points;
  CameraPath placed = apply_registration(choices.unplaced_path, choices.result, choice, &moved);
  if (choices.unplace_failed)
    for (const PieceRegistration& p : choices.result.pieces)
      if (!p.ok && p.piece >= 0 && p.piece < static_cast<int>(placed.pieces.size()))
        placed.pieces[static_cast<std::size_t>(p.piece)].placed = false;
  if (choices.refine_on_walls && !choices.plan.occluder_segments().empty())
    placed = refine_on_plan(placed, &moved, choices.plan, choices.refinement_options, report, progress);
  *path = std::move(placed);
  if (points) *points = std::move(moved);
}

std::string placement_precondition(const Project& project, double camera_height_m) {
  if (project.plan.empty()) return "the project has no plan: import the DXF floor plan first";
  if (project.plan.occluder_segments().empty())
    return "the plan has no sight-blocking segments: mark the walls' layer as blocking sight first";
  if (project.path.empty()) return "the project has no camera path: track the capture first";
  if (project.path_points.empty())
    return "the path has no tracked points (it was imported, or tracked before points were kept): "
           "track the capture again";
  if (!(camera_height_m > 0) && !(project.capture.camera_height_m > 0))
    return "the camera height is unknown: set it in File > Import capture (it gives the metric scale)";
  return {};
}

PlaceStepResult run_place_on_plan(Project project, const PlaceStepOptions& options, Progress& progress) {
  options.check();
  progress.checkpoint(0.0, "placing " + std::to_string(project.path.size()) + " frames on the plan");
  if (const std::string why = placement_precondition(project, options.camera_height_m); !why.empty())
    throw Error(why);
  RegistrationOptions registration;
  registration.camera_height_m =
      options.camera_height_m > 0 ? options.camera_height_m : project.capture.camera_height_m;
  const bool stills = project.capture.stills && project.capture.kind == CaptureKind::kImageFolder;
  registration.check();
  PlaceStepResult out;
  PlacementChoices& choices = out.choices;
  choices.unplaced_path = project.path;
  choices.unplaced_points = project.path_points;
  choices.plan = project.plan;
  choices.refinement_options.registration = registration;
  choices.refine_on_walls = options.refine_on_walls;
  SubProgress search(progress, 0.0, 0.8, "registration");
  choices.result = register_on_plan(project.path, project.path_points, project.plan, registration, search);
  choices.unplace_failed = stills;
  if (stills) {
    // Repeated rooms fit a group's points alike: what the stills see picks among the placements.
    const auto source = FrameSource::open_capture(project.capture);
    CandidateFitOptions fit_options;
    fit_options.fit.camera_height_m = registration.camera_height_m;
    SubProgress fitting(progress, 0.8, 0.85, "the stills against the plan");
    out.still_fit = rerank_by_still_fit(
        &choices.result, project.path,
        [&](int index) { return source->read(project.capture.kept_of_frame_index(index)); }, project.plan,
        fit_options, fitting);
    // Two stills measure their points along one baseline: a turn of their pair is not seen in the points.
    // Such a group is placed through its pairs to placed stills, or by capture order, instead.
    for (PieceRegistration& piece : choices.result.pieces) {
      const long stills_in_piece = std::count_if(project.path.frames.begin(), project.path.frames.end(),
                                                 [&](const PathFrame& f) { return f.piece == piece.piece; });
      if (piece.ok && stills_in_piece < kMinStillsToRegister) {
        piece.ok = false;
        piece.message = "a group of " + std::to_string(stills_in_piece) +
                        " stills is placed by its pairs to placed stills, not by its points alone";
      }
    }
  }

  const int pieces = static_cast<int>(choices.result.pieces.size());
  if (!options.pick.empty() && static_cast<int>(options.pick.size()) != pieces)
    throw Error("PlaceStepOptions.pick: " + std::to_string(options.pick.size()) + " candidates for " +
                std::to_string(pieces) + " piece(s)");
  int fitted = 0;
  std::string failures;
  choices.choice.assign(choices.result.pieces.size(), -1);
  for (std::size_t k = 0; k < choices.result.pieces.size(); ++k) {
    const PieceRegistration& piece = choices.result.pieces[k];
    if (!piece.ok) {
      failures += describe(piece) + "\n";  // "piece N: why"
      continue;
    }
    ++fitted;
    if (!options.pick.empty()) {
      choices.choice[k] = options.pick[k];
      continue;
    }
    // An anchor on the piece decides between candidates (a symmetric building); else the best.
    const int by_anchor = candidate_for_anchors(choices.unplaced_path, piece, project.anchors);
    choices.choice[k] = by_anchor >= 0 ? by_anchor : 0;
  }
  out.pieces_placed = fitted;
  if (!failures.empty() && failures.back() == '\n') failures.pop_back();
  if ((fitted == 0 && options.require == PlaceStepOptions::Require::kAny) ||
      (fitted < pieces && options.require == PlaceStepOptions::Require::kEvery))
    throw Error((fitted == 0 ? "no piece of the path fits the plan:\n" : "not every piece fits the plan:\n") +
                failures);
  CameraPath placed;
  SubProgress refining(progress, 0.85, 0.97, "refinement on the walls");
  apply_placement(choices, choices.choice, &placed, &project.path_points, &choices.refinement, refining);
  SubProgress cells_progress(progress, 0.97, 1.0, "visibility cells along the placed path");
  if (std::optional<VisibilityCells> cells =
          cells_following_path(project, placed, cells_progress, options.visibility_index.get()))
    project.visibility = std::move(*cells);
  project.path = std::move(placed);

  char line[200];
  const PieceRegistration* first = nullptr;
  for (const PieceRegistration& p : choices.result.pieces)
    if (p.ok) {
      first = &p;
      break;
    }
  if (first) {
    const RegistrationCandidate& c =
        first->candidates[static_cast<std::size_t>(choices.choice[static_cast<std::size_t>(first->piece)])];
    std::snprintf(
        line, sizeof line,
        "placed %d of %zu piece(s) on the plan: score %.2f, %.0f %% of wall points on walls, %.1f s", fitted,
        choices.result.pieces.size(), c.score, 100.0 * c.wall_share, choices.result.seconds);
    out.summary = line;
    int refined = 0;
    for (const PieceRefinement& r : choices.refinement.pieces) refined += r.kept ? 1 : 0;
    if (refined > 0) out.summary += "; " + std::to_string(refined) + " piece(s) refined on the walls";
    if (fitted < pieces) out.summary += "; not placed: " + failures.substr(0, failures.find('\n'));
  } else {
    out.summary = "not placed on the plan: " + failures.substr(0, failures.find('\n'));
  }
  progress.report(1.0, out.summary);
  out.project = std::move(project);
  out.changed = kPathChanged | kVisibilityChanged;
  return out;
}

}  // namespace plenopath::pipeline
