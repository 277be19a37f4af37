#include "app/studio/placement.h"

#include <cstdio>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/stills/candidate_fit.h"
#include "widgets/anchor_commands.h"

namespace plenopath::studio {

void apply_placement(const PlacementChoices& choices, const std::vector<int>& choice, CameraPath* path,
                     std::vector<PathPoint>* points, PlanRefinementReport* report, Progress& progress) {
  std::vector<PathPoint> moved = choices.unplaced_points;
  CameraPath placed = apply_registration(choices.unplaced_path, choices.result, choice, &moved);
  if (choices.refine_on_walls && !choices.plan.occluder_segments().empty())
    placed = refine_on_plan(placed, &moved, choices.plan, choices.refinement_options, report, progress);
  *path = std::move(placed);
  if (points) *points = std::move(moved);
}

std::string placement_precondition(const Project& project) {
  if (project.plan.empty()) return "the project has no plan: import the DXF floor plan first";
  if (project.plan.occluder_segments().empty())
    return "the plan has no sight-blocking layer: mark the walls' layer as blocking sight first";
  if (project.path.empty()) return "the project has no camera path: track the capture first";
  if (project.path_points.empty())
    return "the path has no tracked points (it was imported, or tracked before points were kept): "
           "track the capture again";
  if (!(project.capture.camera_height_m > 0))
    return "the camera height is unknown: set it in File > Import capture (it gives the metric scale)";
  return {};
}

PlacementChoices place_project_on_plan(Project& project, Progress& progress, bool require_fit,
                                       std::string* summary) {
  if (const std::string why = placement_precondition(project); !why.empty()) throw Error(why);
  RegistrationOptions options;
  options.camera_height_m = project.capture.camera_height_m;
  options.check();
  PlacementChoices choices;
  choices.unplaced_path = project.path;
  choices.unplaced_points = project.path_points;
  choices.plan = project.plan;
  choices.refinement_options.registration = options;
  SubProgress search(progress, 0.0, 0.8, "registration");
  choices.result = register_on_plan(project.path, project.path_points, project.plan, options, search);
  if (project.capture.stills && project.capture.kind == CaptureKind::kImageFolder) {
    // Repeated rooms fit a group's points alike: what the stills see picks among the placements.
    const auto source = FrameSource::open_capture(project.capture);
    CandidateFitOptions fit_options;
    fit_options.fit.camera_height_m = options.camera_height_m;
    SubProgress fitting(progress, 0.8, 0.85, "the stills against the plan");
    rerank_by_still_fit(
        &choices.result, project.path, [&](int i) { return source->read(i); }, project.plan, fit_options,
        fitting);
  }

  int fitted = 0;
  std::string failures;
  choices.choice.assign(choices.result.pieces.size(), -1);
  for (std::size_t k = 0; k < choices.result.pieces.size(); ++k) {
    const PieceRegistration& piece = choices.result.pieces[k];
    if (!piece.ok) {
      failures += "piece " + std::to_string(piece.piece + 1) + ": " + describe(piece) + "\n";
      continue;
    }
    ++fitted;
    // An anchor on the piece decides between candidates (a symmetric building); else the best.
    const int by_anchor = candidate_for_anchors(choices.unplaced_path, piece, project.anchors);
    choices.choice[k] = by_anchor >= 0 ? by_anchor : 0;
  }
  if (fitted == 0 && require_fit) {
    if (!failures.empty() && failures.back() == '\n') failures.pop_back();
    throw Error("no piece of the path fits the plan:\n" + failures);
  }
  CameraPath placed;
  SubProgress refining(progress, 0.85, 1.0, "refinement on the walls");
  apply_placement(choices, choices.choice, &placed, &project.path_points, &choices.refinement, refining);
  if (std::optional<VisibilityCells> cells = widgets::cells_following_path(project, placed))
    project.visibility = std::move(*cells);
  project.path = std::move(placed);

  if (summary) {
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
      std::snprintf(line, sizeof line,
                    "placed %d of %zu piece(s) on the plan: score %.2f, %.0f %% of wall points on walls, "
                    "%.1f s",
                    fitted, choices.result.pieces.size(), c.score, 100.0 * c.wall_share,
                    choices.result.seconds);
      *summary = line;
      int refined = 0;
      for (const PieceRefinement& r : choices.refinement.pieces) refined += r.kept ? 1 : 0;
      if (refined > 0) *summary += "; " + std::to_string(refined) + " piece(s) refined on the walls";
      if (fitted < static_cast<int>(choices.result.pieces.size()))
        *summary += "; not placed: " + failures.substr(0, failures.find('\n'));
    } else {
      *summary = "not placed on the plan: " + failures.substr(0, failures.find('\n'));
    }
  }
  return choices;
}

}  // namespace plenopath::studio
