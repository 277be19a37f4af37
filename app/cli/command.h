#pragma once
// Every `plenopath` subcommand registers itself with add_*_command() and returns what main() runs when
// that subcommand was chosen. Conventions: long options, --json for machine-readable output, exit codes
// 0 ok / 1 failed / 2 bad usage / 130 cancelled by Ctrl+C, errors on stderr naming the file. Long steps
// report to a ConsoleProgress (console_progress.h), which Ctrl+C cancels.
#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

namespace plenopath::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitCancelled = 130;  // 128 + SIGINT, as shells report a program ended by Ctrl+C

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

// One line per subcommand; keep alphabetical. Each lives in command_<name>.cpp.
Command add_capture_info_command(CLI::App& parent);
Command add_encode_video_command(CLI::App& parent);
Command add_eval_path_command(CLI::App& parent);
Command add_export_command(CLI::App& parent);
Command add_import_tour_command(CLI::App& parent);
Command add_info_command(CLI::App& parent);
Command add_make_sample_command(CLI::App& parent);
Command add_place_still_command(CLI::App& parent);
Command add_plan_info_command(CLI::App& parent);
Command add_refine_command(CLI::App& parent);
Command add_register_command(CLI::App& parent);
Command add_render_command(CLI::App& parent);
Command add_render_scene_command(CLI::App& parent);
Command add_sample_command(CLI::App& parent);
Command add_stitch_command(CLI::App& parent);
Command add_track_command(CLI::App& parent);
Command add_visibility_command(CLI::App& parent);

}  // namespace plenopath::cli
