// Drift-anchor benchmark: how fast the map's drag preview (preview_path_with_anchors) and the global
// refinement (refine_path_with_anchors) are, on the office sample's whole walk (231 m, 2 888 frames) and on
// the same walk sampled 10x finer (28 877 frames). Drift (heading bias + scale) is injected into the truth;
// the anchors sit on ground-truth positions. Also a refinement cut short (2 or 5 solver iterations), the
// alternative drag preview: it is neither fast nor close (why the map previews with the warp). Prints one
// JSON object.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "processing/anchors/anchor_refinement.h"
#include "processing/egomotion/path_evaluation.h"
#include "rig/synthetic_camera.h"

using namespace plenopath;

namespace {

using Clock = std::chrono::steady_clock;

CameraPath with_drift(const CameraPath& path, double bias_rad_per_metre, double scale) {
  CameraPath out = path;
  Eigen::Vector2d p = path.frames.front().position();
  double bias = 0.0;
  for (std::size_t i = 1; i < path.frames.size(); ++i) {
    const Eigen::Vector2d step = path.frames[i].position() - path.frames[i - 1].position();
    bias += bias_rad_per_metre * step.norm();
    const double c = std::cos(bias), s = std::sin(bias);
    p += scale * Eigen::Vector2d(c * step.x() - s * step.y(), s * step.x() + c * step.y());
    out.frames[i].x = p.x();
    out.frames[i].y = p.y();
    out.frames[i].heading = wrap_angle(path.frames[i].heading + bias);
  }
  return out;
}

Anchors anchors_at(const CameraPath& truth, int count) {
  Anchors anchors;
  const std::size_t n = truth.size();
  for (int k = 0; k < count; ++k) {
    const std::size_t i =
        count == 1 ? 0 : (n - 1) * static_cast<std::size_t>(k) / static_cast<std::size_t>(count - 1);
    anchors.push_back({truth.frames[i].index, truth.frames[i].position(), std::nullopt});
  }
  return anchors;
}

nlohmann::json run(double step_m) {
  AutoWalkOptions options;
  options.step = step_m;
  options.frame_pattern.clear();
  const CameraPath truth = auto_walk(make_office_sample_plan(), options);
  // 0.25 deg of heading bias per metre walked and steps 5 % too long.
  const CameraPath drift = with_drift(truth, radians(0.25), 1.05);
  nlohmann::json preview = nlohmann::json::object();
  for (int count : {2, 5, 20}) {
    const Anchors anchors = anchors_at(truth, count);
    std::vector<double> ms;
    for (int k = 0; k < 30; ++k) {
      const auto t0 = Clock::now();
      const CameraPath p = preview_path_with_anchors(drift, anchors);
      ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
      if (p.size() != drift.size()) std::abort();
    }
    std::sort(ms.begin(), ms.end());
    preview[std::to_string(count) + "_anchors_ms_median"] = ms[ms.size() / 2];
  }
  const Anchors three = anchors_at(truth, 3);
  const CameraPath previewed = preview_path_with_anchors(drift, three);
  AnchorRefinementReport report;
  const auto t0 = Clock::now();
  const CameraPath refined = refine_path_with_anchors(drift, three, {}, &report);
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  double worst_anchor = 0.0;
  for (const AnchorResidual& r : report.residuals) worst_anchor = std::max(worst_anchor, r.distance_m);
  // A short refinement (few solver iterations) as a candidate drag preview.
  nlohmann::json short_refinement = nlohmann::json::object();
  for (int iterations : {2, 5}) {
    AnchorRefinementOptions few;
    few.max_iterations = iterations;
    const auto t1 = Clock::now();
    const CameraPath quick = refine_path_with_anchors(drift, three, few);
    short_refinement[std::to_string(iterations) + "_iterations"] = {
        {"ms", std::chrono::duration<double, std::milli>(Clock::now() - t1).count()},
        {"ate_m", evaluate_path(quick, truth).ate_rms_m}};
  }
  return {{"frames", truth.size()},
          {"short_refinement", short_refinement},
          {"length_m", truth.length()},
          {"preview", preview},
          {"ate_drifted_m", evaluate_path(drift, truth).ate_rms_m},
          {"ate_preview_3_anchors_m", evaluate_path(previewed, truth).ate_rms_m},
          {"ate_refined_3_anchors_m", evaluate_path(refined, truth).ate_rms_m},
          {"refine_seconds", seconds},
          {"refine_iterations", report.iterations},
          {"largest_anchor_residual_m", worst_anchor}};
}

}  // namespace

int main() {
  try {
    const nlohmann::json out = {{"benchmark", "anchors"}, {"walk", run(0.08)}, {"fine_walk", run(0.008)}};
    std::cout << out.dump() << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "bench_anchors: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
