// `plenopath refine --project P.plenopath [--anchors ANCHORS.json] [--out OUT.plenopath] [--preview]
// [--json]`: bends the project's path onto the author's anchors (Ceres pose graph with drift; --preview: the
// fast warp) and saves the project (atomically, keeping FILE.bak).
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "model/anchors_io.h"
#include "model/error.h"
#include "model/project_io.h"
#include "processing/anchors/anchor_refinement.h"
#include "processing/pipeline/refine_step.h"

namespace plenopath::cli {

Command add_refine_command(CLI::App& parent) {
  struct Options {
    std::string project, anchors, out;
    bool preview = false, json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand("refine", "Correct path drift with anchors (frame -> plan position)");
  sub->add_option("--project", o->project, "Project file (*.plenopath)")->required();
  sub->add_option("--anchors", o->anchors,
                  "Anchors file: [{\"index\", \"x\", \"y\", \"heading_deg\"?}, ...]; "
                  "default: the project's anchors (the file's replace them)");
  sub->add_option("--out", o->out, "Write the corrected project here (default: in place, keeping .bak)");
  sub->add_flag("--preview", o->preview, "Only the fast warp between anchors, no refinement");
  sub->add_flag("--json", o->json, "Machine-readable report");
  return {sub, [o]() {
            Project project = load_project(o->project);
            if (!o->anchors.empty()) project.anchors = read_anchors_file(o->anchors);
            // The capture's GPS track, when there is one and the plan is on Earth, adds weak priors.
            std::vector<GpsPrior> gps;
            if (!o->preview) {
              gps = gps_priors_for_path(project);
              if (!gps.empty())
                std::cerr << "refine: " << gps.size() << " frames have a GPS fix (weak priors)\n";
            }
            if (project.anchors.empty() && gps.size() < 2)
              throw plenopath::Error(o->project +
                                     ": no anchors (place some in the studio or pass --anchors FILE)");
            // The pipeline's step, as the studio's Process > Refine with anchors (the cells follow the path).
            pipeline::RefineStepOptions options;
            options.preview = o->preview;
            ConsoleProgress progress("refine", o->preview);
            pipeline::RefineStepResult result = pipeline::run_refine(std::move(project), options, progress);
            progress.finish();
            project = std::move(result.project);
            const AnchorRefinementReport& report = result.report;
            const std::string out = o->out.empty() ? o->project : o->out;
            save_project(project, out);
            nlohmann::json residuals = nlohmann::json::array();
            for (const Anchor& a : project.anchors) {
              const PathFrame* f = project.path.find_frame(a.frame);
              if (!f) continue;
              residuals.push_back({{"index", a.frame}, {"distance_m", (f->position() - a.position).norm()}});
            }
            if (o->json) {
              std::cout << nlohmann::json{{"project", out},
                                          {"anchors", project.anchors.size()},
                                          {"method", o->preview ? "preview" : "refine"},
                                          {"iterations", report.iterations},
                                          {"gps_fixes", gps.size()},
                                          {"residuals", residuals}}
                               .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
                        << "\n";
            } else {
              std::cout << (o->preview ? "Warped" : "Refined") << " " << project.path.size()
                        << " frames onto " << project.anchors.size() << " anchors; saved " << out << "\n";
              for (const auto& r : residuals)
                std::cout << "  frame " << r["index"] << ": " << std::fixed << std::setprecision(3)
                          << r["distance_m"].get<double>() << " m from its anchor\n";
            }
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
