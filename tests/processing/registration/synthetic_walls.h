#pragma once
// Synthetic tracker points for registration tests (processing/registration and the studio's placement):
// wall points sampled on a plan's own walls with noise, plus floor, ceiling and stray points, all moved into
// a path frame by a known similarity, so that a registration must find that similarity again.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "model/path_points.h"
#include "processing/egomotion/path_evaluation.h"

namespace plenopath::test {

inline void wall(FloorPlan* plan, Eigen::Vector2d a, Eigen::Vector2d b) {
  plan->segments.push_back({a, b, "WALLS", true});
}

// A 10 x 6 m room with a short wall in the middle of each long side: the same after a half turn.
inline FloorPlan symmetric_room() {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  wall(&plan, {0, 0}, {10, 0});
  wall(&plan, {10, 0}, {10, 6});
  wall(&plan, {10, 6}, {0, 6});
  wall(&plan, {0, 6}, {0, 0});
  wall(&plan, {3, 0}, {3, 2});
  wall(&plan, {7, 6}, {7, 4});
  return plan;
}

struct SyntheticPiece {
  CameraPath path;  // in its own frame
  std::vector<PathPoint> points;
};

// Points on the walls of `plan` within `range` of the walk (as a camera would see them), plus floor,
// ceiling and stray points; all in the frame that `truth` maps onto the plan.
inline SyntheticPiece synthesise(const FloorPlan& plan, const std::vector<Eigen::Vector2d>& walk,
                                 const Similarity2& truth, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double c = std::cos(-truth.rotation), s = std::sin(-truth.rotation);
  auto to_piece = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = (p - truth.translation) / truth.scale;
    return Eigen::Vector2d(c * d.x() - s * d.y(), s * d.x() + c * d.y());
  };
  SyntheticPiece out;
  for (std::size_t i = 0; i < walk.size(); ++i) {
    PathFrame f;
    f.index = static_cast<int>(i);
    const Eigen::Vector2d p = to_piece(walk[i]);
    f.x = p.x();
    f.y = p.y();
    out.path.frames.push_back(f);
  }
  auto add = [&](const Eigen::Vector2d& plan_xy, double z) {
    PathPoint p;
    const Eigen::Vector2d q = to_piece(plan_xy);
    p.position = {q.x(), q.y(), z / truth.scale};
    p.observations = 3 + static_cast<int>(rng() % 8);
    out.points.push_back(p);
  };
  for (const PlanSegment& seg : plan.segments)
    for (double t = 0; t < seg.length(); t += 0.05) {
      const Eigen::Vector2d p = seg.a + (seg.b - seg.a) * (t / seg.length());
      double nearest = 1e9;
      for (const Eigen::Vector2d& w : walk) nearest = std::min(nearest, (w - p).norm());
      if (nearest > 6.0 || unit(rng) < 0.3) continue;
      const Eigen::Vector2d n = Eigen::Vector2d(noise(rng), noise(rng));
      add(p + n, -1.6 + 0.35 + 2.1 * unit(rng) * 0.9);  // between the floor and the ceiling bands
    }
  const std::size_t wall_count = out.points.size();
  const PlanExtents e = plan.extents();
  for (std::size_t i = 0; i < wall_count / 3; ++i) {  // floor and ceiling points anywhere near the walk
    const Eigen::Vector2d& w = walk[rng() % walk.size()];
    const Eigen::Vector2d p = w + Eigen::Vector2d(4 * unit(rng) - 2, 4 * unit(rng) - 2);
    add(p, unit(rng) < 0.5 ? -1.6 : 1.2);
  }
  for (std::size_t i = 0; i < wall_count / 10; ++i)  // strays: furniture, people, bad triangulations
    add(e.min + Eigen::Vector2d(unit(rng) * e.size().x(), unit(rng) * e.size().y()), -0.8 + unit(rng));
  return out;
}

}  // namespace plenopath::test
