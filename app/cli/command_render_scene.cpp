// `plenopath render-scene --scene SCENE.pov (--path PATH.json | --waypoints "X,Y X,Y ...") [--step 0.1]
// [--frames N] [--size 2048x1024] [--camera-height 1.6] [--units-per-metre 1] [--no-depth] [--depth-fog 8]
// [--quality 9] [--no-antialias] [--jpeg-quality Q] [--povray PROGRAM] [--processes N]
// [--frames-per-process N] [--online [--budget N | --ratio R] [--coarse-width 256]] --out DIR`:
// the author's own POV-Ray scene rendered with the studio's spherical camera along a path
// (processing/capture/povray_render.h), colour and depth, with the poses as ground truth. The output is laid
// out as `plenopath render`'s: DIR/groundtruth.json (the path, with `file` fields), DIR/frames/NNNNNN.jpg,
// DIR/depth/NNNNNN.png (16-bit millimetres), so `track`, `sample` and the studio take it as a capture.
// --online renders the whole path as coarse depth first and only the keyframes the depth sampler chooses
// at full size (processing/sampling/online_sampling.h); the capture is then those keyframes, and
// DIR/online_sampling.json says how many of the path's frames were rendered at each size.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "app/cli/render_common.h"
#include "model/error.h"
#include "model/path_io.h"
#include "processing/capture/povray_render.h"
#include "processing/sampling/online_sampling.h"

namespace plenopath::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string scene, path, waypoints, out, size = "2048x1024", povray = "povray";
  double step = 0.1, camera_height = 1.6, units_per_metre = 1.0, depth_fog = 0.0;
  int frames = 0, quality = 9, jpeg_quality = 92, processes = 0, frames_per_process = 16;
  bool no_depth = false, no_antialias = false, quiet = false;
  // Online sampling: coarse depth of the whole path, full frames only for the keyframes it gives.
  bool online = false;
  int budget = 0, coarse_width = 256;
  double ratio = 50.0;
};

// "X,Y X,Y ..." (metres, plan frame): a walk along the polyline, a frame every `step` metres, each facing
// along the path (the direction over the half metre around it, so corners turn smoothly).
CameraPath walk_waypoints(const std::string& text, double step) {
  std::vector<Eigen::Vector2d> points;
  std::stringstream in(text);
  std::string item;
  while (in >> item) {
    double x = 0, y = 0;
    char comma = 0;
    std::stringstream p(item);
    if (!(p >> x >> comma >> y) || comma != ',' || !std::isfinite(x) || !std::isfinite(y))
      throw Error("--waypoints: '" + item + "' is not X,Y (metres)");
    if (points.empty() || (points.back() - Eigen::Vector2d(x, y)).norm() > 1e-9) points.emplace_back(x, y);
  }
  if (points.size() < 2) throw Error("--waypoints needs two distinct points or more");
  if (!(step > 0)) throw Error("--step must be > 0");
  std::vector<double> along = {0.0};
  for (std::size_t k = 1; k < points.size(); ++k)
    along.push_back(along.back() + (points[k] - points[k - 1]).norm());
  auto at = [&](double s) {
    s = std::clamp(s, 0.0, along.back());
    std::size_t k = 1;
    while (k + 1 < points.size() && along[k] < s) ++k;
    const double w = (s - along[k - 1]) / std::max(1e-12, along[k] - along[k - 1]);
    return Eigen::Vector2d((1 - w) * points[k - 1] + w * points[k]);
  };
  CameraPath path;
  const int count = static_cast<int>(std::floor(along.back() / step + 1e-9)) + 1;
  for (int i = 0; i < count; ++i) {
    const double s = i * step;
    const Eigen::Vector2d p = at(s), d = at(s + 0.25) - at(s - 0.25);
    PathFrame f;
    f.index = i;
    f.x = p.x();
    f.y = p.y();
    f.heading = std::atan2(d.y(), d.x());
    path.frames.push_back(f);
  }
  return path;
}

int run(const Options& o) {
  PovrayOptions options;
  int width = 0, height = 0;
  parse_size(o.size, &width, &height, "--size");
  if (height * 2 != width) throw Error("--size must be 2:1 (equirectangular), e.g. 2048x1024");
  options.width = width;
  options.executable = o.povray;
  options.camera_height_m = o.camera_height;
  options.units_per_metre = o.units_per_metre;
  options.depth = !o.no_depth;
  options.depth_fog_m = o.depth_fog;
  options.quality = o.quality;
  options.antialias = !o.no_antialias;
  options.processes = o.processes;
  options.frames_per_process = o.frames_per_process;
  options.check();
  find_povray(options.executable);  // before any output is written
  if (!fs::is_regular_file(o.scene)) throw Error("--scene " + o.scene + ": no such file");
  if (o.frames < 0) throw Error("--frames must be >= 0");
  if (o.path.empty() == o.waypoints.empty()) throw Error("give the path: --path PATH.json or --waypoints");

  CameraPath path = o.path.empty() ? walk_waypoints(o.waypoints, o.step) : read_path_file(o.path);
  if (o.frames > 0 && static_cast<int>(path.size()) > o.frames) path.frames.resize(o.frames);
  if (path.empty()) throw Error("the path has no frames");
  path.scale_source = "ground_truth";
  for (auto& f : path.frames) f.file = "frames/" + numbered_file_name(f.index, "jpg");

  const fs::path out(o.out);
  fs::create_directories(out / "frames");
  if (options.depth) fs::create_directories(out / "depth");
  const fs::path work = out / ".povray";
  fs::create_directories(work);
  write_path_file(path, (out / "groundtruth.json").string());

  ConsoleProgress progress("render-scene", o.quiet);
  auto write_frame = [&](const PathFrame& pose, const PovrayFrame& frame) {
    write_image((out / pose.file).string(), frame.rgb, o.jpeg_quality);
    if (options.depth)
      write_depth_png((out / "depth" / numbered_file_name(pose.index, "png")).string(), frame.depth);
  };
  if (o.online) {
    SamplingParameters parameters;
    parameters.method = SamplingMethod::kDepth;
    parameters.count = o.budget;
    parameters.ratio = o.ratio;
    OnlineSamplingOptions online;
    online.coarse_width = o.coarse_width;
    int written = 0;
    const auto t0 = std::chrono::steady_clock::now();
    double coarse_seconds = 0.0;
    const OnlineSamplingResult result = sample_online(
        path, parameters,
        [&](const std::vector<PathFrame>& poses, int width,
            const std::function<void(int, const cv::Mat&)>& deliver, Progress& p) {
          PovrayOptions coarse = options;
          coarse.width = width;
          coarse.colour = false;
          coarse.depth = true;
          render_povray_frames(
              o.scene, poses, coarse, work.string(), [&](int i, PovrayFrame&& f) { deliver(i, f.depth); }, p);
          coarse_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        },
        [&](const std::vector<PathFrame>& poses, Progress& p) {
          render_povray_frames(
              o.scene, poses, options, work.string(),
              [&](int i, PovrayFrame&& f) {
                write_frame(poses[static_cast<std::size_t>(i)], f);
                progress.frames(++written, static_cast<int>(poses.size()));
              },
              p);
        },
        online, progress);
    progress.finish();
    fs::remove_all(work);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The capture is the keyframes: the path's other frames were never rendered at full size.
    CameraPath kept = path;
    kept.frames.clear();
    for (int index : result.keyframes.indices) kept.frames.push_back(*path.find_frame(index));
    write_path_file(kept, (out / "groundtruth.json").string());
    const nlohmann::json report = {
        {"path_frames", path.size()},       {"coarse_frames", result.coarse_frames},
        {"coarse_width", o.coarse_width},   {"full_frames", result.full_frames},
        {"full_size", {width, height}},     {"keyframes", result.keyframes.indices},
        {"seconds_coarse", coarse_seconds}, {"seconds_total", seconds}};
    std::ofstream((out / "online_sampling.json").string()) << report.dump(2) << "\n";
    if (!o.quiet)
      std::cerr << "render-scene: online sampling kept " << result.full_frames << " of " << path.size()
                << " frames (" << path.length() << " m) of " << o.scene << ", rendered at full size into "
                << o.out << "; the whole path as " << o.coarse_width << "-wide depth first\n";
    return kExitOk;
  }
  render_povray_frames(
      o.scene, path.frames, options, work.string(),
      [&](int i, PovrayFrame&& frame) {
        write_frame(path.frames[static_cast<std::size_t>(i)], frame);
        progress.frames(i + 1, static_cast<int>(path.size()));
      },
      progress);
  progress.finish();
  fs::remove_all(work);
  if (!o.quiet)
    std::cerr << "render-scene: " << path.size() << " frames (" << path.length() << " m) of " << o.scene
              << " in " << o.out << "\n";
  return kExitOk;
}

}  // namespace

Command add_render_scene_command(CLI::App& parent) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand(
      "render-scene", "Render the author's POV-Ray scene with the spherical camera along a path, with depth");
  sub->add_option("--scene", o->scene, "POV-Ray scene (.pov); its own camera is replaced")->required();
  auto* path = sub->add_option("--path", o->path, "Path file (JSON) to render along");
  auto* waypoints = sub->add_option("--waypoints", o->waypoints,
                                    "Walk through these plan points: \"X,Y X,Y ...\" (metres)");
  path->excludes(waypoints);
  sub->add_option("--step", o->step, "Waypoints: metres between frames")->capture_default_str();
  sub->add_option("--frames", o->frames, "At most this many frames (0 = all)")->capture_default_str();
  sub->add_option("--size", o->size, "Panorama size WIDTHxHEIGHT (2:1)")->capture_default_str();
  sub->add_option("--camera-height", o->camera_height,
                  "Camera height above the scene's floor (y = 0), metres")
      ->capture_default_str();
  sub->add_option("--units-per-metre", o->units_per_metre, "Scene units in a metre (100: a scene in cm)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_flag("--no-depth", o->no_depth, "Colour only (no depth passes: a third of the time)");
  sub->add_option("--depth-fog", o->depth_fog, "Fog distance of the depth passes, metres (0 = 8 m)")
      ->capture_default_str();
  sub->add_option("--quality", o->quality, "POV-Ray quality of the colour pass (0-11)")
      ->capture_default_str();
  sub->add_flag("--no-antialias", o->no_antialias, "No antialiasing in the colour pass");
  sub->add_option("--jpeg-quality", o->jpeg_quality, "JPEG quality 1..100")->capture_default_str();
  sub->add_option("--povray", o->povray, "The POV-Ray program")->capture_default_str();
  sub->add_option("--processes", o->processes, "POV-Ray processes at once (0 = the cores + 2)")
      ->capture_default_str();
  sub->add_option("--frames-per-process", o->frames_per_process,
                  "Frames one POV-Ray process renders (animation mode: it idles a quarter second a frame)")
      ->capture_default_str();
  sub->add_flag("--online", o->online,
                "Online sampling: the whole path as coarse depth first, full frames only for the keyframes "
                "the depth sampler chooses from it");
  sub->add_option("--budget", o->budget, "Online: at most this many keyframes (0 = by --ratio)")
      ->capture_default_str();
  sub->add_option("--ratio", o->ratio, "Online: frames per keyframe when no --budget")->capture_default_str();
  sub->add_option("--coarse-width", o->coarse_width, "Online: width of the coarse depth pass")
      ->capture_default_str();
  sub->add_option("--out", o->out, "Output folder")->required();
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return {sub, [o]() { return run(*o); }};
}

}  // namespace plenopath::cli
