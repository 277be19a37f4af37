// Capture import speed: scanning a large image folder (headers only, and decoding everything), full and
// thumbnail decoding of JPEG frames, and an H.264 MP4's sequential decoding and random seeks (alone and
// through the frame cache with prefetch). Prints one JSON object.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <random>

#include "processing/capture/frame_cache.h"
#include "processing/capture/frame_source.h"

namespace fs = std::filesystem;
using clock_type = std::chrono::steady_clock;

namespace {

double seconds_since(clock_type::time_point t) {
  return std::chrono::duration<double>(clock_type::now() - t).count();
}

cv::Mat textured_frame(int width, int height, int number) {
  cv::Mat frame(height, width, CV_8UC3);
  cv::randu(frame, cv::Scalar::all(0), cv::Scalar::all(255));
  cv::GaussianBlur(frame, frame, cv::Size(0, 0), 3.0);  // compressible, like a photo
  cv::putText(frame, std::to_string(number), cv::Point(width / 3, height / 2), cv::FONT_HERSHEY_SIMPLEX,
              height / 100.0, cv::Scalar(255, 255, 255), 3);
  return frame;
}

}  // namespace

int main() {
  using namespace plenopath;
  const fs::path dir = fs::temp_directory_path() / ("plenopath_bench_import_" + std::to_string(::getpid()));
  fs::create_directories(dir / "folder");
  nlohmann::json result = {{"benchmark", "capture_import"}};

  // 1. A folder of 3000 JPEG frames (2048x1024; the same bytes copied, as the scan reads headers only).
  constexpr int kFiles = 3000;
  std::vector<uchar> jpeg;
  cv::imencode(".jpg", textured_frame(2048, 1024, 7), jpeg, {cv::IMWRITE_JPEG_QUALITY, 90});
  for (int i = 0; i < kFiles; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.jpg", i);
    std::ofstream(dir / "folder" / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(jpeg.data()), static_cast<std::streamsize>(jpeg.size()));
  }
  auto t = clock_type::now();
  std::unique_ptr<FrameSource> folder = FrameSource::open((dir / "folder").string());
  const double scan_s = seconds_since(t);
  result["folder_frames"] = folder->frame_count();
  result["folder_jpeg_kib"] = jpeg.size() / 1024.0;
  result["folder_scan_ms_per_1000_frames"] = 1000.0 * scan_s * 1000.0 / kFiles;
  result["folder_scan_100000_frames_s_estimate"] = scan_s * 100000.0 / kFiles;

  t = clock_type::now();
  for (int i = 0; i < 20; ++i) folder->read(i * 7);
  result["jpeg_full_decode_ms"] = 1000.0 * seconds_since(t) / 20;
  t = clock_type::now();
  for (int i = 0; i < 20; ++i) folder->read_thumbnail(i * 7, 256);
  result["jpeg_thumbnail_256_decode_ms"] = 1000.0 * seconds_since(t) / 20;

  // 2. An H.264 MP4, 1024x512, 150 frames at 30 fps.
  constexpr int kVideoFrames = 150;
  const std::string video = (dir / "walk.mp4").string();
  {
    cv::VideoWriter writer(video, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('a', 'v', 'c', '1'), 30.0,
                           cv::Size(1024, 512));
    const cv::Mat base = textured_frame(1024, 512, 0);
    for (int i = 0; i < kVideoFrames; ++i) {
      cv::Mat frame;
      cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 3.0 * i, 0, 1, 0);  // a slow pan
      cv::warpAffine(base, frame, shift, base.size(), cv::INTER_LINEAR, cv::BORDER_WRAP);
      cv::putText(frame, std::to_string(i), cv::Point(400, 300), cv::FONT_HERSHEY_SIMPLEX, 4.0,
                  cv::Scalar(255, 255, 255), 6);
      writer.write(frame);
    }
  }
  t = clock_type::now();
  std::shared_ptr<FrameSource> source = FrameSource::open(video);
  result["video_open_ms"] = 1000.0 * seconds_since(t);
  result["video_frames"] = source->frame_count();
  t = clock_type::now();
  for (int i = 0; i < source->frame_count(); ++i) source->read(i);
  result["video_sequential_fps"] = source->frame_count() / seconds_since(t);
  std::mt19937 random(5);
  t = clock_type::now();
  for (int k = 0; k < 20; ++k) source->read(static_cast<int>(random() % source->frame_count()));
  result["video_random_seek_ms"] = 1000.0 * seconds_since(t) / 20;

  // 3. Playback through the cache: the worker decodes ahead while the caller "shows" each frame.
  FrameCacheOptions options;
  options.frame_bytes_bound = std::size_t(64) << 20;
  FrameCache cache(source, options);
  t = clock_type::now();
  for (int i = 0; i < source->frame_count(); ++i) {
    cache.prefetch(i, +1);
    cache.get(i);
  }
  const FrameCacheStats stats = cache.stats();
  result["cached_playback_fps"] = source->frame_count() / seconds_since(t);
  result["cached_playback_hit_rate"] = double(stats.hits) / double(stats.hits + stats.misses);

  std::error_code ec;
  fs::remove_all(dir, ec);
  std::cout << result.dump() << std::endl;
  return 0;
}
