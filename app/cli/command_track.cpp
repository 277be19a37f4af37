// `plenopath track --capture DIR|VIDEO [--camera-height M] [--out PATH.json] [--json]`: the camera path
// from the panoramas alone (processing/egomotion/egomotion.h). Progress goes to stderr.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "model/error.h"
#include "model/path_io.h"
#include "processing/egomotion/egomotion.h"
#include "processing/frame_source.h"

namespace plenopath::cli {

Command add_track_command(CLI::App& parent) {
  struct Options {
    std::string capture;
    double camera_height = 0.0;
    std::string out;
    bool json = false;
    bool quiet = false;
    int work_width = 1024;
    std::vector<double> known_distance;  // frame a, frame b, metres
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand("track", "Recover the camera path (x, y, heading per frame) from the panoramas");
  sub->add_option("--capture", options->capture, "Folder of equirectangular frames (natural sort order) or a video")
      ->required();
  sub->add_option("--camera-height", options->camera_height,
                  "Camera height above the floor in metres: gives metric scale (else the scale is relative)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--known-distance", options->known_distance,
                  "Metric scale from a distance the author knows: FRAME_A FRAME_B METRES (used without --camera-height)")
      ->expected(3);
  sub->add_option("--out", options->out, "Write the path file here (JSON, see ARCHITECTURE.md)");
  sub->add_option("--work-width", options->work_width, "Tracking resolution (frames are resized to this width)")
      ->check(CLI::Range(64, 16384));
  sub->add_flag("--json", options->json, "Machine-readable summary on stdout");
  sub->add_flag("--quiet", options->quiet, "No progress on stderr");
  return {sub, [options]() {
            std::unique_ptr<FrameSource> source = FrameSource::open(options->capture);
            EgomotionOptions eo;
            eo.camera_height_m = options->camera_height;
            eo.klt.work_width = options->work_width;
            if (options->known_distance.size() == 3) {
              eo.scale_frame_a = static_cast<int>(options->known_distance[0]);
              eo.scale_frame_b = static_cast<int>(options->known_distance[1]);
              eo.scale_distance_m = options->known_distance[2];
              const std::string bad = eo.check();
              if (!bad.empty()) throw Error("--known-distance: " + bad);
            }
            const int n = source->frame_count();
            int last_percent = -1;
            std::string last_stage;
            auto progress = [&](const std::string& stage, double f) {
              const int percent = static_cast<int>(std::floor(100 * f));
              if (!options->quiet && (percent / 10 != last_percent / 10 || stage != last_stage)) {
                std::cerr << "track: " << stage << " " << percent << "%\n";
                last_percent = percent;
                last_stage = stage;
              }
              return true;
            };
            EgomotionResult r = EgomotionTracker::run(n, [&](int i) { return source->read(i); }, eo, progress);
            for (int i = 0; i < n && i < static_cast<int>(r.path.frames.size()); ++i) {
              if (source->kind() == CaptureKind::kImageFolder) r.path.frames[i].file = source->frame_name(i);
            }
            if (!options->out.empty()) write_path_file(r.path, options->out);
            const nlohmann::json summary = {
                {"capture", options->capture},
                {"frames", r.path.size()},
                {"keyframes", r.keyframes.size()},
                {"points", r.points},
                {"length", r.path.length()},
                {"scale_source", r.scale_source},
                {"flagged_frames", r.flagged_frames},
                {"refinement_rms_deg", r.refinement.final_rms * 180.0 / M_PI},
                {"seconds", r.seconds_per_frame_stage + r.seconds_geometry},
                {"out", options->out}};
            if (options->json) {
              std::cout << summary.dump(2) << "\n";
            } else {
              std::cout << "Tracked " << r.path.size() << " frames (" << r.keyframes.size() << " keyframes, "
                        << r.points << " points), path length " << std::fixed << std::setprecision(2)
                        << r.path.length() << (r.scale_source == "relative" ? " (relative units)" : " m")
                        << ", scale from " << r.scale_source << ", " << r.flagged_frames << " frames flagged\n";
              if (!options->out.empty()) std::cout << "Wrote " << options->out << "\n";
            }
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
