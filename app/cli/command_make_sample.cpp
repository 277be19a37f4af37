// `plenopath make-sample --out DIR [--frames N] [--size 1024x512]`: writes the office sample: DIR/office.dxf
// (millimetres, layers WALLS, COLUMNS, DOORS with swing arcs, FURNITURE as block inserts, TEXT labels),
// DIR/office_path.json (the default walk) and DIR/office.plenopath (the plan imported from the DXF, the walk,
// its visibility cells and keyframes, and a capture in DIR/capture/ that `plenopath render` fills; `make run`
// does that).
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli/command.h"
#include "app/cli/render_common.h"
#include "model/error.h"
#include "model/path_io.h"
#include "model/project_io.h"
#include "processing/pipeline/sample_step.h"
#include "processing/pipeline/visibility_step.h"
#include "processing/plan/dxf_export.h"
#include "processing/plan/dxf_import.h"
#include "processing/sampling/sampling_session.h"
#include "processing/visibility/visibility.h"
#include "rig/plan_drawing.h"
#include "rig/synthetic_camera.h"

namespace plenopath::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string out = "resources/samples/office";
  std::string size = "1024x512";
  int frames = 300;
};

int run(const Options& o) {
  int width = 0, height = 0;
  parse_size(o.size, &width, &height, "--size");
  if (o.frames < 1) throw Error("--frames must be >= 1");
  const fs::path dir = fs::absolute(o.out);
  fs::create_directories(dir);
  const std::string dxf = (dir / "office.dxf").string();
  write_dxf(make_office_sample_drawing(), dxf);

  Project project;
  project.plan = import_dxf(dxf);
  AutoWalkOptions walk;
  walk.max_frames = o.frames;
  CameraPath path = auto_walk(project.plan, walk);
  path.scale_source = "ground_truth";
  write_path_file(path, (dir / "office_path.json").string());

  project.path = path;
  project.capture.kind = CaptureKind::kImageFolder;
  project.capture.source = (dir / "capture" / "frames").string();
  project.capture.depth_folder = (dir / "capture" / "depth").string();
  project.capture.frame_count = static_cast<int>(path.size());
  project.capture.width = width;
  project.capture.height = height;
  project.capture.frame_rate = 30.0;
  project.capture.camera_height_m = 1.6;
  for (const auto& f : path.frames)
    project.capture.frame_names.push_back(fs::path(f.file).filename().string());
  project.tour.title = "Office sample";
  // Ready to export as it opens: the walk's visibility cells, and keyframes by the studio's default method.
  if (path.size() >= 2) {
    project = pipeline::run_visibility(std::move(project), {}).project;
    pipeline::SampleStepOptions sampling;
    sampling.request.geometric_loss = false;
    project = pipeline::run_sample(std::move(project), sampling).project;
  }
  save_project(project, (dir / "office.plenopath").string());
  fs::remove(dir / "office.plenopath.bak");
  std::cout << "sample: wrote " << dxf << ", office_path.json (" << path.size() << " frames, "
            << path.length() << " m) and office.plenopath in " << dir.string() << "\n"
            << "render its capture with: plenopath render --plan " << dxf << " --path "
            << (dir / "office_path.json").string() << " --size " << o.size << " --depth --out "
            << (dir / "capture").string() << "\n";
  return kExitOk;
}

}  // namespace

Command add_make_sample_command(CLI::App& parent) {
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      parent.add_subcommand("make-sample", "Write the office sample: DXF plan, default path, project");
  sub->add_option("--out", o->out, "Folder")->capture_default_str();
  sub->add_option("--frames", o->frames, "Frames of the default walk")->capture_default_str();
  sub->add_option("--size", o->size, "Capture size the project expects")->capture_default_str();
  return {sub, [o]() { return run(*o); }};
}

}  // namespace plenopath::cli
