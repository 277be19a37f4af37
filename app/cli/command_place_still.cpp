// `plenopath place-still` (issue 20): a still panorama placed on the plan from where the author says the
// tripod stood, its heading and position then found by lining the plan's walls up with the still
// (processing/stills/still_on_plan.h).
//   --project P --frame INDEX --at X Y [--toward X Y] [--out OUT]: the project's still (a capture index,
//     as the path numbers it) and its piece placed, the project saved (atomically, keeping FILE.bak);
//   --plan PLAN.dxf --image FILE --at X Y [--toward X Y] --camera-height M: a bare image, nothing written.
// --toward X Y is a second click: a point of the plan the still's centre looks towards.
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "model/error.h"
#include "model/project_io.h"
#include "processing/capture/frame_source.h"
#include "processing/plan/dxf_import.h"
#include "processing/stills/still_on_plan.h"

namespace plenopath::cli {

Command add_place_still_command(CLI::App& parent) {
  struct Options {
    std::string project, out, plan, image;
    int frame = -1;
    std::vector<double> at, toward;
    std::string overlay;  // the still with the plan's curves at the pose found
    double camera_height = 0.0, radius = StillOnPlanOptions{}.search_radius_m;
    bool json = false, quiet = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand(
      "place-still", "Place a still panorama on the plan from roughly where it was shot (one click)");
  CLI::Option* project = sub->add_option("--project", o->project, "Project file (*.plenopath)");
  sub->add_option("--frame", o->frame, "With --project: the still's frame index in the path")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--out", o->out,
                  "With --project: write the project here (default: in place, keeping .bak)");
  CLI::Option* plan =
      sub->add_option("--plan", o->plan, "Floor plan (DXF) for a bare image")->excludes(project);
  sub->add_option("--image", o->image, "With --plan: the still panorama (equirectangular)")->needs(plan);
  sub->add_option("--at", o->at, "Where the tripod stood, roughly: X Y in plan metres")
      ->expected(2)
      ->required();
  sub->add_option("--toward", o->toward, "A point X Y the still's centre looks towards (a second click)")
      ->expected(2);
  sub->add_option("--camera-height", o->camera_height,
                  "Nodal point above the floor, metres (default: the project capture's)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--radius", o->radius, "Search this far around --at, metres")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  sub->add_option("--overlay", o->overlay,
                  "Write the still with the plan's walls at the pose found drawn over it (red) and the "
                  "still's edges they were lined up with (green), PNG");
  sub->add_flag("--json", o->json, "Machine-readable summary on stdout");
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return {sub, [o]() {
            if (o->project.empty() == o->plan.empty())
              throw Error("give --project with --frame, or --plan with --image");
            Project p;
            FloorPlan floor_plan;
            cv::Mat still;
            double height = o->camera_height;
            std::string what;
            if (!o->project.empty()) {
              if (o->frame < 0) throw Error("--project needs --frame (the still's index in the path)");
              p = load_project(o->project);
              if (p.plan.empty()) throw Error(o->project + ": the project has no plan to place the still on");
              if (!p.path.find_frame(o->frame))
                throw Error(o->project + ": the path has no frame " + std::to_string(o->frame));
              if (p.capture.kind != CaptureKind::kImageFolder)
                throw Error(o->project + ": stills are placed from an image folder capture");
              const auto source = FrameSource::open_capture(p.capture);
              if (o->frame >= source->frame_count())
                throw Error(o->project + ": frame " + std::to_string(o->frame) + " is beyond the capture's " +
                            std::to_string(source->frame_count()) + " frames");
              still = source->read(o->frame);
              floor_plan = p.plan;
              if (!(height > 0)) height = p.capture.camera_height_m;
              what = source->frame_name(o->frame);
            } else {
              if (o->image.empty()) throw Error("--plan needs --image (the still panorama)");
              floor_plan = import_dxf(o->plan);
              still = cv::imread(o->image, cv::IMREAD_COLOR);
              if (still.empty()) throw Error(o->image + ": cannot read the image");
              what = o->image;
            }
            if (!(height > 0)) throw Error("the camera height is unknown: give --camera-height");
            StillOnPlanOptions options;
            options.camera_height_m = height;
            options.search_radius_m = o->radius;
            const Eigen::Vector2d click(o->at[0], o->at[1]);
            if (o->toward.size() == 2) {
              const Eigen::Vector2d d = Eigen::Vector2d(o->toward[0], o->toward[1]) - click;
              if (d.norm() < 1e-6) throw Error("--toward is the same point as --at: no direction");
              options.heading_hint_deg = std::atan2(d.y(), d.x()) * 180.0 / M_PI;
            }
            ConsoleProgress progress("place-still", o->quiet);
            const StillPlacement placed = place_still_on_plan(still, floor_plan, click, options, progress);
            progress.finish();
            nlohmann::json summary = {{"still", what},
                                      {"x", placed.x},
                                      {"y", placed.y},
                                      {"heading_deg", placed.heading_deg},
                                      {"score_px", placed.score_px},
                                      {"runner_up_heading_deg", placed.runner_up_heading_deg},
                                      {"runner_up_score_px", placed.runner_up_score_px},
                                      {"samples", placed.samples},
                                      {"seconds", placed.seconds},
                                      {"summary", placed.summary}};
            if (!o->overlay.empty() &&
                !cv::imwrite(o->overlay, draw_plan_on_still(still, floor_plan, placed.x, placed.y,
                                                            placed.heading_deg, options)))
              throw Error(o->overlay + ": cannot write the overlay");
            if (!o->project.empty()) {
              p.path = path_with_still_placed(p.path, o->frame, placed);
              p.visibility = {};  // cells belong to the old path
              const std::string out = o->out.empty() ? o->project : o->out;
              save_project(p, out);
              summary["out"] = out;
            }
            if (o->json)
              std::cout << summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            else
              std::cout << what << ": " << placed.summary << "\n";
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
