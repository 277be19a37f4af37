// `plenopath render-scene --scene SCENE.pov (--path PATH.json | --waypoints "X,Y X,Y ...") [--step 0.1]
// [--frames N] [--size 2048x1024] [--camera-height 1.6] [--units-per-metre 1] [--no-depth] [--depth-fog 8]
// [--quality 9] [--no-antialias] [--jpeg-quality Q] [--povray PROGRAM] --out DIR`:
// the author's own POV-Ray scene rendered with the studio's spherical camera along a path
// (processing/capture/povray_render.h), colour and depth, with the poses as ground truth. The output is laid
// out as `plenopath render`'s: DIR/groundtruth.json (the path, with `file` fields), DIR/frames/NNNNNN.jpg,
// DIR/depth/NNNNNN.png (16-bit millimetres), so `track`, `sample` and the studio take it as a capture.
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
#include "processing/capture/povray_render.h"

namespace plenopath::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string scene, path, waypoints, out, size = "2048x1024", povray = "povray";
  double step = 0.1, camera_height = 1.6, units_per_metre = 1.0, depth_fog = 0.0;
  int frames = 0, quality = 9, jpeg_quality = 92;
  bool no_depth = false, no_antialias = false, quiet = false;
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
  for (std::size_t i = 0; i < path.size(); ++i) {
    const PathFrame& pose = path.frames[i];
    SubProgress frame_progress(progress, double(i) / path.size(), double(i + 1) / path.size());
    const PovrayFrame frame = render_povray_frame(o.scene, pose, options, work.string(), frame_progress);
    write_image((out / pose.file).string(), frame.rgb, o.jpeg_quality);
    if (options.depth)
      write_depth_png((out / "depth" / numbered_file_name(pose.index, "png")).string(), frame.depth);
    progress.frames(static_cast<int>(i + 1), static_cast<int>(path.size()));
  }
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
  sub->add_option("--out", o->out, "Output folder")->required();
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return {sub, [o]() { return run(*o); }};
}

}  // namespace plenopath::cli
