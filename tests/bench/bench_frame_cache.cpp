// A 100 000-frame capture (frames generated on the fly, never stored) opened and scrubbed through the
// frame cache: forward playback with prefetch, backward scrubbing, random jumps, timeline thumbnails.
// Prints one JSON object: the cache's byte bound, its peak, and the process's peak resident memory
// (VmHWM) before and after, so memory is seen to stay bounded however long the capture is.
#include <malloc.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>

#include "processing/capture/frame_cache.h"
#include "processing/capture/frame_source.h"

namespace {

// Peak resident set size of this process in bytes (VmHWM in /proc/self/status), 0 if unknown.
std::size_t peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;  // kB
  }
  return 0;
}
std::size_t resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  }
  return 0;
}

double mib(std::size_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

}  // namespace

int main() {
  using namespace plenopath;
  using clock = std::chrono::steady_clock;
  constexpr int kFrames = 100000;
  constexpr int kWidth = 2048, kHeight = 1024;  // 6 MiB per decoded frame: the whole capture would be 600 GiB
  const std::size_t frame_bytes = std::size_t(kWidth) * kHeight * 3;

  // Frames go straight to mmap and back to the OS when evicted; without this glibc raises its mmap
  // threshold after the first frees and keeps freed frames in its heaps (the studio's main() should do the
  // same).
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  const std::size_t rss_start = resident_bytes();
  const std::size_t hwm_start = peak_resident_bytes();
  const auto t_open = clock::now();
  std::shared_ptr<FrameSource> source = FrameSource::from_generator(
      kFrames, kWidth, kHeight, 30.0,
      [&](int i) {
        cv::Mat frame(kHeight, kWidth, CV_8UC3, cv::Scalar(i % 251, (i / 7) % 253, (i / 49) % 255));
        cv::rectangle(frame, cv::Rect((i * 16) % kWidth, 0, 16, kHeight), cv::Scalar(255, 255, 255),
                      cv::FILLED);
        return frame;
      },
      "synthetic 100000-frame capture");
  const double open_s = std::chrono::duration<double>(clock::now() - t_open).count();
  const std::size_t rss_open = resident_bytes();  // the frame index: names and time stamps, ~50 B a frame

  FrameCacheOptions options;
  options.frame_bytes_bound = std::size_t(192) << 20;  // 32 frames
  options.thumbnail_bytes_bound = std::size_t(16) << 20;
  options.thumbnail_width = 192;
  options.prefetch_ahead = 8;
  options.prefetch_behind = 2;
  FrameCache cache(source, options);

  long accesses = 0;
  std::size_t sum = 0;  // keeps the reads from being optimised away
  auto touch = [&](int i, int direction) {
    cache.prefetch(i, direction);
    const cv::Mat frame = cache.get(i);
    sum += frame.data[0];
    ++accesses;
  };
  const auto t_scrub = clock::now();
  for (int i = 0; i < 400; ++i) touch(i, +1);    // playback from the start
  for (int i = 400; i > 200; --i) touch(i, -1);  // scrub back
  std::mt19937 random(42);
  std::uniform_int_distribution<int> anywhere(0, kFrames - 1);
  for (int jump = 0; jump < 20; ++jump) {  // jumps across the timeline
    const int at = anywhere(random);
    for (int k = 0; k < 10 && at + k < kFrames; ++k) touch(at + k, +1);
  }
  for (int i = kFrames - 200; i < kFrames; ++i) touch(i, +1);  // the end of the capture
  for (int i = 0; i < kFrames; i += kFrames / 400) {           // a timeline strip of 400 thumbnails
    sum += cache.thumbnail(i).data[0];
  }
  cache.wait_for_prefetch();
  const double scrub_s = std::chrono::duration<double>(clock::now() - t_scrub).count();
  const FrameCacheStats stats = cache.stats();
  const std::size_t hwm_end = peak_resident_bytes();

  // What the bound promises, beyond the frame index: the cache's frames and thumbnails plus a few frames
  // in flight (the worker's and the caller's decodes, the caller's copy) and allocator slack.
  const std::size_t allowed =
      options.frame_bytes_bound + options.thumbnail_bytes_bound + 4 * frame_bytes + (std::size_t(8) << 20);
  const std::size_t growth = hwm_end > rss_open ? hwm_end - rss_open : 0;
  nlohmann::json result = {
      {"benchmark", "frame_cache"},
      {"frames", kFrames},
      {"frame_size", {kWidth, kHeight}},
      {"frame_mib", mib(frame_bytes)},
      {"whole_capture_decoded_gib", mib(frame_bytes) * kFrames / 1024.0},
      {"open_s", open_s},
      {"index_mib", mib(rss_open > rss_start ? rss_open - rss_start : 0)},
      {"accesses", accesses},
      {"scrub_s", scrub_s},
      {"ms_per_access", 1000.0 * scrub_s / accesses},
      {"hit_rate", double(stats.hits) / double(stats.hits + stats.misses)},
      {"prefetched", stats.prefetched},
      {"evictions", stats.evictions},
      {"bound_mib", mib(options.frame_bytes_bound)},
      {"thumbnail_bound_mib", mib(options.thumbnail_bytes_bound)},
      {"peak_cache_mib", mib(stats.peak_frame_bytes)},
      {"peak_thumbnail_mib", mib(stats.peak_thumbnail_bytes)},
      {"cache_within_bound", stats.peak_frame_bytes <= options.frame_bytes_bound &&
                                 stats.peak_thumbnail_bytes <= options.thumbnail_bytes_bound},
      {"rss_start_mib", mib(rss_start)},
      {"vmhwm_start_mib", mib(hwm_start)},
      {"vmhwm_end_mib", mib(hwm_end)},
      {"vmhwm_growth_mib", mib(growth)},
      {"allowed_growth_mib", mib(allowed)},
      {"memory_bounded", growth <= allowed},
      {"checksum", sum % 1000}};
  std::cout << result.dump() << std::endl;
  return 0;  // the verdicts are in the JSON; a non-zero exit would stop `make bench` for everyone
}
