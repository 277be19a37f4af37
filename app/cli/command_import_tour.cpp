// `plenopath import-tour --package DIR|tour.json|FILE.zip --project P.plenopath [--json]`: re-opens a
// published tour for editing. The keyframe images and hotspot media go to P_tour/ beside the project.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "model/error.h"
#include "model/project_io.h"
#include "processing/export/tour_import.h"

namespace plenopath::cli {

Command add_import_tour_command(CLI::App& parent) {
  struct Options {
    std::string package, project;
    bool json = false, force = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand(
      "import-tour", "Make a project from a published tour (folder, tour.json or .zip) to edit it again");
  sub->add_option("--package", o->package, "The tour: its folder, its tour.json, or its .zip")->required();
  sub->add_option("--project", o->project, "The project file to make (*.plenopath)")->required();
  sub->add_flag("--force", o->force, "Replace the project file if it exists (its media folder never is)");
  sub->add_flag("--json", o->json, "Machine-readable report");
  return {sub, [o]() {
            std::error_code ec;
            if (!o->force && std::filesystem::exists(o->project, ec))
              throw file_error(o->project, "already exists (--force replaces it)");
            ConsoleProgress progress("import-tour");
            const TourImportResult result = import_tour({o->package, o->project}, progress);
            save_project(result.project, o->project);
            progress.finish();
            for (const std::string& w : result.warnings) std::cerr << "import-tour: warning: " << w << "\n";
            if (o->json) {
              std::cout << nlohmann::json{{"project", o->project},
                                          {"media_folder", result.media_folder},
                                          {"keyframes", result.keyframes},
                                          {"path_frames", result.project.path.frames.size()},
                                          {"hotspots", result.project.hotspots.size()},
                                          {"media_files", result.media_files},
                                          {"warnings", result.warnings}}
                               .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
                        << "\n";
            } else {
              std::cout << "Imported " << result.keyframes << " keyframes, "
                        << result.project.path.frames.size() << " path frames and "
                        << result.project.hotspots.size() << " hotspots into " << o->project << " (images in "
                        << result.media_folder << ")\n";
            }
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
