// Registration benchmark (issue 19): how close and how fast register_on_plan() places a path on its plan
// with no alignment at all.
// - "points" scenes: walks of 1 000 frames (auto_walk, or looped through waypoints) on three plans, the wall
// points as a tracker would
//   triangulate them: rays cast by the renderer's ray caster from every 4th frame (72 azimuths x 9
//   elevations), with 1 % depth noise, in a path frame set by a known similarity (scale 1.01); per scene
//   the absolute position RMS and heading RMS of the placed path against the walk, and the seconds.
// - "drift" scenes: the same walks as a drifting tracker gives them (5 % scale error, 0.02 deg of heading
//   bias per frame: 18 deg over 900 frames, as in the anchor tests), the points cast from every 4th true
//   pose and carried by the drifted ones; registered, then refined on the walls (plan_refinement.h): the
//   absolute RMS of both, and the refinement's seconds. The "points" scenes report the refinement too, so
//   that a refinement that makes a drift-free path worse shows.
// - "tracked" scene: 120 frames of the office sample rendered (512 x 256), tracked by the egomotion
//   tracker, registered by its own points: the end-to-end figure.
// - "baseline": a fixed workload measured in the same run (200 forward DFTs of 512 x 512 floats, the
//   search's inner step), so that seconds can be compared across loads as a ratio.
// Prints one JSON object (with the commit and the load average).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>

#include "processing/egomotion/egomotion.h"
#include "processing/registration/plan_refinement.h"
#include "processing/registration/registration.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/registration/drifted_walk.h"

using namespace plenopath;

namespace {

using test::absolute_rms;
using test::heading_rms_deg;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string line;
  std::getline(f, line);
  return line;
}

std::string git_commit() {
  std::string out;
  const std::string cmd = std::string("git -C '") + PLENOPATH_SOURCE_DIR + "' rev-parse HEAD 2>/dev/null";
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[128];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

double baseline_seconds() {
  cv::Mat a(512, 512, CV_32F), f;
  cv::randu(a, 0, 1);
  const auto t0 = Clock::now();
  for (int i = 0; i < 200; ++i) cv::dft(a, f);
  return seconds_since(t0);
}

FloorPlan l_building() {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) { plan.segments.push_back({a, b, "WALLS", true}); };
  wall({0, 0}, {14, 0});
  wall({14, 0}, {14, 5});
  wall({14, 5}, {6, 5});
  wall({6, 5}, {6, 12});
  wall({6, 12}, {0, 12});
  wall({0, 12}, {0, 0});
  wall({0, 2}, {1.0, 2});
  wall({1.9, 2}, {9, 2});
  wall({9.9, 2}, {14, 2});
  wall({3.5, 2}, {3.5, 5.5});
  wall({3.5, 6.4}, {3.5, 12});
  wall({0, 7}, {1.2, 7});
  wall({2.1, 7}, {3.5, 7});
  wall({10, 2}, {10, 5});
  return plan;
}

// A hall with angled wings (walls at 0, 30 and 120 deg): not a Manhattan plan.
FloorPlan angled_hall() {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  const std::vector<Eigen::Vector2d> outline = {{0, 0},       {16, 0},    {16, 6}, {12, 6},
                                                {9.5, 10.33}, {2, 10.33}, {2, 6},  {0, 6}};
  for (std::size_t i = 0; i < outline.size(); ++i)
    plan.segments.push_back({outline[i], outline[(i + 1) % outline.size()], "WALLS", true});
  auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) { plan.segments.push_back({a, b, "WALLS", true}); };
  wall({6, 0}, {6, 2.5});
  wall({11, 3}, {13.6, 4.5});  // a 30 deg screen
  wall({4, 6}, {7, 6});
  return plan;
}

struct Scene {
  std::string name;
  FloorPlan plan;
  std::vector<Eigen::Vector2d> waypoints;  // a walk through them (8 cm steps, looped to 1 000 frames); empty:
                                           // auto_walk (which leaves single-line buildings to walk outside)
};

CameraPath walk_through(const std::vector<Eigen::Vector2d>& waypoints, std::size_t frames) {
  CameraPath path;
  std::size_t leg = 0;
  double along = 0;
  while (path.size() < frames) {
    const Eigen::Vector2d a = waypoints[leg % waypoints.size()], b = waypoints[(leg + 1) % waypoints.size()];
    const double length = (b - a).norm();
    if (along > length) {
      along -= length;
      ++leg;
      continue;
    }
    PathFrame f;
    f.index = static_cast<int>(path.size());
    const Eigen::Vector2d p = a + (b - a) * (along / length);
    f.x = p.x();
    f.y = p.y();
    f.heading = wrap_angle(std::atan2((b - a).y(), (b - a).x()) + radians(2.0) * std::sin(0.3 * f.index));
    path.frames.push_back(f);
    along += 0.08;
  }
  return path;
}

nlohmann::json points_scene(const Scene& s) {
  AutoWalkOptions walk_options;
  walk_options.max_frames = 1000;
  walk_options.frame_pattern.clear();
  const CameraPath truth =
      s.waypoints.empty() ? auto_walk(s.plan, walk_options) : walk_through(s.waypoints, 1000);
  const SyntheticScene scene = build_synthetic_scene(s.plan);
  RenderOptions render;
  Similarity2 to_plan;  // the path frame's placement: what registration must find
  to_plan.rotation = radians(-63.0);
  to_plan.scale = 1.01;
  to_plan.translation = truth.frames.front().position();
  const double c = std::cos(-to_plan.rotation), sn = std::sin(-to_plan.rotation);
  auto to_piece = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = (p - to_plan.translation) / to_plan.scale;
    return Eigen::Vector2d(c * d.x() - sn * d.y(), sn * d.x() + c * d.y());
  };
  CameraPath path = truth;
  for (PathFrame& f : path.frames) {
    const Eigen::Vector2d p = to_piece(f.position());
    f.x = p.x();
    f.y = p.y();
    f.heading = wrap_angle(f.heading - to_plan.rotation);
  }
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<PathPoint> points;
  const double h = 1.6;
  for (std::size_t i = 0; i < truth.size(); i += 4) {
    const Eigen::Vector3d origin(truth.frames[i].x, truth.frames[i].y, h);
    for (int a = 0; a < 72; ++a)
      for (int e = -4; e <= 4; ++e) {
        const double az = 2 * M_PI * (a + 0.37 * (i % 7)) / 72, el = radians(12.0 * e);
        const Eigen::Vector3d dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
        const RayHit hit = trace_ray(scene, origin, dir, render, static_cast<int>(i));
        if (hit.distance <= 0 || hit.distance > 12) continue;
        const Eigen::Vector3d p = origin + dir * hit.distance * (1.0 + 0.01 * noise(rng));
        PathPoint q;
        const Eigen::Vector2d xy = to_piece(p.head<2>());
        q.position = {xy.x(), xy.y(), (p.z() - h) / to_plan.scale};
        q.observations = 4;
        q.frame = truth.frames[i].index;
        points.push_back(q);
      }
  }
  RegistrationOptions options;
  options.camera_height_m = h;
  const auto t0 = Clock::now();
  const RegistrationResult r = register_on_plan(path, points, s.plan, options);
  const double seconds = seconds_since(t0);
  std::vector<PathPoint> moved = points;
  const CameraPath placed = apply_registration(path, r, {}, &moved);
  double p2 = 0, h2 = 0;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    p2 += (placed.frames[i].position() - truth.frames[i].position()).squaredNorm();
    h2 += std::pow(wrap_angle(placed.frames[i].heading - truth.frames[i].heading), 2);
  }
  PlanRefinementOptions refine_options;
  refine_options.registration = options;
  const auto t1 = Clock::now();
  PlanRefinementReport refinement;
  const CameraPath refined = refine_on_plan(placed, &moved, s.plan, refine_options, &refinement);
  const double refine_seconds = seconds_since(t1);
  const PieceRegistration& p = r.pieces.front();
  return {{"scene", s.name},
          {"refined_position_rms_m", absolute_rms(refined, truth)},
          {"refinement_kept", refinement.pieces.front().kept},
          {"refinement_seconds", refine_seconds},
          {"frames", truth.size()},
          {"length_m", truth.length()},
          {"points", points.size()},
          {"wall_points", p.wall_points},
          {"ok", p.ok},
          {"message", p.message},
          {"position_rms_m", std::sqrt(p2 / placed.size())},
          {"heading_rms_deg", degrees(std::sqrt(h2 / placed.size()))},
          {"scale", p.candidates.empty() ? 0.0 : p.candidates[0].transform.scale},
          {"wall_share", p.candidates.empty() ? 0.0 : p.candidates[0].wall_share},
          {"ambiguity_ratio", std::isfinite(p.ambiguity_ratio()) ? p.ambiguity_ratio() : -1.0},
          {"seconds", seconds}};
}

nlohmann::json drift_scene(const Scene& s) {
  AutoWalkOptions walk_options;
  walk_options.max_frames = 900;
  walk_options.frame_pattern.clear();
  const CameraPath truth =
      s.waypoints.empty() ? auto_walk(s.plan, walk_options) : walk_through(s.waypoints, 900);
  const double scale = 1.05;
  const CameraPath tracked = test::drifted(truth, radians(0.02), scale, {3.0, -2.0}, 0.7);
  std::vector<PathPoint> points =
      test::cast_points(build_synthetic_scene(s.plan), truth, tracked, scale, 4, 72, 9, 11);
  const auto t0 = Clock::now();
  const RegistrationResult r = register_on_plan(tracked, points, s.plan);
  const double register_seconds = seconds_since(t0);
  const CameraPath placed = apply_registration(tracked, r, {}, &points);
  const auto t1 = Clock::now();
  PlanRefinementReport refinement;
  const CameraPath refined = refine_on_plan(placed, &points, s.plan, {}, &refinement);
  const double refine_seconds = seconds_since(t1);
  const PieceRefinement& pr = refinement.pieces.front();
  return {{"scene", s.name + "_drift"},
          {"frames", truth.size()},
          {"length_m", truth.length()},
          {"points", points.size()},
          {"ok", r.all_ok()},
          {"registered_position_rms_m", absolute_rms(placed, truth)},
          {"registered_heading_rms_deg", heading_rms_deg(placed, truth)},
          {"position_rms_m", absolute_rms(refined, truth)},
          {"heading_rms_deg", heading_rms_deg(refined, truth)},
          {"refinement_kept", pr.kept},
          {"refinement_message", pr.message},
          {"drift_scale", pr.drift_scale},
          {"wall_share_before", pr.wall_share_before},
          {"wall_share_after", pr.wall_share_after},
          {"register_seconds", register_seconds},
          {"refinement_seconds", refine_seconds},
          {"seconds", register_seconds + refine_seconds}};
}

nlohmann::json tracked_scene() {
  const FloorPlan plan = make_office_sample_plan();
  AutoWalkOptions walk_options;
  walk_options.max_frames = 120;
  walk_options.seed = 7;
  const CameraPath truth = auto_walk(plan, walk_options);
  const SyntheticScene scene = build_synthetic_scene(plan);
  RenderOptions render;
  render.width = 512;
  render.height = 256;
  render.depth = false;
  EgomotionOptions eo;
  eo.camera_height_m = 1.6;
  const EgomotionResult tracked = EgomotionTracker::run(
      static_cast<int>(truth.size()),
      [&](int i) { return render_panorama(scene, truth.frames[i], render).rgb; }, eo);
  const auto t0 = Clock::now();
  const RegistrationResult r = register_on_plan(tracked.path, tracked.tracked_points, plan);
  const double seconds = seconds_since(t0);
  const CameraPath placed = apply_registration(tracked.path, r);
  double p2 = 0, h2 = 0;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    p2 += (placed.frames[i].position() - truth.frames[i].position()).squaredNorm();
    h2 += std::pow(wrap_angle(placed.frames[i].heading - truth.frames[i].heading), 2);
  }
  const PieceRegistration& p = r.pieces.front();
  return {{"scene", "office_tracked"},
          {"frames", truth.size()},
          {"points", tracked.tracked_points.size()},
          {"wall_points", p.wall_points},
          {"ok", p.ok},
          {"position_rms_m", std::sqrt(p2 / placed.size())},
          {"heading_rms_deg", degrees(std::sqrt(h2 / placed.size()))},
          {"ambiguity_ratio", std::isfinite(p.ambiguity_ratio()) ? p.ambiguity_ratio() : -1.0},
          {"seconds", seconds}};
}

}  // namespace

int main() {
  try {
    const double baseline = baseline_seconds();
    nlohmann::json scenes = nlohmann::json::array();
    for (const Scene& s : {Scene{"office", make_office_sample_plan(), {}},
                           Scene{"l_building",
                                 l_building(),
                                 {{0.8, 1.0},
                                  {9.45, 1.0},
                                  {9.45, 3.5},
                                  {8.0, 3.8},
                                  {9.45, 3.5},
                                  {9.45, 1.0},
                                  {1.45, 1.0},
                                  {1.45, 6.0},
                                  {1.65, 7.5},
                                  {1.6, 10.5},
                                  {1.65, 7.5},
                                  {1.45, 6.0},
                                  {1.45, 1.0}}},
                           Scene{"angled_hall",
                                 angled_hall(),
                                 {{1, 4},
                                  {9, 4.5},
                                  {10.5, 2},
                                  {14.5, 2},
                                  {14.5, 5.5},
                                  {11, 7},
                                  {8, 9},
                                  {4, 9},
                                  {3, 8},
                                  {3, 5.2}}}}) {
      for (nlohmann::json j : {points_scene(s), drift_scene(s)}) {
        j["seconds_per_1000_frames"] = j["seconds"].get<double>() * 1000.0 / j["frames"].get<double>();
        j["ratio_to_baseline"] = j["seconds"].get<double>() / baseline;
        scenes.push_back(std::move(j));
      }
    }
    nlohmann::json tracked = tracked_scene();
    tracked["ratio_to_baseline"] = tracked["seconds"].get<double>() / baseline;
    scenes.push_back(std::move(tracked));
    const nlohmann::json out = {{"benchmark", "registration"},
                                {"commit", git_commit()},
                                {"load_average", load_average()},
                                {"baseline_seconds", baseline},
                                {"scenes", scenes}};
    std::cout << out.dump() << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "bench_registration: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
