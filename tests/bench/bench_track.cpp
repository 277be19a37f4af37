// Egomotion benchmark: renders a walk through the office sample with the synthetic surround camera (ground
// truth), encodes the frames as JPEG in memory (a capture), tracks them and prints one JSON object: heading
// RMS after step 1 (rings), of the chained frame-to-frame KLT turns, after step 2 (chaining) and after
// refinement, ATE in metres and % of the path length, scale error with the camera-height scale, frames/s
// with decoding (or on-the-fly rendering) excluded, seconds per stage and peak memory.
// Runs: 1024x512 clean, 1024x512 with noise + people, 2048x1024 clean, and a long run (10 000 frames of
// 1024x512 rendered on the fly through FrameSource::from_generator: the walk there and back, with turns on
// the spot) that checks time and memory scale. PLENOPATH_BENCH_QUICK=1 leaves out the 2048 and long runs.
// Usage: bench_track [--frames N] [--width W] [--noise] [--long [--walk N]] [--no-loop] [--global-limit N]
// [--only]  (--only: just that one run; --walk: the long run turns back after N frames of the walk;
// --no-loop: without loop closure; --global-limit: RefinementOptions::global_max_observations, 0 = no
// thinning)
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "processing/capture/frame_source.h"
#include "processing/egomotion/egomotion.h"
#include "processing/egomotion/path_evaluation.h"
#include "rig/synthetic_camera.h"

using namespace plenopath;

namespace {

struct RunSpec {
  int frames = 400;
  int width = 1024;
  bool noise = false;
  bool long_walk = false;  // frames rendered on the fly (not kept), the walk repeated there and back
  int walk_frames = 0;     // long runs: frames of the walk before turning back (0 = the whole walk)
  bool loop_closure = true;
  int global_limit = -1;  // RefinementOptions::global_max_observations (-1 = the default)
};

double current_rss_mb() {
  long pages = 0, resident = 0;
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (f) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return resident * (sysconf(_SC_PAGESIZE) / 1048576.0);
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

// The office walk, then a turn on the spot, the walk back, a turn, ... until `frames` frames: a continuous
// trolley path of any length.
CameraPath there_and_back(const CameraPath& walk, int frames) {
  CameraPath out;
  const int turn_frames = 30;  // 180 deg in 30 frames: 6 deg per frame
  bool forward = true;
  double heading_offset = 0.0;
  while (static_cast<int>(out.size()) < frames) {
    for (size_t k = 0; k < walk.size() && static_cast<int>(out.size()) < frames; ++k) {
      PathFrame f = walk.frames[forward ? k : walk.size() - 1 - k];
      f.heading = wrap_angle(f.heading + heading_offset);
      f.index = static_cast<int>(out.size());
      f.file.clear();
      out.frames.push_back(f);
    }
    const PathFrame last = out.frames.back();
    for (int k = 1; k <= turn_frames && static_cast<int>(out.size()) < frames; ++k) {
      PathFrame f = last;
      f.heading = wrap_angle(last.heading + M_PI * k / turn_frames);
      f.index = static_cast<int>(out.size());
      out.frames.push_back(f);
    }
    forward = !forward;
    heading_offset = forward ? 0.0 : M_PI;
  }
  return out;
}

// The long runs walk the same path there and back again and again: each place is rendered once, kept as a
// lossless PNG in a temporary folder (on disk, so the cache does not count in the tracker's memory), and
// read back; a frame facing the other way at the same spot is the cached one turned by half a turn, which
// on an equirectangular panorama is an exact shift by half its width.
class RenderCache {
 public:
  RenderCache(const SyntheticScene& scene, const RenderOptions& render) : scene_(scene), render_(render) {
    char folder[] = "/tmp/plenopath-bench-track-XXXXXX";
    if (!mkdtemp(folder)) throw std::runtime_error("bench_track: cannot make a temporary folder");
    folder_ = folder;
  }
  ~RenderCache() {
    for (const auto& [place, views] : cached_)
      for (const View& v : views) std::remove(v.file.c_str());
    rmdir(folder_.c_str());
  }
  cv::Mat frame(const PathFrame& f) {
    std::vector<View>& views = cached_[{f.x, f.y}];
    for (const View& v : views) {
      const double d = std::abs(std::remainder(f.heading - v.heading, 2 * M_PI));
      if (d < 1e-9) return cv::imread(v.file, cv::IMREAD_COLOR);
      if (std::abs(d - M_PI) < 1e-9) {
        const cv::Mat m = cv::imread(v.file, cv::IMREAD_COLOR);
        cv::Mat turned;
        cv::hconcat(m.colRange(m.cols / 2, m.cols), m.colRange(0, m.cols / 2), turned);
        return turned;
      }
    }
    const auto t = std::chrono::steady_clock::now();
    const cv::Mat rgb = render_panorama(scene_, f, render_).rgb;
    render_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    View v{f.heading, folder_ + "/" + std::to_string(rendered++) + ".png"};
    cv::imwrite(v.file, rgb, {cv::IMWRITE_PNG_COMPRESSION, 1});
    views.push_back(v);
    return rgb;
  }
  int rendered = 0;
  double render_seconds = 0.0;

 private:
  struct View {
    double heading;
    std::string file;
  };
  const SyntheticScene& scene_;
  RenderOptions render_;
  std::string folder_;
  std::map<std::pair<double, double>, std::vector<View>> cached_;
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
  for (size_t i = 0; i < estimate.size(); ++i)
    s2 += std::pow(wrap_angle(estimate[i] + offset - truth.frames[i].heading), 2);
  return degrees(std::sqrt(s2 / estimate.size()));
}

nlohmann::json run(const RunSpec& spec) {
  const FloorPlan plan = make_office_sample_plan();
  SceneOptions scene_options;
  const SyntheticScene scene = build_synthetic_scene(plan, scene_options);
  AutoWalkOptions walk;
  walk.max_frames = spec.long_walk ? spec.walk_frames : spec.frames;
  const CameraPath truth =
      spec.long_walk ? there_and_back(auto_walk(plan, walk), spec.frames) : auto_walk(plan, walk);
  RenderOptions render;
  render.width = spec.width;
  render.height = spec.width / 2;
  render.depth = false;
  if (spec.noise) {
    render.noise_sigma = 3.0;
    render.exposure_drift = 0.1;
    render.people = 6;
  }
  EgomotionOptions options;
  options.camera_height_m = scene_options.camera_height;
  options.loop.enabled = spec.loop_closure;
  if (spec.global_limit >= 0) options.refinement.global_max_observations = spec.global_limit;
  double render_s = 0, decode_s = 0;
  auto seconds = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  // Captures of up to a few hundred frames are rendered first and kept as JPEG (decoding timed apart); the
  // long one is rendered frame by frame as the tracker asks (rendering timed apart), so memory shows what
  // the tracker itself keeps.
  std::vector<std::vector<unsigned char>> jpegs;
  std::unique_ptr<FrameSource> generated;
  std::unique_ptr<RenderCache> cache;
  if (spec.long_walk) {
    cache = std::make_unique<RenderCache>(scene, render);
    generated = FrameSource::from_generator(static_cast<int>(truth.size()), render.width, render.height, 30.0,
                                            [&](int i) { return cache->frame(truth.frames[i]); });
  } else {
    const auto t_render = std::chrono::steady_clock::now();
    jpegs.resize(truth.size());
    for (size_t i = 0; i < truth.size(); ++i) {
      const RenderedPanorama p = render_panorama(scene, truth.frames[i], render);
      cv::imencode(".jpg", p.rgb, jpegs[i], {cv::IMWRITE_JPEG_QUALITY, 92});
    }
    render_s = seconds(t_render);
  }
  const double rss_before_mb = peak_rss_mb();
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, double>> stage_seconds;  // stage, when it started (from t0)
  FunctionProgress progress([&](double, const std::string& stage) {
    if (!stage.empty() && (stage_seconds.empty() || stage_seconds.back().first != stage)) {
      stage_seconds.emplace_back(stage, seconds(t0));
      if (spec.long_walk)
        std::cerr << "bench_track: stage " << stage << " at " << seconds(t0) << " s, RSS " << current_rss_mb()
                  << " MB (peak " << peak_rss_mb() << ")" << std::endl;
    }
  });
  const EgomotionResult r = EgomotionTracker::run(
      static_cast<int>(truth.size()),
      [&](int i) {
        const auto t = std::chrono::steady_clock::now();
        cv::Mat m = generated ? generated->read(i) : cv::imdecode(jpegs[i], cv::IMREAD_COLOR);
        // Long runs take an hour or more: a line every 5 000 frames to follow them by.
        if (generated && i > 0 && i % 5000 == 0)
          std::cerr << "bench_track: frame " << i << "/" << truth.size() << ", " << i / seconds(t0)
                    << " frames/s, RSS " << current_rss_mb() << " MB" << std::endl;
        (generated ? render_s : decode_s) += seconds(t);
        return m;
      },
      options, progress);
  const double total_s = seconds(t0);
  // Seconds spent in each stage of finish() (the frames stage includes decoding; see seconds_frames_stage).
  nlohmann::json geometry_stages;
  for (size_t k = 0; k < stage_seconds.size(); ++k)
    if (stage_seconds[k].first != "frames")
      geometry_stages[stage_seconds[k].first] =
          (k + 1 < stage_seconds.size() ? stage_seconds[k + 1].second : total_s) - stage_seconds[k].second;
  const double track_s = total_s - decode_s - (generated ? render_s : 0.0);

  const PathErrors e = evaluate_path(r.path, truth);
  if (std::getenv("PLENOPATH_BENCH_DUMP")) {
    for (size_t i = 0; i < truth.size(); ++i)
      std::cerr << i << " truth " << truth.frames[i].x << " " << truth.frames[i].y << " "
                << degrees(truth.frames[i].heading) << " ring " << degrees(r.ring_headings[i]) << " est "
                << r.path.frames[i].x << " " << r.path.frames[i].y << " " << degrees(r.path.frames[i].heading)
                << " kf " << std::count(r.keyframes.begin(), r.keyframes.end(), int(i)) << " flags "
                << r.path.frames[i].flags << " " << r.path.frames[i].reason << "\n";
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
          {"rendered_on_the_fly", spec.long_walk},
          {"frames_rendered", cache ? cache->rendered : static_cast<int>(truth.size())},
          {"seconds_rendering_itself", cache ? cache->render_seconds : render_s},
          {"track_memory_mb", r.track_memory_mb},
          {"turns_back_after", spec.long_walk ? static_cast<int>(auto_walk(plan, walk).size()) : 0},
          {"peak_rss_mb", peak_rss_mb()},
          {"peak_rss_mb_before_tracking", rss_before_mb},
          {"size", {render.width, render.height}},
          {"noise_and_people", spec.noise},
          {"path_length_m", e.truth_length_m},
          {"keyframes", r.keyframes.size()},
          {"points", r.points},
          {"observations", r.observations},
          {"heading_rms_deg_rings", heading_rms_deg(r.ring_headings, truth)},
          {"heading_rms_deg_tracked", heading_rms_deg(r.tracked_headings, truth)},
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
          {"loop_closure", spec.loop_closure},
          {"global_max_observations", options.refinement.global_max_observations},
          {"loop_closures", r.loop_closures},
          {"merged_points", r.merged_points},
          {"flagged_frames", r.flagged_frames},
          {"seconds_frames_stage", r.seconds_per_frame_stage},
          {"seconds_geometry", r.seconds_geometry},
          {"seconds_geometry_stages", geometry_stages},
          {"seconds_decoding_excluded", track_s},
          {"seconds_decoding", decode_s},
          {"frames_per_second", truth.size() / track_s},
          {"seconds_render", render_s}};
}

}  // namespace

int main(int argc, char** argv) {
  RunSpec spec;
  bool only = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
      spec.frames = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--width") && i + 1 < argc)
      spec.width = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--noise"))
      spec.noise = true;
    else if (!std::strcmp(argv[i], "--long"))
      spec.long_walk = true;
    else if (!std::strcmp(argv[i], "--walk") && i + 1 < argc)
      spec.walk_frames = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--only"))
      only = true;
    else if (!std::strcmp(argv[i], "--no-loop"))
      spec.loop_closure = false;
    else if (!std::strcmp(argv[i], "--global-limit") && i + 1 < argc)
      spec.global_limit = std::atoi(argv[++i]);
  }
  nlohmann::json out;
  out["benchmark"] = "track";
  try {
    if (only) {
      out["runs"].push_back(run(spec));
    } else {
      out["runs"].push_back(run({spec.frames, 1024, false, false, 0}));
      out["runs"].push_back(run({spec.frames, 1024, true, false, 0}));
      const char* quick = std::getenv("PLENOPATH_BENCH_QUICK");
      if (!quick || std::string(quick) != "1") {
        out["runs"].push_back(run({spec.frames, 2048, false, false, 0}));
        // 1024 wide: at 512 the scale decays along the walk (a known limit of working images that small).
        out["runs"].push_back(run({10000, 1024, false, true, 0}));
      }
    }
  } catch (const std::exception& e) {
    out["error"] = e.what();
  }
  std::cout << out.dump(2) << std::endl;
  return out.contains("error") ? 1 : 0;
}
