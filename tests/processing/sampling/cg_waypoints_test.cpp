// Waypoints for the CG capture (issue 23): a walk thinned to its corners (what the studio's Auto walk
// types into the CG scene dialog) and the text walk_waypoints reads back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "model/error.h"
#include "processing/sampling/cg_capture.h"

namespace plenopath {
namespace {

// Distance from p to the polyline (brute force over every segment).
double distance_to_polyline(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& line) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const Eigen::Vector2d a = line[k], ab = line[k + 1] - line[k];
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

TEST(CgWaypoints, AWobblyRectangleWalkThinsToItsFourCorners) {
  // (0,0) -> (4,0) -> (4,3) -> (0,3), a frame every centimetre, wobbling up to 1 cm inward with a period
  // of 0.5 m (so exactly on the line at the corners, which are at multiples of 0.5 m along the walk).
  const std::vector<Eigen::Vector2d> corners = {{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  CameraPath path;
  double s = 0.0;
  for (std::size_t k = 0; k + 1 < corners.size(); ++k) {
    const Eigen::Vector2d d = (corners[k + 1] - corners[k]).normalized(), side(-d.y(), d.x());
    const double length = (corners[k + 1] - corners[k]).norm();
    for (int i = 0; i < std::lround(length * 100) + (k + 2 == corners.size()); ++i, s += 0.01) {
      const Eigen::Vector2d p =
          corners[k] + 0.01 * i * d + 0.01 * std::pow(std::sin(2 * M_PI * s / 0.5), 2) * side;
      PathFrame f;
      f.index = static_cast<int>(path.frames.size());
      f.x = p.x();
      f.y = p.y();
      path.frames.push_back(f);
    }
  }
  const std::vector<Eigen::Vector2d> kept = path_corners(path, 0.05);
  ASSERT_EQ(kept.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_LT((kept[k] - corners[k]).norm(), 1e-9) << k;
  // A tolerance under the wobble keeps more, and every frame stays within it.
  const std::vector<Eigen::Vector2d> fine = path_corners(path, 0.004);
  EXPECT_GT(fine.size(), 20u);
  for (const PathFrame& f : path.frames) EXPECT_LE(distance_to_polyline(f.position(), fine), 0.004 + 1e-12);
}

TEST(CgWaypoints, EveryFrameOfARandomWalkStaysWithinTheTolerance) {
  std::mt19937 rng(7);
  std::normal_distribution<double> turn(0.0, 0.3);
  CameraPath path;
  Eigen::Vector2d p(1, 2);
  double heading = 0.0;
  for (int i = 0; i < 3000; ++i) {
    heading += turn(rng);
    p += 0.05 * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    PathFrame f;
    f.index = i;
    f.x = p.x();
    f.y = p.y();
    path.frames.push_back(f);
  }
  const std::vector<Eigen::Vector2d> kept = path_corners(path, 0.05);
  EXPECT_LT(kept.size(), path.size() / 2);
  EXPECT_EQ(kept.front(), path.frames.front().position());
  EXPECT_EQ(kept.back(), path.frames.back().position());
  for (const PathFrame& f : path.frames) EXPECT_LE(distance_to_polyline(f.position(), kept), 0.05 + 1e-12);
  EXPECT_THROW(path_corners(path, 0.0), Error);
}

TEST(CgWaypoints, TheTextHasTwoDecimalsAndReadsBackAsTheWalk) {
  const std::vector<Eigen::Vector2d> points = {{1.234, -0.004}, {5.0, 0.0}, {5.0, 7.456}};
  const std::string text = waypoints_text(points);
  EXPECT_EQ(text, "1.23,0.00 5.00,0.00 5.00,7.46");
  const CameraPath walk = walk_waypoints(text, 0.5);
  ASSERT_FALSE(walk.empty());
  EXPECT_NEAR(walk.frames.front().x, 1.23, 1e-9);
  EXPECT_NEAR(walk.frames.front().y, 0.0, 1e-9);
  // 3.77 m then 7.46 m: a frame every 0.5 m from the start, the last at 11 m along.
  EXPECT_EQ(walk.size(), 23u);
  EXPECT_NEAR(walk.frames.back().x, 5.0, 1e-9);
  EXPECT_NEAR(walk.frames.back().y, 11.0 - 3.77, 1e-9);
  EXPECT_EQ(waypoints_text({}), "");
}

}  // namespace
}  // namespace plenopath
