// The acceptance figure on a rendered capture: a walk through the office sample is rendered and
// tracked; drift (a slow heading bias plus a scale error) is injected into the RECOVERED path; three anchors
// at ground-truth positions must cut the ATE at least 5x and hold the anchored frames within 5 cm.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "processing/anchors/anchor_refinement.h"
#include "processing/egomotion/egomotion.h"
#include "processing/egomotion/path_evaluation.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

// Re-integrates the path's own steps with a heading bias growing by `bias_rad_per_frame` and the steps
// scaled by `scale`, as a drifting tracker would have produced them.
CameraPath with_drift(const CameraPath& path, double bias_rad_per_frame, double scale) {
  CameraPath out = path;
  Eigen::Vector2d p = path.frames.front().position();
  double bias = 0.0;
  for (std::size_t i = 1; i < path.frames.size(); ++i) {
    const Eigen::Vector2d step = path.frames[i].position() - path.frames[i - 1].position();
    bias += bias_rad_per_frame;
    const double c = std::cos(bias), s = std::sin(bias);
    p += scale * Eigen::Vector2d(c * step.x() - s * step.y(), s * step.x() + c * step.y());
    out.frames[i].x = p.x();
    out.frames[i].y = p.y();
    out.frames[i].heading = wrap_angle(path.frames[i].heading + bias);
  }
  return out;
}

TEST(AnchorRefinement, ThreeAnchorsUndoDriftInjectedIntoATrackedRenderedWalk) {
  const FloorPlan plan = make_office_sample_plan();
  AutoWalkOptions walk_options;
  walk_options.step = 0.12;
  walk_options.max_frames = 110;
  const CameraPath truth = auto_walk(plan, walk_options);
  const SyntheticScene scene = build_synthetic_scene(plan);
  RenderOptions render;
  render.width = 512;
  render.height = 256;
  render.depth = false;
  std::vector<cv::Mat> frames;
  for (const PathFrame& f : truth.frames) frames.push_back(render_panorama(scene, f, render).rgb);

  EgomotionOptions options;
  options.camera_height_m = 1.6;
  const EgomotionResult tracked = EgomotionTracker::run(
      static_cast<int>(frames.size()), [&](int i) { return frames[i]; }, options);
  ASSERT_EQ(tracked.path.size(), truth.size());
  const std::size_t n = truth.size();

  // 0.15 deg of heading bias per frame (16 deg over the walk) and steps 6 % too long.
  const CameraPath drifted = with_drift(tracked.path, radians(0.15), 1.06);
  Anchors anchors;
  for (std::size_t i : {std::size_t{0}, n / 2, n - 1})
    anchors.push_back({truth.frames[i].index, truth.frames[i].position(), std::nullopt});
  AnchorRefinementReport report;
  const CameraPath refined = refine_path_with_anchors(drifted, anchors, {}, &report);

  const PathErrors own = evaluate_path(tracked.path, truth);
  const PathErrors before = evaluate_path(drifted, truth);
  const PathErrors after = evaluate_path(refined, truth);
  std::printf(
      "tracked walk of %zu frames (%.1f m): tracker ATE %.3f m; with injected drift %.3f m; refined with "
      "3 anchors %.3f m (%.1fx lower)\n",
      n, before.truth_length_m, own.ate_rms_m, before.ate_rms_m, after.ate_rms_m,
      before.ate_rms_m / after.ate_rms_m);
  EXPECT_GT(before.ate_rms_m / after.ate_rms_m, 5.0);
  for (const Anchor& a : anchors) {
    const double off = (refined.find_frame(a.frame)->position() - a.position).norm();
    std::printf("  anchored frame %d: %.4f m from its anchor\n", a.frame, off);
    EXPECT_LT(off, 0.05) << "frame " << a.frame;
  }
}

}  // namespace
}  // namespace plenopath
