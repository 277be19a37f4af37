// Synthetic camera speed: 2048x1024 RGB + depth panoramas of the office sample along its auto walk, on all
// cores (target >= 20 frames/s on the 2-core reference machine), plus the single-thread cost per frame.
// Prints one JSON object.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <thread>

#include "rig/synthetic_camera.h"

using namespace plenopath;

namespace {
double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}
double load_average() {
  double load = -1;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = -1;
    std::fclose(f);
  }
  return load;
}
}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 40;
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan);
  AutoWalkOptions walk;
  walk.max_frames = frames;
  const CameraPath path = auto_walk(plan, walk);
  RenderOptions options;  // 2048 x 1024, depth on

  RenderedPanorama pano;
  render_panorama(scene, path.frames[0], options, pano);  // warm-up
  const double load_before = load_average();
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds();
  for (const PathFrame& pose : path.frames) render_panorama(scene, pose, options, pano);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = cpu_seconds() - c0;

  RenderOptions single = options;
  single.threads = 1;
  const int single_frames = std::max(1, frames / 4);
  const double c1 = cpu_seconds();
  for (int i = 0; i < single_frames; ++i) render_panorama(scene, path.frames[i], single, pano);
  const double single_cpu = (cpu_seconds() - c1) / single_frames;

  const double megapixels = options.width * options.height * 1e-6;
  nlohmann::json j = {{"benchmark", "render"},
                      {"size", {options.width, options.height}},
                      {"depth", true},
                      {"frames", path.size()},
                      {"threads", cv::getNumThreads()},
                      {"hardware_threads", std::thread::hardware_concurrency()},
                      {"frames_per_s", path.size() / wall},
                      {"megapixels_per_s", path.size() * megapixels / wall},
                      {"cpu_s_per_frame", cpu / path.size()},
                      {"single_thread_cpu_ms_per_frame", single_cpu * 1e3},
                      {"single_thread_frames_per_s", 1.0 / single_cpu},
                      {"load_average_at_start", load_before},
                      {"target_frames_per_s", 20}};
  std::cout << j.dump() << "\n";
  return 0;
}
