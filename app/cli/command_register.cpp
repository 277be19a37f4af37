// `plenopath register --project P.plenopath [--points P.points.json] [--camera-height M] [--pick K ...]
// [--out OUT.plenopath] [--no-refine] [--json] [--quiet]`: places the project's path on its plan by the
// tracker's points (processing/registration/registration.h), each piece on its own, refines it on the walls
// (plan_refinement.h) unless --no-refine, and saves the project (atomically,
// keeping FILE.bak) with the points sidecar moved alike. No piece is written unless every piece fits.
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "app/cli/registration_common.h"
#include "model/error.h"
#include "model/path_points.h"
#include "model/project_io.h"
#include "processing/pipeline/place_step.h"
#include "processing/registration/registration.h"

namespace plenopath::cli {

Command add_register_command(CLI::App& parent) {
  struct Options {
    std::string project, points, out;
    double camera_height = 0.0;
    std::vector<int> pick;
    bool json = false, quiet = false, no_refine = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand("register", "Place the project's path on its plan by itself");
  sub->add_option("--project", o->project, "Project file (*.plenopath) with a plan and a tracked path")
      ->required();
  sub->add_option("--points", o->points,
                  "The tracker's points (default: PROJECT.points.json beside the project, as track writes)");
  sub->add_option("--camera-height", o->camera_height,
                  "Camera height above the floor, metres (default: the project capture's)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--pick", o->pick,
                  "Candidate to apply per piece (1 = best; one number per piece), e.g. for a symmetric plan")
      ->check(CLI::PositiveNumber);
  sub->add_option("--out", o->out, "Write the placed project here (default: in place, keeping .bak)");
  sub->add_flag("--no-refine", o->no_refine,
                "Place each piece by one similarity only (default: then refine the path on the walls, which "
                "takes out drift)");
  sub->add_flag("--json", o->json, "Machine-readable summary on stdout");
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return {sub, [o]() {
            Project project = load_project(o->project);
            const std::string points_file = o->points.empty() ? points_file_beside(o->project) : o->points;
            if (!std::filesystem::exists(points_file))
              throw Error(points_file +
                          ": no points file (track the capture with --out beside the project, or "
                          "give --points)");
            std::vector<PathPoint> points = read_path_points_file(points_file);
            if (project.path.empty()) throw Error(o->project + ": the project has no path to register");
            if (project.plan.empty()) throw Error(o->project + ": the project has no plan to register on");
            const double camera_height =
                o->camera_height > 0 ? o->camera_height : project.capture.camera_height_m;
            if (!(camera_height > 0))
              throw Error(o->project + ": the capture's camera height is unknown: give --camera-height");
            project.path_points = std::move(points);
            // The pipeline's step, as the studio's Process > Place path on plan; nothing is written unless
            // every piece fits (checked below, after the report).
            pipeline::PlaceStepOptions options;
            options.camera_height_m = camera_height;
            options.refine_on_walls = !o->no_refine;
            options.require = pipeline::PlaceStepOptions::Require::kNone;
            for (int k : o->pick) options.pick.push_back(k - 1);
            if (!options.pick.empty() && static_cast<int>(options.pick.size()) != project.path.piece_count())
              throw Error("--pick: " + std::to_string(options.pick.size()) + " numbers for " +
                          std::to_string(project.path.piece_count()) + " piece(s)");
            const std::size_t points_count = project.path_points.size();
            ConsoleProgress progress("register", o->quiet);
            pipeline::PlaceStepResult placed = pipeline::run_place_on_plan(project, options, progress);
            progress.finish();
            const RegistrationResult& result = placed.choices.result;
            const PlanRefinementReport& refinement = placed.choices.refinement;
            nlohmann::json summary = registration_to_json(result);
            summary["project"] = o->project;
            summary["points"] = points_file;
            summary["points_count"] = points_count;
            if (!o->no_refine && result.all_ok())
              summary["plan_refinement"] = plan_refinement_to_json(refinement);
            const std::string out = o->out.empty() ? o->project : o->out;
            bool written = false;
            if (result.all_ok()) {
              project = std::move(placed.project);
              save_project(project, out);
              write_path_points_file(project.path_points, points_file_beside(out));
              written = true;
            }
            summary["out"] = written ? nlohmann::json(out) : nlohmann::json(nullptr);
            if (o->json) {
              std::cout << summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            } else {
              std::cout << "Registered " << project.path.size() << " frames in " << result.pieces.size()
                        << " piece(s) on the plan:\n";
              print_registration(std::cout, result);
              print_plan_refinement(std::cout, refinement);
              if (written) std::cout << "Wrote " << out << "\n";
            }
            require_registered(result, o->project);
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
