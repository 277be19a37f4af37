// `plenopath sample (--plan PLAN.dxf [--layers ...] [--occluders ...] [--units U] --path PATH.json
//                    [--capture DIR|VIDEO] [--depth DIR] | --project P.plenopath [--save])
//                   --method uniform|visibility|depth (--count N | --ratio R) [--exponent E] [--boost B]
//                   [--rule expected_loss|cell_rule] [--pin i,j,...] [--min-spacing M] [--max-spacing M]
//                   [--photometric-frames N] [--json]`
// Keyframes in progressive order (key "keyframes") and what they lose: reduction ratio and largest gap
// always; geometric loss when there is a plan; PSNR/SSIM when the capture's frames can be read.
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "model/error.h"
#include "model/path_io.h"
#include "model/project_io.h"
#include "processing/capture/frame_source.h"
#include "processing/pipeline/sample_step.h"
#include "processing/plan/dxf_import.h"
#include "processing/sampling/keyframe_sampler.h"
#include "processing/sampling/sampling_loss.h"
#include "processing/sampling/uniform_sampling.h"
#include "processing/visibility/visibility.h"

namespace plenopath::cli {

namespace {

struct Options {
  std::string plan, path, capture, depth, project;
  DxfImportOptions import;
  bool save = false;
  SamplingParameters parameters;  // method and rule set from `method` and `rule` before run()
  std::string method;
  std::string rule = to_string(VisibilityRule::expected_loss);
  std::vector<int> pinned;
  int photometric_frames = 20;
  bool json = false;
};

nlohmann::json geometric_json(const GeometricLoss& g) {
  return {{"mean", g.mean},           {"p95", g.p95},        {"max", g.max}, {"dropped", g.dropped},
          {"evaluated", g.evaluated}, {"inexact", g.inexact}};
}

int run(const Options& o, CLI::App* sub) {
  const bool from_project = !o.project.empty();
  if (!from_project && o.path.empty()) {
    std::cerr
        << "plenopath sample: give --path PATH.json (with --plan for visibility), or --project P.plenopath\n"
        << sub->help();
    return kExitUsage;
  }
  if (o.save && !from_project) {
    std::cerr << "plenopath sample: --save writes the keyframes into the project: it needs --project\n";
    return kExitUsage;
  }
  Project project;
  if (from_project) project = load_project(o.project);
  const std::string where = from_project ? o.project : o.path;

  // What the step works on: the project (or a path file) with the plan and capture given here; a --save
  // writes only the keyframes into the project as it was.
  Project work = project;
  // The plan (optional for uniform and depth); the cells of another plan are stale.
  if (!o.plan.empty()) {
    work.plan = import_dxf(o.plan, o.import);
    work.visibility = {};
  }
  if (!from_project) work.path = read_path_file(o.path);
  const CameraPath& path = work.path;
  if (path.empty()) throw Error(where + ": the camera path has no frames");
  if (o.parameters.method == SamplingMethod::kVisibility && work.plan.occluder_segments().empty())
    throw Error((o.plan.empty() ? where : o.plan) +
                ": visibility sampling needs a floor plan with walls (give --plan PLAN.dxf)");

  // The capture (optional): frames for the photometric loss, depth maps for depth sampling; the work reads
  // it through the project's Capture, as the studio does.
  int photometric_frames = o.photometric_frames;
  if (!o.capture.empty()) {
    namespace fs = std::filesystem;
    FrameSourceOptions options;
    std::string frames = o.capture;
    options.depth_folder = o.depth;
    // A rendered capture folder (frames/ and depth/ inside) is taken as such.
    if (fs::is_directory(fs::path(o.capture) / "frames")) {
      frames = (fs::path(o.capture) / "frames").string();
      if (options.depth_folder.empty() && fs::is_directory(fs::path(o.capture) / "depth"))
        options.depth_folder = (fs::path(o.capture) / "depth").string();
    }
    const std::unique_ptr<FrameSource> source = FrameSource::open(frames, options);
    if (o.parameters.method == SamplingMethod::kDepth && source->depth_match_count() == 0)
      throw Error(source->source() + ": no depth maps found (give --depth DIR with 16-bit PNG or EXR depth)");
    work.capture = capture_from_frame_source(*source, work.capture);
  } else if (from_project && !work.capture.empty()) {
    try {
      FrameSource::open_capture(work.capture);
    } catch (const Error& e) {
      if (o.parameters.method == SamplingMethod::kDepth) throw;
      std::cerr << "plenopath sample: warning: " << e.what() << " (no photometric loss)\n";
      photometric_frames = 0;
    }
  }
  if (o.parameters.method == SamplingMethod::kDepth && work.capture.empty())
    throw Error(where + ": depth sampling needs the capture's depth maps (give --capture DIR)");
  if (work.capture.empty()) photometric_frames = 0;

  // The pipeline's step, as the studio's sampling panel.
  pipeline::SampleStepOptions options;
  options.request.parameters = o.parameters;
  options.request.pinned = o.pinned;
  options.compute_missing_cells = true;  // a path file and a plan: the cells along the path first
  options.photometric_frames = photometric_frames;
  if (work.capture.stills) std::cerr << "sample: the capture is still panoramas: every still is a keyframe\n";
  ConsoleProgress progress("sample");
  pipeline::SampleStepResult result = pipeline::run_sample(work, options, progress);
  progress.finish();
  const Keyframes& keyframes = result.outcome.keyframes;
  const SamplingLoss& loss = result.outcome.loss;

  if (o.save) {
    project.keyframes = keyframes;
    save_project(project, o.project);
  }

  const std::vector<int> order = keyframes.progressive_order();
  nlohmann::json out = {{"method", to_string(keyframes.parameters.method)},
                        {"frames", path.size()},
                        {"budget", keyframe_budget(o.parameters, static_cast<int>(path.size()))},
                        {"keyframes", order},
                        {"pinned", o.pinned},
                        {"reduction_ratio", loss.reduction_ratio},
                        {"largest_gap_m", loss.largest_gap_m},
                        {"geometric_loss", nullptr},
                        {"photometric_loss", nullptr}};
  if (keyframes.parameters.method == SamplingMethod::kVisibility)
    out["rule"] = to_string(keyframes.parameters.rule);
  if (keyframes.parameters.method != SamplingMethod::kUniform) {
    out["exponent"] = o.parameters.exponent;
    out["boost"] = o.parameters.transition_boost;
  }
  if (loss.has_geometric) out["geometric_loss"] = geometric_json(loss.geometric);
  if (loss.has_photometric && loss.photometric.frames > 0)
    out["photometric_loss"] = {{"psnr_mean_db", loss.photometric.psnr_mean_db},
                               {"psnr_min_db", loss.photometric.psnr_min_db},
                               {"ssim_mean", loss.photometric.ssim_mean},
                               {"ssim_min", loss.photometric.ssim_min},
                               {"frames", loss.photometric.frames}};
  if (o.save) out["saved"] = o.project;
  if (o.json) {
    std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return kExitOk;
  }
  std::cout << std::fixed << std::setprecision(3) << "Method     " << to_string(keyframes.parameters.method)
            << "\nKept       " << loss.kept << " of " << loss.total << " frames (" << std::setprecision(1)
            << loss.reduction_ratio << " : 1), largest gap " << std::setprecision(2) << loss.largest_gap_m
            << " m\n";
  if (loss.has_geometric)
    std::cout << std::setprecision(4) << "Geometric  mean " << loss.geometric.mean << ", p95 "
              << loss.geometric.p95 << " (1 - IoU of envelopes, " << loss.geometric.evaluated
              << " dropped frames)\n";
  if (loss.has_photometric && loss.photometric.frames > 0)
    std::cout << std::setprecision(2) << "Photometric PSNR " << loss.photometric.psnr_mean_db << " dB, SSIM "
              << std::setprecision(3) << loss.photometric.ssim_mean << " (" << loss.photometric.frames
              << " frames)\n";
  std::cout << "Keyframes  (coarse to fine)";
  for (int i : order) std::cout << " " << i;
  std::cout << "\n";
  if (o.save) std::cout << "Saved      " << o.project << "\n";
  return kExitOk;
}

}  // namespace

Command add_sample_command(CLI::App& parent) {
  auto o = std::make_shared<Options>();
  o->parameters.exponent =
      CellRuleOptions{}.exponent;  // measured best in the plan (cell_rule.h), not the seed's 3
  CLI::App* sub = parent.add_subcommand(
      "sample", "Keyframes along the path (uniform, visibility or depth) and what they lose");
  auto* plan = sub->add_option("--plan", o->plan, "Floor plan (*.dxf, ASCII)");
  sub->add_option("--layers", o->import.layers, "Import only these layers (default: all)");
  sub->add_option("--occluders", o->import.occluder_layers,
                  "Layers that block sight (default: guessed from the names)");
  sub->add_option("--units", o->import.units_override, "Units of the plan file (mm, cm, m, in, ft, ...)");
  auto* path = sub->add_option("--path", o->path, "Path file (JSON, metres)");
  auto* capture =
      sub->add_option("--capture", o->capture,
                      "Frames (folder or video; a folder holding frames/ and depth/ is taken apart)");
  sub->add_option("--depth", o->depth, "Depth maps folder (16-bit PNG mm or EXR m), for --method depth");
  auto* project = sub->add_option("--project", o->project, "Project file: plan, path and capture from it");
  project->excludes(path)->excludes(capture);
  sub->add_flag("--save", o->save, "Write the keyframes into the project (--project)");
  auto names = [](const auto& table) {
    std::vector<std::string> out;
    for (const auto& n : table) out.push_back(n.id);
    return out;
  };
  sub->add_option("--method", o->method, "uniform, visibility or depth")
      ->required()
      ->check(CLI::IsMember(names(EnumInfo<SamplingMethod>::names)));
  auto* count = sub->add_option("--count", o->parameters.count, "Budget: number of keyframes")
                    ->check(CLI::PositiveNumber);
  auto* ratio =
      sub->add_option("--ratio", o->parameters.ratio, "Budget: frames per keyframe (reduction ratio)")
          ->check(CLI::PositiveNumber);
  count->excludes(ratio);
  sub->add_option("--exponent", o->parameters.exponent,
                  "Exponent e of the cell rule l^e / v (default 1; the seed's is 3)")
      ->check(CLI::Range(0.0, 10.0));
  sub->add_option("--boost", o->parameters.transition_boost, "Transition boost of the cell rule (default 1)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--rule", o->rule,
                  "Visibility rule: expected_loss (default) or cell_rule (the seed's l^e / v)")
      ->check(CLI::IsMember(names(EnumInfo<VisibilityRule>::names)));
  sub->add_option("--pin", o->pinned, "Frames always kept (capture indices)")->delimiter(',');
  sub->add_option("--min-spacing", o->parameters.min_spacing_m, "Minimum metres between keyframes")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--max-spacing", o->parameters.max_spacing_m, "Maximum metres between keyframes (0 = none)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--photometric-frames", o->photometric_frames,
                  "Dropped frames compared by PSNR/SSIM when frames are readable (0 = skip)")
      ->check(CLI::NonNegativeNumber);
  sub->add_flag("--json", o->json, "Machine-readable output");
  (void)plan;
  return {sub, [o, sub, count, ratio]() {
            if (count->count() == 0 && ratio->count() == 0) {
              std::cerr << "plenopath sample: give a budget, --count N or --ratio R\n" << sub->help();
              return kExitUsage;
            }
            if (count->count() > 0) o->parameters.ratio = 1.0;  // unused with a count
            o->parameters.method = enum_from_string<SamplingMethod>(o->method);
            o->parameters.rule = enum_from_string<VisibilityRule>(o->rule);
            return run(*o, sub);
          }};
}

}  // namespace plenopath::cli
