// Synthetic camera speed: 2048x1024 RGB + depth panoramas of the office sample along its auto walk, on all
// cores (target >= 20 frames/s on the 2-core reference machine, i.e. <= 100 ms of CPU a frame), the
// single-thread cost per frame, and the throughput of `plenopath render`'s loop (JPEG + 16-bit PNG depth
// written on a background thread while the next frame renders, as the CLI does, and written in turn for
// comparison). Prints one JSON object with the commit, the load and a baseline measured in the same run.
//
// bench_render [FRAMES [DUMP_DIR]]: FRAMES (default 40) along the walk; with DUMP_DIR, also writes every
// frame of the first pass as DUMP_DIR/NNNNNN.png (BGR, lossless) and NNNNNN.f32 (raw float depth), to
// compare two builds bit for bit.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "bench_common.h"
#include "processing/capture/frame_files.h"
#include "processing/util/background_queue.h"
#include "rig/synthetic_camera.h"

using namespace plenopath;
using namespace plenopath::bench;

namespace {
namespace fs = std::filesystem;

double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

// A fixed single-thread workload (bilinear remaps of a 2048x1024 BGR image), CPU milliseconds: how fast this
// machine is at the moment of the run, to compare figures across runs and machines.
double baseline_cpu_ms() {
  cv::Mat image(1024, 2048, CV_8UC3), map_x(1024, 2048, CV_32F), map_y(1024, 2048, CV_32F), out;
  cv::RNG rng(1);
  rng.fill(image, cv::RNG::UNIFORM, 0, 255);
  rng.fill(map_x, cv::RNG::UNIFORM, 0, 2047);
  rng.fill(map_y, cv::RNG::UNIFORM, 0, 1023);
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  const double c0 = cpu_seconds();
  for (int i = 0; i < 10; ++i) cv::remap(image, out, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_WRAP);
  const double ms = (cpu_seconds() - c0) * 1e3 / 10;
  cv::setNumThreads(threads);
  return ms;
}

// Renders `frames` poses and writes them as `plenopath render --depth` does, overlapped (a background
// writer, as the CLI) or in turn. Returns frames per second (wall clock) and CPU seconds per frame.
std::pair<double, double> render_and_write(const SyntheticScene& scene, const CameraPath& path, int frames,
                                           const RenderOptions& options, const fs::path& dir,
                                           bool overlapped) {
  fs::create_directories(dir);
  const auto t0 = Clock::now();
  const double c0 = cpu_seconds();
  if (overlapped) {
    BackgroundQueue writer(2);
    std::vector<RenderedPanorama> buffers(static_cast<std::size_t>(writer.capacity()) + 2);
    for (int i = 0; i < frames; ++i) {
      RenderedPanorama& pano = buffers[i % buffers.size()];
      render_panorama(scene, path.frames[i], options, pano);
      writer.submit([rgb = pano.rgb, depth = pano.depth, &dir, i, q = options.jpeg_quality] {
        write_image((dir / numbered_file_name(i, "jpg")).string(), rgb, q);
        write_depth_png((dir / numbered_file_name(i, "png")).string(), depth);
      });
    }
    writer.finish();
  } else {
    RenderedPanorama pano;
    for (int i = 0; i < frames; ++i) {
      render_panorama(scene, path.frames[i], options, pano);
      write_image((dir / numbered_file_name(i, "jpg")).string(), pano.rgb, options.jpeg_quality);
      write_depth_png((dir / numbered_file_name(i, "png")).string(), pano.depth);
    }
  }
  const double wall = seconds_since(t0);
  return {frames / wall, (cpu_seconds() - c0) / frames};
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 40;
  const std::string dump = argc > 2 ? argv[2] : "";
  const double load_before = std::atof(load_average().c_str());
  const double baseline = baseline_cpu_ms();
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan);
  AutoWalkOptions walk;
  walk.max_frames = frames;
  const CameraPath path = auto_walk(plan, walk);
  RenderOptions options;  // 2048 x 1024, depth on

  RenderedPanorama pano;
  render_panorama(scene, path.frames[0], options, pano);  // warm-up
  const auto t0 = Clock::now();
  const double c0 = cpu_seconds();
  for (const PathFrame& pose : path.frames) {
    render_panorama(scene, pose, options, pano);
    if (!dump.empty()) {
      fs::create_directories(dump);
      const std::string stem = (fs::path(dump) / numbered_file_name(pose.index, "")).string();
      cv::imwrite(stem + "png", pano.rgb);
      std::ofstream(stem + "f32", std::ios::binary)
          .write(reinterpret_cast<const char*>(pano.depth.data),
                 static_cast<std::streamsize>(pano.depth.total() * sizeof(float)));
    }
  }
  const double wall = seconds_since(t0);
  const double cpu = cpu_seconds() - c0;

  RenderOptions single = options;
  single.threads = 1;
  const int single_frames = std::max(1, frames / 4);
  const double c1 = cpu_seconds();
  for (int i = 0; i < single_frames; ++i) render_panorama(scene, path.frames[i], single, pano);
  const double single_cpu = (cpu_seconds() - c1) / single_frames;

  // `plenopath render --depth`'s loop, into a scratch folder.
  const fs::path scratch = fs::temp_directory_path() / ("bench_render_" + std::to_string(getpid()));
  const int written_frames = std::min<int>(static_cast<int>(path.size()), 20);
  const auto [overlapped_fps, overlapped_cpu] =
      render_and_write(scene, path, written_frames, options, scratch / "overlapped", true);
  const auto [serial_fps, serial_cpu] =
      render_and_write(scene, path, written_frames, options, scratch / "serial", false);
  fs::remove_all(scratch);

  const double megapixels = options.width * options.height * 1e-6;
  nlohmann::json j = {{"benchmark", "render"},
                      {"commit", git_commit()},
                      {"load_average_at_start", load_before},
                      {"load_average_at_end", std::atof(load_average().c_str())},
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
                      {"written_frames", written_frames},
                      {"written_frames_per_s", overlapped_fps},
                      {"written_cpu_ms_per_frame", overlapped_cpu * 1e3},
                      {"written_in_turn_frames_per_s", serial_fps},
                      {"written_in_turn_cpu_ms_per_frame", serial_cpu * 1e3},
                      {"baseline_cpu_ms", baseline},
                      {"single_thread_ms_per_baseline", single_cpu * 1e3 / baseline},
                      {"target_frames_per_s", 20},
                      {"target_cpu_ms_per_frame_on_2_cores", 100}};
  std::cout << j.dump() << "\n";
  return 0;
}
