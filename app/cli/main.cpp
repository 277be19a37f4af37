// `plenopath`: the command line. No Qt Widgets here; everything it runs lives in processing/.
#include <iostream>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "model/error.h"
#include "processing/util/progress.h"

int main(int argc, char** argv) {
  using namespace plenopath::cli;
  CLI::App app{"Plenopath Studio command line: plenoptic path recovery, visibility, sampling and export"};
  app.set_version_flag("--version", std::string("plenopath ") + PLENOPATH_VERSION);
  app.require_subcommand(0, 1);

  std::vector<Command> commands = {
      add_capture_info_command(app), add_encode_video_command(app), add_eval_path_command(app),
      add_export_command(app),       add_import_tour_command(app),  add_info_command(app),
      add_make_sample_command(app),  add_place_still_command(app),  add_plan_info_command(app),
      add_refine_command(app),       add_register_command(app),     add_render_command(app),
      add_render_scene_command(app), add_sample_command(app),       add_stitch_command(app),
      add_track_command(app),        add_visibility_command(app),
  };

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }
  // Ctrl+C cancels the running step (every long step polls it through its ConsoleProgress).
  install_interrupt_handler();
  for (const Command& c : commands) {
    if (!c.app->parsed()) continue;
    try {
      return c.run();
    } catch (const plenopath::Cancelled&) {
      std::cerr << "plenopath " << c.app->get_name() << ": cancelled\n";
      return kExitCancelled;
    } catch (const plenopath::Error& e) {
      std::cerr << "plenopath " << c.app->get_name() << ": error: " << e.what() << "\n";
      return kExitFailed;
    } catch (const std::exception& e) {
      std::cerr << "plenopath " << c.app->get_name() << ": internal error: " << e.what() << "\n";
      return kExitFailed;
    }
  }
  std::cout << app.help();
  return kExitUsage;
}
