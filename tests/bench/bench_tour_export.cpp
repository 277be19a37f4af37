// Tour package export at scale (issue 21): KEYFRAMES keyframes (default 2000) of SIZE x SIZE/2 pixels
// (default 4096) exported as a .zip, streamed entry by entry. Prints one JSON object: seconds, peak RSS
// (target < 500 MB whatever the tour's size), package bytes and their ratio to the full keyframe JPEGs
// (target <= 1.1), and whether the zip passes `unzip -t` and python's zipfile testzip().
//
// bench_tour_export [KEYFRAMES [SIZE [--keep]]]. The frames are rendered once (office sample, synthetic
// camera, JPEG 95) into ${XDG_CACHE_HOME:-~/.cache}/plenopath/bench-tour-export-SIZE/ (100 distinct frames,
// ~300 MB at 4096) in a child process, so their rendering does not count in the peak RSS; the capture names
// them in turn. The package (~3 GB at the defaults) goes to the temporary folder and is removed after the
// checks unless --keep.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bench_common.h"
#include "model/error.h"
#include "processing/export/tour_export.h"
#include "rig/synthetic_camera.h"

using namespace plenopath;
using namespace plenopath::bench;

namespace {
namespace fs = std::filesystem;

constexpr int kDistinctFrames = 100;

fs::path cache_dir(int width) {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  const fs::path root = xdg && *xdg ? fs::path(xdg) : fs::path(home ? home : "/tmp") / ".cache";
  return root / "plenopath" / ("bench-tour-export-" + std::to_string(width));
}

std::string frame_name(int i) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.jpg", i);
  return name;
}

// The office sample's auto walk, repeated back and forth until it has `count` frames.
CameraPath long_walk(const FloorPlan& plan, int count) {
  const CameraPath walk = auto_walk(plan);
  CameraPath path;
  const int n = static_cast<int>(walk.frames.size());
  for (int i = 0; i < count; ++i) {
    const int lap = i / n, k = i % n;
    PathFrame f = walk.frames[lap % 2 == 0 ? k : n - 1 - k];
    f.index = i;
    f.file = "frames/" + frame_name(i);
    path.frames.push_back(f);
  }
  return path;
}

// Renders the cached frames (once) in a child process.
void make_frame_cache(const fs::path& dir, int width) {
  if (fs::exists(dir / "complete")) return;
  const pid_t child = fork();
  if (child < 0) throw Error("bench: fork failed");
  if (child == 0) {
    try {
      fs::create_directories(dir);
      const FloorPlan plan = make_office_sample_plan();
      const SyntheticScene scene = build_synthetic_scene(plan);
      const CameraPath walk = long_walk(plan, kDistinctFrames * 3);
      RenderOptions render;
      render.width = width;
      render.height = width / 2;
      render.depth = false;
      for (int i = 0; i < kDistinctFrames; ++i)
        cv::imwrite((dir / frame_name(i)).string(), render_panorama(scene, walk.frames[i * 3], render).rgb,
                    {cv::IMWRITE_JPEG_QUALITY, 95});
      std::ofstream(dir / "complete") << kDistinctFrames << "\n";
      std::_Exit(0);
    } catch (const std::exception& e) {
      std::cerr << "bench: " << e.what() << "\n";
      std::_Exit(1);
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw Error("bench: rendering the frame cache failed");
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // kilobytes on Linux
}

}  // namespace

int main(int argc, char** argv) {
  const int keyframes = argc > 1 ? std::atoi(argv[1]) : 2000;
  const int width = argc > 2 ? std::atoi(argv[2]) : 4096;
  const bool keep = argc > 3 && std::string(argv[3]) == "--keep";
  nlohmann::json out = {{"bench", "tour_export"},
                        {"commit", git_commit()},
                        {"load", load_average()},
                        {"keyframes", keyframes},
                        {"width", width}};
  const fs::path work = fs::temp_directory_path() / ("plenopath_bench_export_" + std::to_string(::getpid()));
  try {
    const fs::path cache = cache_dir(width);
    auto t = Clock::now();
    make_frame_cache(cache, width);
    out["cache"] = cache.string();
    out["cache_seconds"] = seconds_since(t);

    // The capture: KEYFRAMES symlinks naming the cached frames in turn; every frame a keyframe.
    fs::create_directories(work / "frames");
    Project p;
    p.plan = make_office_sample_plan();
    p.path = long_walk(p.plan, keyframes);
    for (int i = 0; i < keyframes; ++i) {
      fs::create_symlink(cache / frame_name(i % kDistinctFrames), work / "frames" / frame_name(i));
      p.capture.frame_names.push_back(frame_name(i));
      p.keyframes.indices.push_back(i);
      p.keyframes.rank.push_back(i);
    }
    p.capture.kind = CaptureKind::kImageFolder;
    p.capture.source = (work / "frames").string();
    p.capture.frame_count = keyframes;
    p.capture.width = width;
    p.capture.height = width / 2;

    TourExportOptions options;
    options.output = (work / "tour.zip").string();
    options.max_size = width;
    options.preview_size = std::min(options.preview_size, width);
    const double rss_before = peak_rss_mb();
    t = Clock::now();
    const TourExportReport report = export_tour(p, options);
    const double seconds = seconds_since(t);
    const double rss = peak_rss_mb();
    out["seconds"] = seconds;
    out["ms_per_keyframe"] = 1e3 * seconds / keyframes;
    out["peak_rss_mb_before_export"] = rss_before;
    out["peak_rss_mb"] = rss;
    out["package_bytes"] = report.package_bytes;
    out["full_image_bytes"] = report.full_image_bytes;
    out["package_ratio"] = report.package_ratio;
    out["files"] = report.files.size();
    out["zip64"] = report.package_bytes > 0xFFFFFFFFull;

    t = Clock::now();
    const std::string unzip = "unzip -tq '" + options.output + "' > /dev/null";
    out["unzip_t_ok"] = std::system(unzip.c_str()) == 0;
    const std::string python =
        "/usr/bin/python3 -c \"import sys, zipfile; z = zipfile.ZipFile(sys.argv[1]); "
        "assert z.testzip() is None; assert len(z.namelist()) == int(sys.argv[2])\" '" +
        options.output + "' " + std::to_string(report.files.size());
    out["python_testzip_ok"] = std::system(python.c_str()) == 0;
    out["check_seconds"] = seconds_since(t);
    out["targets_met"] = rss < 500 && report.package_ratio <= 1.1 && out["unzip_t_ok"].get<bool>() &&
                         out["python_testzip_ok"].get<bool>();
  } catch (const std::exception& e) {
    out["error"] = e.what();
  }
  if (!keep) {
    std::error_code ec;
    fs::remove_all(work, ec);
  } else {
    out["package"] = (work / "tour.zip").string();
  }
  std::cout << out.dump(2) << std::endl;
  return out.contains("error") ? 1 : 0;
}
