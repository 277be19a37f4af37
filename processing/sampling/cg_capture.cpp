#include "processing/sampling/cg_capture.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "model/error.h"
#include "model/option_check.h"
#include "model/path_io.h"
#include "processing/capture/frame_files.h"
#include "processing/sampling/online_sampling.h"
#include "processing/util/scoped_folder.h"

namespace plenopath {

namespace fs = std::filesystem;

std::vector<Eigen::Vector2d> parse_waypoints(const std::string& text) {
  std::vector<Eigen::Vector2d> points;
  std::stringstream in(text);
  std::string item;
  while (in >> item) {
    double x = 0, y = 0;
    char comma = 0;
    std::stringstream p(item);
    if (!(p >> x >> comma >> y) || comma != ',' || !std::isfinite(x) || !std::isfinite(y))
      throw Error("--waypoints: '" + item + "' is not X,Y (metres)");
    if (points.empty() || (points.back() - Eigen::Vector2d(x, y)).norm() > 1e-9) points.emplace_back(x, y);
  }
  return points;
}

// A frame every `step` metres along the polyline, each facing along the path (the direction over the half
// metre around it, so corners turn smoothly).
CameraPath walk_waypoints(const std::string& text, double step) {
  const std::vector<Eigen::Vector2d> points = parse_waypoints(text);
  if (points.size() < 2) throw Error("--waypoints needs two distinct points or more");
  if (!(step > 0)) throw Error("--step must be > 0");
  std::vector<double> along = {0.0};
  for (std::size_t k = 1; k < points.size(); ++k)
    along.push_back(along.back() + (points[k] - points[k - 1]).norm());
  auto at = [&](double s) {
    s = std::clamp(s, 0.0, along.back());
    std::size_t k = 1;
    while (k + 1 < points.size() && along[k] < s) ++k;
    const double w = (s - along[k - 1]) / std::max(1e-12, along[k] - along[k - 1]);
    return Eigen::Vector2d((1 - w) * points[k - 1] + w * points[k]);
  };
  CameraPath path;
  const int count = static_cast<int>(std::floor(along.back() / step + 1e-9)) + 1;
  for (int i = 0; i < count; ++i) {
    const double s = i * step;
    const Eigen::Vector2d p = at(s), d = at(s + 0.25) - at(s - 0.25);
    PathFrame f;
    f.index = i;
    f.x = p.x();
    f.y = p.y();
    f.heading = std::atan2(d.y(), d.x());
    path.frames.push_back(f);
  }
  return path;
}

std::string waypoints_text(const std::vector<Eigen::Vector2d>& points) {
  std::string text;
  char item[64];
  for (const Eigen::Vector2d& p : points) {
    // Two decimals; a coordinate that rounds to zero is written 0.00, never -0.00.
    const double x = std::round(p.x() * 100.0) / 100.0 + 0.0, y = std::round(p.y() * 100.0) / 100.0 + 0.0;
    std::snprintf(item, sizeof item, "%s%.2f,%.2f", text.empty() ? "" : " ", x, y);
    text += item;
  }
  return text;
}

std::vector<Eigen::Vector2d> path_corners(const CameraPath& path, double tolerance) {
  if (!(tolerance > 0)) throw Error("path_corners: the tolerance must be > 0 metres");
  const std::size_t n = path.frames.size();
  if (n < 3) {
    std::vector<Eigen::Vector2d> all;
    for (const PathFrame& f : path.frames) all.push_back(f.position());
    return all;
  }
  // Douglas-Peucker without recursion (a walk has thousands of frames): split a span at its farthest
  // frame from the chord while that frame is farther than the tolerance.
  std::vector<char> keep(n, 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> spans{{0, n - 1}};
  while (!spans.empty()) {
    const auto [first, last] = spans.back();
    spans.pop_back();
    const Eigen::Vector2d a = path.frames[first].position(), b = path.frames[last].position();
    const Eigen::Vector2d ab = b - a;
    double farthest = -1.0;
    std::size_t at = first;
    for (std::size_t i = first + 1; i < last; ++i) {
      const Eigen::Vector2d p = path.frames[i].position();
      // Distance to the segment a-b (to a when a and b coincide, as at the ends of a loop).
      const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      const double d = (a + t * ab - p).norm();
      if (d > farthest) farthest = d, at = i;
    }
    if (farthest <= tolerance) continue;
    keep[at] = 1;
    spans.emplace_back(first, at);
    spans.emplace_back(at, last);
  }
  std::vector<Eigen::Vector2d> corners;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) corners.push_back(path.frames[i].position());
  return corners;
}

void CgCaptureOptions::check() const {
  povray.check();
  blender.check();
  require_option(jpeg_quality >= 1 && jpeg_quality <= 100, "CgCaptureOptions.jpeg_quality",
                 "must be in [1, 100]", jpeg_quality);
  section.check();
  require_option(online_loss_target >= 0.0 && online_loss_target < 1.0, "CgCaptureOptions.online_loss_target",
                 "must be in [0, 1)", online_loss_target);
  require_option(coarse_width >= 16 && coarse_width % 2 == 0, "CgCaptureOptions.coarse_width",
                 "must be even and >= 16", coarse_width);
}

namespace {

// Renders `poses` with the scene's renderer, handing each frame's colour (empty when `coarse_width` > 0) and
// depth to `deliver` in order. `coarse_width` > 0: depth only, that wide (online sampling's coarse pass).
void render_frames(const std::string& scene_file, const std::vector<PathFrame>& poses,
                   const CgCaptureOptions& options, int coarse_width, const fs::path& work,
                   const std::function<void(int, cv::Mat&& rgb, cv::Mat&& depth)>& deliver,
                   Progress& progress) {
  if (is_blender_scene(scene_file)) {
    BlenderOptions blender = options.blender;
    if (coarse_width > 0) {
      blender.width = coarse_width;
      blender.colour = false;
      blender.depth = true;
    }
    render_blender_frames(
        scene_file, poses, blender, work.string(),
        [&](int i, BlenderFrame&& f) { deliver(i, std::move(f.rgb), std::move(f.depth)); }, progress);
    return;
  }
  PovrayOptions povray = options.povray;
  if (coarse_width > 0) {
    povray.width = coarse_width;
    povray.colour = false;
    povray.depth = true;
  }
  render_povray_frames(
      scene_file, poses, povray, work.string(),
      [&](int i, PovrayFrame&& f) { deliver(i, std::move(f.rgb), std::move(f.depth)); }, progress);
}

}  // namespace

CgCaptureResult render_cg_capture(const std::string& scene_file, const CameraPath& path_in,
                                  const CgCaptureOptions& options, const std::string& out_dir,
                                  Progress& progress) {
  options.check();
  const bool blender = is_blender_scene(scene_file);
  // The renderer is there before any output is written.
  if (blender)
    find_blender(options.blender.executable);
  else
    find_povray(options.povray.executable);
  if (!fs::is_regular_file(scene_file))
    throw Error((blender ? "Blender scene " : "POV-Ray scene ") + scene_file + ": no such file");
  const bool depth = blender ? options.blender.depth : options.povray.depth;
  const int full_width = blender ? options.blender.width : options.povray.width;
  if (options.section_plan && !depth) throw Error("the plan cut at eye height needs the render's depth");
  if (path_in.empty()) throw Error("the path has no frames");
  CameraPath path = path_in;
  path.scale_source = "ground_truth";
  for (PathFrame& f : path.frames) f.file = "frames/" + numbered_file_name(f.index, "jpg");
  const fs::path out(out_dir);
  fs::create_directories(out / "frames");
  if (depth) fs::create_directories(out / "depth");
  const fs::path work = out / (blender ? ".blender" : ".povray");
  fs::create_directories(work);
  const RemoveFolderOnExit remove_work(work);  // whatever happens
  const auto t0 = std::chrono::steady_clock::now();
  auto since = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  auto write_frame = [&](const PathFrame& pose, const cv::Mat& rgb, const cv::Mat& depth_image) {
    write_image((out / pose.file).string(), rgb, options.jpeg_quality);
    if (depth) write_depth_png((out / "depth" / numbered_file_name(pose.index, "png")).string(), depth_image);
  };
  CgCaptureResult result;
  result.path_frames = static_cast<int>(path.size());
  result.depth = depth;
  result.camera_height_m = blender ? options.blender.camera_height_m : options.povray.camera_height_m;
  DepthSectionBuilder section(options.section);
  auto finish_section = [&] {
    if (!options.section_plan) return;
    SubProgress tracing(progress, 0.99, 1.0, "the scene cut at eye height");
    result.section_plan = section.finish(tracing).plan;
    result.section_plan.source_file = scene_file;
  };
  if (!options.online) {
    write_path_file(path, (out / "groundtruth.json").string());
    int written = 0;
    render_frames(
        scene_file, path.frames, options, 0, work,
        [&](int i, cv::Mat&& rgb, cv::Mat&& depth_image) {
          write_frame(path.frames[static_cast<std::size_t>(i)], rgb, depth_image);
          if (options.section_plan) section.add(depth_image, path.frames[static_cast<std::size_t>(i)]);
          ++written;
          progress.report(double(written) / path.size(),
                          "frame " + std::to_string(written) + " of " + std::to_string(path.size()));
        },
        progress);
    result.path = path;
    result.full_frames = result.path_frames;
    finish_section();
    result.seconds_total = since();
    return result;
  }
  SamplingParameters parameters = options.online_parameters;
  parameters.method = SamplingMethod::kDepth;
  OnlineSamplingOptions online;
  online.coarse_width = options.coarse_width;
  online.loss_target = options.online_loss_target;
  const OnlineSamplingResult sampled = sample_online(
      path, parameters,
      [&](const std::vector<PathFrame>& poses, int width,
          const std::function<void(int, const cv::Mat&)>& deliver, Progress& p) {
        render_frames(
            scene_file, poses, options, width, work,
            [&](int i, cv::Mat&&, cv::Mat&& depth_image) {
              if (options.section_plan) section.add(depth_image, poses[static_cast<std::size_t>(i)]);
              deliver(i, depth_image);
            },
            p);
        result.seconds_coarse = since();
      },
      [&](const std::vector<PathFrame>& poses, Progress& p) {
        int written = 0;
        render_frames(
            scene_file, poses, options, 0, work,
            [&](int i, cv::Mat&& rgb, cv::Mat&& depth_image) {
              write_frame(poses[static_cast<std::size_t>(i)], rgb, depth_image);
              ++written;
              p.report(double(written) / poses.size(),
                       "keyframe " + std::to_string(written) + " of " + std::to_string(poses.size()));
            },
            p);
      },
      online, progress);
  // The capture is the keyframes: the path's other frames were never rendered at full size.
  result.path = path;
  result.path.frames.clear();
  for (int index : sampled.keyframes.indices) result.path.frames.push_back(*path.find_frame(index));
  write_path_file(result.path, (out / "groundtruth.json").string());
  result.full_frames = sampled.full_frames;
  result.coarse_frames = sampled.coarse_frames;
  finish_section();
  result.online_keyframes = sampled.keyframes;
  result.online_loss = sampled.loss.mean;
  result.online_loss_target_met = sampled.loss_target_met;
  result.seconds_total = since();
  const nlohmann::json report = {{"path_frames", result.path_frames},
                                 {"coarse_frames", result.coarse_frames},
                                 {"coarse_width", options.coarse_width},
                                 {"full_frames", result.full_frames},
                                 {"full_size", {full_width, full_width / 2}},
                                 {"keyframes", sampled.keyframes.indices},
                                 {"loss_mean", sampled.loss.mean},
                                 {"loss_p95", sampled.loss.p95},
                                 {"loss_target", options.online_loss_target},
                                 {"loss_target_met", sampled.loss_target_met},
                                 {"samplings", sampled.samplings},
                                 {"seconds_coarse", result.seconds_coarse},
                                 {"seconds_total", result.seconds_total}};
  const fs::path report_file = out / "online_sampling.json";
  std::ofstream(report_file) << report.dump(2) << "\n";
  return result;
}

}  // namespace plenopath
