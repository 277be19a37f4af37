// Egomotion benchmark: renders a walk through the office sample with the synthetic surround camera (ground
// truth), encodes the frames as JPEG in memory (a capture), tracks them and prints one JSON object: heading
// RMS after step 1 (rings), after step 2 (chaining) and after refinement, ATE in metres and % of the path
// length, scale error with the camera-height scale, and frames/s with decoding excluded.
// Runs: 1024x512 clean, 1024x512 with noise + people, and (PLENOPATH_BENCH_LARGE=1) 2048x1024.
// Usage: bench_track [--frames N] [--width W] [--noise] [--only]  (--only: just that one run)
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "processing/egomotion/egomotion.h"
#include "processing/egomotion/path_evaluation.h"
#include "rig/synthetic_camera.h"

using namespace plenopath;

namespace {

struct RunSpec {
  int frames = 400;
  int width = 1024;
  bool noise = false;
};

double heading_rms_deg(const std::vector<double>& estimate, const CameraPath& truth) {
  // Best constant offset removed (the estimate's frame 0 is heading 0).
  double sx = 0, sy = 0;
  for (size_t i = 0; i < estimate.size(); ++i) {
    sx += std::cos(truth.frames[i].heading - estimate[i]);
    sy += std::sin(truth.frames[i].heading - estimate[i]);
  }
  const double offset = std::atan2(sy, sx);
  double s2 = 0;
  for (size_t i = 0; i < estimate.size(); ++i) s2 += std::pow(wrap_angle(estimate[i] + offset - truth.frames[i].heading), 2);
  return degrees(std::sqrt(s2 / estimate.size()));
}

nlohmann::json run(const RunSpec& spec) {
  const FloorPlan plan = make_office_sample_plan();
  SceneOptions scene_options;
  const SyntheticScene scene = build_synthetic_scene(plan, scene_options);
  AutoWalkOptions walk;
  walk.max_frames = spec.frames;
  const CameraPath truth = auto_walk(plan, walk);
  RenderOptions render;
  render.width = spec.width;
  render.height = spec.width / 2;
  render.depth = false;
  if (spec.noise) {
    render.noise_sigma = 3.0;
    render.exposure_drift = 0.1;
    render.people = 6;
  }
  const auto t_render = std::chrono::steady_clock::now();
  std::vector<std::vector<unsigned char>> jpegs(truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    const RenderedPanorama p = render_panorama(scene, truth.frames[i], render);
    cv::imencode(".jpg", p.rgb, jpegs[i], {cv::IMWRITE_JPEG_QUALITY, 92});
  }
  const double render_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_render).count();

  EgomotionOptions options;
  options.camera_height_m = scene_options.camera_height;
  double decode_s = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const EgomotionResult r = EgomotionTracker::run(static_cast<int>(jpegs.size()), [&](int i) {
    const auto t = std::chrono::steady_clock::now();
    cv::Mat m = cv::imdecode(jpegs[i], cv::IMREAD_COLOR);
    decode_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    return m;
  }, options);
  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double track_s = total_s - decode_s;

  const PathErrors e = evaluate_path(r.path, truth);
  if (std::getenv("PLENOPATH_BENCH_DUMP")) {
    for (size_t i = 0; i < truth.size(); ++i)
      std::cerr << i << " truth " << truth.frames[i].x << " " << truth.frames[i].y << " "
                << degrees(truth.frames[i].heading) << " ring " << degrees(r.ring_headings[i]) << " est "
                << r.path.frames[i].x << " " << r.path.frames[i].y << " " << degrees(r.path.frames[i].heading)
                << " flags " << r.path.frames[i].flags << " " << r.path.frames[i].reason << "\n";
  }
  CameraPath coarse = r.path;
  for (size_t i = 0; i < coarse.frames.size(); ++i) {
    coarse.frames[i].x = r.coarse_poses[i].x();
    coarse.frames[i].y = r.coarse_poses[i].y();
    coarse.frames[i].heading = r.coarse_poses[i].z();
  }
  const PathErrors ec = evaluate_path(coarse, truth);
  std::vector<double> final_heading;
  for (const auto& f : r.path.frames) final_heading.push_back(f.heading);
  // Scale error of the metric (camera-height) path: rigid alignment would mix in ATE; the similarity's
  // scale says how far the estimate's metres are off.
  return {{"frames", truth.size()},
          {"size", {render.width, render.height}},
          {"noise_and_people", spec.noise},
          {"path_length_m", e.truth_length_m},
          {"keyframes", r.keyframes.size()},
          {"points", r.points},
          {"observations", r.observations},
          {"heading_rms_deg_rings", heading_rms_deg(r.ring_headings, truth)},
          {"heading_rms_deg_chained", ec.rot_rms_deg},
          {"heading_rms_deg_refined", e.rot_rms_deg},
          {"ate_m_chained", ec.ate_rms_m},
          {"ate_pct_chained", ec.ate_pct},
          {"ate_rms_m", e.ate_rms_m},
          {"ate_max_m", e.ate_max_m},
          {"ate_pct", e.ate_pct},
          {"scale_source", r.scale_source},
          {"floor_points", r.floor_points},
          {"scale_error_pct", e.scale_error_pct},
          {"scale_error_signed_pct", 100.0 * (1.0 / e.scale - 1.0)},  // > 0: the estimate is too large
          {"refinement_rms_deg", {degrees(r.refinement.initial_rms), degrees(r.refinement.final_rms)}},
          {"refinement_iterations", r.refinement.iterations},
          {"flagged_frames", r.flagged_frames},
          {"seconds_frames_stage", r.seconds_per_frame_stage},
          {"seconds_geometry", r.seconds_geometry},
          {"seconds_decoding_excluded", decode_s},
          {"frames_per_second", truth.size() / track_s},
          {"seconds_render", render_s}};
}

}  // namespace

int main(int argc, char** argv) {
  RunSpec spec;
  bool only = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) spec.frames = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--width") && i + 1 < argc) spec.width = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--noise")) spec.noise = true;
    else if (!std::strcmp(argv[i], "--only")) only = true;
  }
  nlohmann::json out;
  out["benchmark"] = "track";
  try {
    if (only) {
      out["runs"].push_back(run(spec));
    } else {
      out["runs"].push_back(run({spec.frames, 1024, false}));
      out["runs"].push_back(run({spec.frames, 1024, true}));
      const char* large = std::getenv("PLENOPATH_BENCH_LARGE");
      if (large && std::string(large) == "1") out["runs"].push_back(run({spec.frames, 2048, false}));
    }
  } catch (const std::exception& e) {
    out["error"] = e.what();
  }
  std::cout << out.dump(2) << std::endl;
  return out.contains("error") ? 1 : 0;
}
