// `plenopath visibility (--plan PLAN.dxf [--layers ...] [--occluders ...] [--units U]
//                        (--point X,Y | --path PATH.json) | --project P.plenopath [--point X,Y] [--save])
//                       [--samples N] [--json]`
// For a point: its envelope polygon, area and status. For a path (a path file, or the project's): the
// visibility events (frame, path parameter) and the cells between them, computed by the pipeline's
// visibility step (processing/pipeline/visibility_step.h) as the studio's Process > Compute visibility;
// with --save they are written into the project.
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "model/error.h"
#include "model/path_io.h"
#include "model/project_io.h"
#include "processing/pipeline/visibility_step.h"
#include "processing/plan/dxf_import.h"
#include "processing/visibility/visibility.h"

namespace plenopath::cli {

Command add_visibility_command(CLI::App& parent) {
  struct Options {
    std::string plan;
    DxfImportOptions import;
    std::vector<double> point;
    std::string path;
    std::string project;
    int samples = 0;
    bool json = false;
    bool save = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub =
      parent.add_subcommand("visibility", "Envelope of a point, or events and cells along a path");
  auto* plan = sub->add_option("--plan", options->plan, "Floor plan (*.dxf, ASCII)");
  sub->add_option("--layers", options->import.layers, "Import only these layers (default: all)");
  sub->add_option("--occluders", options->import.occluder_layers,
                  "Layers that block sight (default: guessed from the names)");
  sub->add_option("--units", options->import.units_override, "Units of the file (mm, cm, m, in, ft, ...)");
  auto* point =
      sub->add_option("--point", options->point, "Query point X,Y in metres")->delimiter(',')->expected(2);
  auto* path = sub->add_option("--path", options->path, "Path file (JSON, metres)");
  point->excludes(path);
  auto* project =
      sub->add_option("--project", options->project,
                      "Project file: its plan and path (the cells along its path without --point)");
  project->excludes(plan)->excludes(path);
  sub->add_flag("--save", options->save, "Write the cells into the project (--project)")->needs(project);
  sub->add_option("--samples", options->samples, "Also sample the radial function at N azimuths (--point)")
      ->check(CLI::Range(0, 1000000));
  sub->add_flag("--json", options->json, "Machine-readable output");
  return {sub, [options, sub]() {
            const bool from_project = !options->project.empty();
            if (!from_project && options->plan.empty()) {
              std::cerr << "plenopath visibility: give --plan PLAN.dxf or --project P.plenopath\n"
                        << sub->help();
              return kExitUsage;
            }
            if (!from_project && options->point.empty() && options->path.empty()) {
              std::cerr << "plenopath visibility: give --point X,Y or --path PATH.json\n" << sub->help();
              return kExitUsage;
            }
            Project project;
            if (from_project)
              project = load_project(options->project);
            else
              project.plan = import_dxf(options->plan, options->import);
            nlohmann::json out = {{"plan", from_project ? options->project : options->plan}};
            if (!options->point.empty()) {
              const VisibilityIndex index(project.plan);
              const Eigen::Vector2d p(options->point[0], options->point[1]);
              const Envelope e = index.envelope(p);
              nlohmann::json polygon = nlohmann::json::array();
              for (const auto& q : e.polygon) polygon.push_back({q.x(), q.y()});
              out["point"] = {p.x(), p.y()};
              out["status"] = to_string(e.status);
              out["area_m2"] = e.area;
              out["polygon"] = polygon;
              if (options->samples > 0) out["radial_m"] = index.radial_function(p, options->samples);
              if (options->json) {
                std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
              } else {
                std::cout << std::fixed << std::setprecision(3) << "Point     (" << p.x() << ", " << p.y()
                          << "): " << to_string(e.status) << "\nEnvelope  " << e.area << " m^2, "
                          << e.polygon.size() << " vertices\n";
              }
              return kExitOk;
            }
            if (!from_project) project.path = read_path_file(options->path);
            ConsoleProgress progress("visibility");
            pipeline::StepResult result = pipeline::run_visibility(std::move(project), {}, progress);
            progress.finish();
            const CameraPath& camera_path = result.project.path;
            const VisibilityCells& cells = result.project.visibility;
            if (options->save) save_project(result.project, options->project);
            nlohmann::json events = nlohmann::json::array(), cell_list = nlohmann::json::array();
            for (const auto& e : cells.events) events.push_back({{"frame", e.frame}, {"s", e.s}});
            for (const auto& c : cells.cells)
              cell_list.push_back({{"first_frame", c.first_frame},
                                   {"last_frame", c.last_frame},
                                   {"s_begin", c.s_begin},
                                   {"s_end", c.s_end},
                                   {"length_m", c.length},
                                   {"area_mid_m2", c.area_mid},
                                   {"area_mean_m2", c.area_mean}});
            out["path"] = from_project ? options->project : options->path;
            if (options->save) out["saved"] = options->project;
            out["frames"] = camera_path.size();
            out["length_m"] = camera_path.length();
            out["events"] = events;
            out["cells"] = cell_list;
            out["critical_lines"] = cells.critical_lines.size();
            if (options->json) {
              std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            } else {
              std::cout << std::fixed << std::setprecision(3) << "Path      " << camera_path.size()
                        << " frames, " << camera_path.length() << " m\nEvents    " << cells.events.size()
                        << "\nCells     " << cells.cells.size() << "\n";
              for (const auto& c : cells.cells)
                std::cout << "  frames " << c.first_frame << "-" << c.last_frame << "  l " << c.length
                          << " m  v " << c.area_mid << " m^2\n";
            }
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
