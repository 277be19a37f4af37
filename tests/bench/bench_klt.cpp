// KLT observation accuracy against the renderer's ground truth: renders the office walk with exact depth,
// tracks it (translation-only Lucas-Kanade, then with the affine refinement), and for every track whose
// first patch lies on one smooth surface (depth within 15 % over the window: no occlusion edge), places its
// 3-D point from the first observation's ray and depth and measures how far each later observation is from
// where that point projects (working pixels). Prints one JSON object: median and p90 error by track age,
// the mean signed azimuth error (a bias turns into heading drift), track counts and frames/s.
// Usage: bench_klt [--frames N] [--width W]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "processing/egomotion/klt_tracks.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/egomotion/klt_ground_truth.h"

using namespace plenopath;

namespace {

nlohmann::json measure(const std::vector<RenderedPanorama>& frames, const CameraPath& truth,
                       double camera_height, bool affine) {
  KltOptions options;
  options.affine_refinement = affine;
  KltTracker klt(options);
  const auto t0 = std::chrono::steady_clock::now();
  for (const RenderedPanorama& p : frames) klt.add_frame(p.rgb);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<cv::Mat> depths;
  for (const RenderedPanorama& p : frames) depths.push_back(p.depth);
  test::KltTruthErrors e = test::klt_truth_errors(klt, options.window_px, depths, truth, camera_height);
  nlohmann::json by_age = nlohmann::json::array();
  for (auto& [age, errors] : e.error_px) {
    if (errors.size() < 100 || (age > 10 && age % 5 != 0)) continue;
    std::sort(errors.begin(), errors.end());
    double mean_signed = 0;
    for (double v : e.signed_azimuth_px[age]) mean_signed += v;
    by_age.push_back({{"age_frames", age},
                      {"observations", errors.size()},
                      {"median_px", errors[errors.size() / 2]},
                      {"p90_px", errors[errors.size() * 9 / 10]},
                      {"mean_signed_azimuth_px", mean_signed / errors.size()}});
  }
  return {{"affine_refinement", affine},
          {"tracks", klt.tracks().size()},
          {"smooth_surface_tracks", e.smooth_tracks},
          {"affine_refusals", klt.affine_failures()},
          {"frames_per_second", frames.size() / seconds},
          {"error_by_age", by_age}};
}

}  // namespace

int main(int argc, char** argv) {
  int frame_count = 200, width = 1024;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
      frame_count = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--width") && i + 1 < argc)
      width = std::atoi(argv[++i]);
  }
  nlohmann::json out;
  out["benchmark"] = "klt";
  try {
    const FloorPlan plan = make_office_sample_plan();
    SceneOptions scene_options;
    const SyntheticScene scene = build_synthetic_scene(plan, scene_options);
    AutoWalkOptions walk;
    walk.max_frames = frame_count;
    const CameraPath truth = auto_walk(plan, walk);
    RenderOptions render;
    render.width = width;
    render.height = width / 2;
    std::vector<RenderedPanorama> frames;
    for (const PathFrame& f : truth.frames) frames.push_back(render_panorama(scene, f, render));
    out["frames"] = frames.size();
    out["size"] = {width, width / 2};
    out["runs"].push_back(measure(frames, truth, scene_options.camera_height, false));
    out["runs"].push_back(measure(frames, truth, scene_options.camera_height, true));
  } catch (const std::exception& e) {
    out["error"] = e.what();
  }
  std::cout << out.dump(2) << std::endl;
  return out.contains("error") ? 1 : 0;
}
