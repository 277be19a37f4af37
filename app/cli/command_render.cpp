// `plenopath render --plan PLAN.dxf [--layers L1,L2] [--path PATH.json | --auto-path] [--step 0.08]
// [--frames N] [--size 2048x1024] [--depth] [--noise S] [--people N] [--exposure-drift A] [--exposure-jump J]
// [--tilt-wobble DEG] [--bumps DEG] [--trolley] [--operator] [--plain-walls] [--jpeg-quality Q]
// [--rig RIG.json] --out DIR`:
// renders the synthetic surround camera along a path. Writes DIR/groundtruth.json (the path file, with
// `file` fields) first, then renders from that file as read back, so rendering again with
// `--path DIR/groundtruth.json` reproduces every frame bit for bit. Frames go to DIR/frames/NNNNNN.jpg,
// depth (--depth) to DIR/depth/NNNNNN.png (16-bit millimetres); with --rig, per-head images go to
// DIR/heads/<head>/NNNNNN.jpg instead (stitch them with `plenopath stitch`). Frame i is encoded and written
// on a background thread while frame i + 1 renders; the files are the same as written in turn.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "app/cli/render_common.h"
#include "model/error.h"
#include "model/path_io.h"
#include "processing/util/background_queue.h"
#include "rig/multi_head_rig.h"
#include "rig/synthetic_camera.h"

namespace plenopath::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string plan, layers, path, rig, out, size = "2048x1024";
  bool auto_path = false, depth = false, quiet = false, trolley = false, operator_person = false,
       plain_walls = false;
  double step = 0.08, noise = 0.0, exposure_drift = 0.0, wall_height = 2.8, camera_height = 1.6;
  double exposure_jump = 0.0, tilt_wobble = 0.0, bumps = 0.0;
  int frames = 0, people = 0, jpeg_quality = 92;
  unsigned seed = 1;
  int texture_size = SceneOptions{}.texture_size;
  double texels_per_metre = SceneOptions{}.texels_per_metre;
};

int run(const Options& o) {
  SceneOptions scene_options;
  scene_options.layers = split_list(o.layers);
  scene_options.wall_height = o.wall_height;
  scene_options.camera_height = o.camera_height;
  scene_options.texture_seed = o.seed;
  scene_options.texture_size = o.texture_size;
  scene_options.texels_per_metre = o.texels_per_metre;
  if (o.plain_walls) {
    scene_options.wall_finish = WallFinish::kPlainPaint;
    scene_options.posters = false;
  }
  RenderOptions render_options;
  parse_size(o.size, &render_options.width, &render_options.height, "--size");
  render_options.depth = o.depth;
  render_options.noise_sigma = o.noise;
  render_options.people = o.people;
  render_options.exposure_drift = o.exposure_drift;
  render_options.jpeg_quality = o.jpeg_quality;
  render_options.exposure_jump = o.exposure_jump;
  render_options.tilt_wobble_deg = o.tilt_wobble;
  render_options.bump_deg = o.bumps;
  render_options.trolley = o.trolley;
  render_options.operator_person = o.operator_person;
  render_options.check();
  if (o.frames < 0) throw Error("--frames must be >= 0");

  const FloorPlan plan = load_render_plan(o.plan);
  const SyntheticScene scene = build_synthetic_scene(plan, scene_options);
  std::unique_ptr<MultiHeadRig> rig;
  if (!o.rig.empty()) rig = std::make_unique<MultiHeadRig>(read_rig_file(o.rig));

  CameraPath path;
  if (!o.path.empty()) {
    path = read_path_file(o.path);
    if (o.frames > 0 && static_cast<int>(path.size()) > o.frames) path.frames.resize(o.frames);
  } else {
    AutoWalkOptions walk;
    walk.step = o.step;
    walk.max_frames = o.frames;
    walk.scene = scene_options;
    path = auto_walk(plan, walk);
  }
  if (path.empty()) throw Error("the path has no frames");
  path.scale_source = "ground_truth";
  for (auto& f : path.frames) f.file = "frames/" + numbered_file_name(f.index, "jpg");

  fs::create_directories(fs::path(o.out) / "frames");
  if (o.depth && !rig) fs::create_directories(fs::path(o.out) / "depth");
  const std::string truth_file = (fs::path(o.out) / "groundtruth.json").string();
  write_path_file(path, truth_file);
  path = read_path_file(truth_file);  // render exactly what a re-render from the file would
  if (rig) {
    for (const auto& h : rig->heads) fs::create_directories(fs::path(o.out) / "heads" / h.name);
    write_rig_file(*rig, (fs::path(o.out) / "rig.json").string());
  }

  ConsoleProgress progress("render", o.quiet);
  // Frame i is encoded and written on a background thread while frame i + 1 renders. The writer may still
  // hold capacity + 1 frames when a render starts, so the panoramas rotate through capacity + 2 buffers.
  BackgroundQueue writer(2);
  std::vector<RenderedPanorama> buffers(static_cast<std::size_t>(writer.capacity()) + 2);
  for (std::size_t i = 0; i < path.size(); ++i) {
    const PathFrame& pose = path.frames[i];
    if (rig) {
      std::vector<cv::Mat> heads = render_heads(scene, *rig, pose, render_options);
      std::vector<std::string> files;
      for (const auto& head : rig->heads)
        files.push_back(
            (fs::path(o.out) / "heads" / head.name / numbered_file_name(pose.index, "jpg")).string());
      writer.submit([heads = std::move(heads), files = std::move(files), quality = o.jpeg_quality] {
        for (std::size_t h = 0; h < heads.size(); ++h) write_image(files[h], heads[h], quality);
      });
    } else {
      RenderedPanorama& pano = buffers[i % buffers.size()];
      render_panorama(scene, pose, render_options, pano);
      const std::string frame_file = (fs::path(o.out) / pose.file).string();
      const std::string depth_file =
          o.depth ? (fs::path(o.out) / "depth" / numbered_file_name(pose.index, "png")).string() : "";
      writer.submit([rgb = pano.rgb, depth = pano.depth, frame_file, depth_file, quality = o.jpeg_quality] {
        write_image(frame_file, rgb, quality);
        if (!depth_file.empty()) write_depth_png(depth_file, depth);
      });
    }
    progress.frames(static_cast<int>(i + 1), static_cast<int>(path.size()));
  }
  writer.finish();
  progress.finish();
  if (!o.quiet)
    std::cerr << "render: " << path.size() << " frames (" << path.length() << " m) in " << o.out
              << (rig ? " as per-head images" : "") << "\n";
  return kExitOk;
}

}  // namespace

Command add_render_command(CLI::App& parent) {
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      parent.add_subcommand("render", "Render the synthetic surround camera along a path, with ground truth");
  sub->add_option("--plan", o->plan, "Floor plan (DXF), or office-sample for the built-in sample")
      ->required();
  sub->add_option("--layers", o->layers, "Layers to render, comma-separated (default: all visible)");
  auto* path = sub->add_option("--path", o->path, "Path file (JSON) to render along");
  auto* auto_path =
      sub->add_flag("--auto-path", o->auto_path, "Walk through the rooms automatically (default)");
  path->excludes(auto_path);
  sub->add_option("--step", o->step, "Auto path: metres between frames")->capture_default_str();
  sub->add_option("--frames", o->frames, "At most this many frames (0 = all)")->capture_default_str();
  sub->add_option("--size", o->size, "Panorama size WIDTHxHEIGHT")->capture_default_str();
  sub->add_flag("--depth", o->depth, "Also write depth maps (16-bit PNG, millimetres)");
  sub->add_option("--noise", o->noise, "Sensor noise sigma (grey levels)")->capture_default_str();
  sub->add_option("--people", o->people, "Moving people")->capture_default_str();
  sub->add_option("--exposure-drift", o->exposure_drift, "Relative exposure drift amplitude")
      ->capture_default_str();
  sub->add_option("--exposure-jump", o->exposure_jump,
                  "Auto-exposure steps: gain jumps by up to exp(+-J) about every 60 frames")
      ->capture_default_str();
  sub->add_option("--tilt-wobble", o->tilt_wobble, "Pitch/roll wobble from an uneven floor, degrees (RMS)")
      ->capture_default_str();
  sub->add_option("--bumps", o->bumps, "Floor bumps: jolts of up to this many degrees")
      ->capture_default_str();
  sub->add_flag("--trolley", o->trolley, "The trolley (mast, frame, handle) in every frame");
  sub->add_flag("--operator", o->operator_person, "The operator behind the trolley in every frame");
  sub->add_flag("--plain-walls", o->plain_walls, "Plain painted walls and pillars, no posters");
  sub->add_option("--jpeg-quality", o->jpeg_quality, "JPEG quality 1..100")->capture_default_str();
  sub->add_option("--seed", o->seed, "Texture seed")->capture_default_str();
  sub->add_option("--texture-size", o->texture_size,
                  "Texels per side of each procedural texture (a power of two); the textures repeat every "
                  "texture-size / texels-per-metre metres, which wide-baseline matching of stills can alias")
      ->capture_default_str();
  sub->add_option("--texels-per-metre", o->texels_per_metre, "Texture resolution on the surfaces")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--wall-height", o->wall_height, "Wall height, metres")->capture_default_str();
  sub->add_option("--camera-height", o->camera_height, "Camera height, metres")->capture_default_str();
  sub->add_option("--rig", o->rig, "Multi-head rig calibration (JSON): write per-head images");
  sub->add_option("--out", o->out, "Output folder")->required();
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return {sub, [o]() { return run(*o); }};
}

}  // namespace plenopath::cli
