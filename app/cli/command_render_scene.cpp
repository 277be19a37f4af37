// `plenopath render-scene --scene SCENE.pov|SCENE.blend (--path PATH.json | --waypoints "X,Y X,Y ...")
// [--step 0.1] [--frames N] [--size 2048x1024] [--camera-height 1.6] [--units-per-metre 1] [--no-depth]
// [--jpeg-quality Q] [--online [--budget N | --ratio R] [--loss-target L] [--coarse-width 256]]
// [--project P.plenopath [--plan PLAN.dxf | --section-plan]] --out DIR`, with for POV-Ray
// [--z-up] [--depth-fog 8] [--quality 9] [--no-antialias] [--povray PROGRAM] [--processes N]
// [--frames-per-process N], for Blender [--samples N] [--blender PROGRAM]:
// the author's own POV-Ray scene (processing/capture/povray_render.h) or Blender scene (Cycles,
// processing/capture/blender_render.h; by the extension) rendered with the studio's spherical camera along a
// path, colour and depth, with the poses as ground truth. The output is laid
// out as `plenopath render`'s: DIR/groundtruth.json (the path, with `file` fields), DIR/frames/NNNNNN.jpg,
// DIR/depth/NNNNNN.png (16-bit millimetres), so `track`, `sample` and the studio take it as a capture.
// --online renders the whole path as coarse depth first and only the keyframes the depth sampler chooses
// at full size (processing/sampling/online_sampling.h); the capture is then those keyframes, and
// DIR/online_sampling.json says how many of the path's frames were rendered at each size.
// --project lands the render in a project as the studio's Process > Render CG scene does
// (processing/sampling/cg_project.h): the frames its capture, their true poses its path; the project is
// made when it does not exist (its plan from --plan, which also replaces an existing project's plan), and
// without --path or --waypoints the render follows the project's own path. --section-plan makes the
// project's plan from the render itself: the scene cut at eye height as the path saw it
// (processing/sampling/depth_section.h), for a scene that comes without a DXF.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "app/cli/render_common.h"
#include "model/error.h"
#include "model/path_io.h"
#include "model/project_io.h"
#include "processing/capture/blender_render.h"
#include "processing/capture/povray_render.h"
#include "processing/plan/dxf_import.h"
#include "processing/sampling/cg_capture.h"
#include "processing/sampling/cg_project.h"

namespace plenopath::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string scene, path, waypoints, out, size = "2048x1024", povray = "povray", blender = "blender";
  std::string project, plan;  // land the render in this project (made when missing), with this plan
  double step = 0.1, camera_height = 1.6, units_per_metre = 1.0, depth_fog = 0.0;
  int frames = 0, quality = 9, jpeg_quality = 92, processes = 0, frames_per_process = 16, samples = 0;
  bool no_depth = false, no_antialias = false, quiet = false, z_up = false, section_plan = false;
  // Online sampling: coarse depth of the whole path, full frames only for the keyframes it gives.
  bool online = false;
  int budget = 0, coarse_width = 256;
  double ratio = 50.0, loss_target = 0.0;
  // Options given that the scene's renderer has no use for (refused), and whether the units were given
  // (a Blender scene otherwise says its own).
  std::vector<std::string> other_renderers_options;
  bool units_given = false;
};

int run(const Options& o) {
  CgCaptureOptions options;
  PovrayOptions& povray = options.povray;
  int width = 0, height = 0;
  parse_size(o.size, &width, &height, "--size");
  if (height * 2 != width) throw Error("--size must be 2:1 (equirectangular), e.g. 2048x1024");
  povray.width = width;
  povray.executable = o.povray;
  povray.camera_height_m = o.camera_height;
  povray.units_per_metre = o.units_per_metre;
  povray.z_up = o.z_up;
  povray.depth = !o.no_depth;
  povray.depth_fog_m = o.depth_fog;
  povray.quality = o.quality;
  povray.antialias = !o.no_antialias;
  povray.processes = o.processes;
  povray.frames_per_process = o.frames_per_process;
  options.jpeg_quality = o.jpeg_quality;
  options.online = o.online;
  options.online_parameters.count = o.budget;
  options.online_parameters.ratio = o.ratio;
  options.coarse_width = o.coarse_width;
  options.online_loss_target = o.loss_target;
  options.section_plan = o.section_plan;
  if (o.section_plan && o.project.empty())
    throw Error("--section-plan makes the plan of a project: give --project");
  if (o.section_plan && !o.plan.empty())
    throw Error("--section-plan and --plan both give the plan: choose one");
  if (o.section_plan && o.no_depth)
    throw Error("--section-plan cuts the scene from its depth: drop --no-depth");
  BlenderOptions& blender = options.blender;
  blender.width = width;
  blender.executable = o.blender;
  blender.camera_height_m = o.camera_height;
  blender.units_per_metre = o.units_given ? o.units_per_metre : 0.0;
  blender.depth = !o.no_depth;
  blender.samples = o.samples;
  const bool is_blender = is_blender_scene(o.scene);
  if (!o.other_renderers_options.empty()) {
    std::string names;
    for (const std::string& n : o.other_renderers_options) names += (names.empty() ? "" : ", ") + n;
    throw Error(
        names + (o.other_renderers_options.size() > 1 ? " are" : " is") + " for " +
        (is_blender ? "POV-Ray scenes, not the Blender scene " : "Blender scenes, not the POV-Ray scene ") +
        o.scene);
  }
  options.check();
  if (o.loss_target > 0 && !o.online) throw Error("--loss-target goes with --online");
  // The renderer is there before any output is written.
  if (is_blender)
    find_blender(blender.executable);
  else
    find_povray(povray.executable);
  if (!fs::is_regular_file(o.scene)) throw Error("--scene " + o.scene + ": no such file");
  if (o.frames < 0) throw Error("--frames must be >= 0");
  if (!o.plan.empty() && o.project.empty()) throw Error("--plan goes with --project (the project's plan)");
  // The project first: a bad one is refused before the long render.
  Project project;
  const bool project_exists = !o.project.empty() && fs::exists(o.project);
  if (project_exists) project = load_project(o.project);
  if (!o.plan.empty()) project.plan = import_dxf(o.plan);
  const bool along_project = o.path.empty() && o.waypoints.empty() && project_exists;
  if (!along_project && o.path.empty() == o.waypoints.empty())
    throw Error(
        o.project.empty() || !project_exists
            ? "give the path: --path PATH.json or --waypoints"
            : "give the path: --path PATH.json, --waypoints, or neither to follow the project's path");
  if (along_project && project.path.empty())
    throw Error(o.project + ": the project has no path to render along");
  CameraPath path = along_project    ? project.path
                    : o.path.empty() ? walk_waypoints(o.waypoints, o.step)
                                     : read_path_file(o.path);
  if (o.frames > 0 && static_cast<int>(path.size()) > o.frames) path.frames.resize(o.frames);
  if (path.empty()) throw Error("the path has no frames");

  ConsoleProgress progress("render-scene", o.quiet);
  const CgCaptureResult result = render_cg_capture(o.scene, path, options, o.out, progress);
  progress.finish();
  if (!o.project.empty()) {
    land_cg_capture(project, result, options, fs::absolute(o.out).string());
    save_project(project, o.project);
    if (!o.quiet)
      std::cerr << "render-scene: " << (project_exists ? "updated " : "made ") << o.project << ": "
                << project.capture.frame_count << " frames as its capture, their true poses as its path"
                << (project.plan.empty() ? " (no plan)"
                    : o.section_plan     ? "; its plan the scene cut at eye height (" +
                                           std::to_string(project.plan.segments.size()) + " segments)"
                                     : "")
                << "\n";
  }
  if (!o.quiet && o.online)
    std::cerr << "render-scene: online sampling kept " << result.full_frames << " of " << result.path_frames
              << " frames (" << path.length() << " m) of " << o.scene << ", rendered at full size into "
              << o.out << " after the whole path as " << o.coarse_width << "-wide depth ("
              << result.seconds_coarse << " s of " << result.seconds_total << " s); geometric loss "
              << result.online_loss
              << (o.loss_target <= 0              ? ""
                  : result.online_loss_target_met ? " (target met)"
                                                  : " (the budget ran out before the loss target)")
              << "\n";
  else if (!o.quiet)
    std::cerr << "render-scene: " << path.size() << " frames (" << path.length() << " m) of " << o.scene
              << " in " << o.out << " (" << result.seconds_total << " s)\n";
  return kExitOk;
}

}  // namespace

Command add_render_scene_command(CLI::App& parent) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand(
      "render-scene",
      "Render the author's POV-Ray or Blender scene with the spherical camera along a path, with depth");
  sub->add_option("--scene", o->scene,
                  "POV-Ray scene (.pov) or Blender scene (.blend, Cycles); its own camera is replaced")
      ->required();
  auto* path = sub->add_option("--path", o->path, "Path file (JSON) to render along");
  auto* waypoints = sub->add_option("--waypoints", o->waypoints,
                                    "Walk through these plan points: \"X,Y X,Y ...\" (metres)");
  path->excludes(waypoints);
  sub->add_option("--step", o->step, "Waypoints: metres between frames")->capture_default_str();
  sub->add_option("--frames", o->frames, "At most this many frames (0 = all)")->capture_default_str();
  sub->add_option("--size", o->size, "Panorama size WIDTHxHEIGHT (2:1)")->capture_default_str();
  sub->add_option("--camera-height", o->camera_height,
                  "Camera height above the scene's floor (POV-Ray y = 0, Blender z = 0), metres")
      ->capture_default_str();
  auto* units =
      sub->add_option("--units-per-metre", o->units_per_metre,
                      "Scene units in a metre (100: a scene in cm; Blender: default the scene's unit "
                      "scale)")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
  std::vector<CLI::Option*> pov_only, blender_only;
  pov_only.push_back(sub->add_flag("--z-up", o->z_up,
                                   "POV-Ray: the scene is modelled with z up (sky z), as CAD exports are"));
  sub->add_flag("--no-depth", o->no_depth, "Colour only (no depth passes: a third of the time)");
  pov_only.push_back(sub->add_option("--depth-fog", o->depth_fog,
                                     "POV-Ray: fog distance of the depth passes, metres (0 = 8 m)")
                         ->capture_default_str());
  pov_only.push_back(sub->add_option("--quality", o->quality, "POV-Ray quality of the colour pass (0-11)")
                         ->capture_default_str());
  pov_only.push_back(
      sub->add_flag("--no-antialias", o->no_antialias, "POV-Ray: no antialiasing in the colour pass"));
  sub->add_option("--jpeg-quality", o->jpeg_quality, "JPEG quality 1..100")->capture_default_str();
  pov_only.push_back(sub->add_option("--povray", o->povray, "The POV-Ray program")->capture_default_str());
  pov_only.push_back(
      sub->add_option("--processes", o->processes, "POV-Ray processes at once (0 = the cores + 2)")
          ->capture_default_str());
  pov_only.push_back(
      sub->add_option(
             "--frames-per-process", o->frames_per_process,
             "Frames one POV-Ray process renders (animation mode: it idles a quarter second a frame)")
          ->capture_default_str());
  blender_only.push_back(sub->add_option("--samples", o->samples,
                                         "Blender: Cycles samples of the colour render (0 = the scene's)")
                             ->check(CLI::NonNegativeNumber)
                             ->capture_default_str());
  blender_only.push_back(
      sub->add_option("--blender", o->blender, "The Blender program")->capture_default_str());
  sub->add_flag("--online", o->online,
                "Online sampling: the whole path as coarse depth first, full frames only for the keyframes "
                "the depth sampler chooses from it");
  sub->add_option("--budget", o->budget, "Online: at most this many keyframes (0 = by --ratio)")
      ->capture_default_str();
  sub->add_option("--ratio", o->ratio, "Online: frames per keyframe when no --budget")->capture_default_str();
  sub->add_option("--loss-target", o->loss_target,
                  "Online: the fewest keyframes whose geometric loss (mean 1 - IoU of the envelopes) is at "
                  "most this; --budget caps them")
      ->capture_default_str();
  sub->add_option("--coarse-width", o->coarse_width, "Online: width of the coarse depth pass")
      ->capture_default_str();
  sub->add_option("--project", o->project,
                  "Land the render in this project (made when missing): the frames its capture, their true "
                  "poses its path; without --path or --waypoints, render along the project's path");
  sub->add_option("--plan", o->plan, "With --project: the project's floor plan (DXF)");
  sub->add_flag("--section-plan", o->section_plan,
                "With --project: the project's plan cut from the render at eye height, as the path saw the "
                "scene (for a scene without a DXF)");
  sub->add_option("--out", o->out, "Output folder")->required();
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return {sub, [o, units, pov_only, blender_only]() {
            o->units_given = units->count() > 0;
            for (CLI::Option* option : is_blender_scene(o->scene) ? pov_only : blender_only)
              if (option->count() > 0) o->other_renderers_options.push_back(option->get_name());
            return run(*o);
          }};
}

}  // namespace plenopath::cli
