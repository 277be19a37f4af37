// Edge lengths from shared features, against the known lengths of a synthetic chain of stills down a
// corridor: all on one line, so the directions alone cannot place them (view_graph_test shows that).
#include "processing/stills/edge_lengths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/camera_path.h"
#include "processing/stills/view_graph.h"

namespace plenopath {
namespace {

Eigen::Vector3d rotate_z(const Eigen::Vector3d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}

struct Chain {
  std::vector<Eigen::Vector2d> positions;
  std::vector<double> headings;
  std::vector<Eigen::Vector3d> points;
  std::vector<ViewEdge> edges;
  std::vector<EdgeDepths> depths;
};

// Five stills along y = 0 (a corridor), points on its walls (y = +-1) and floor; edges between neighbours
// and next neighbours. Feature k of every still is point k.
Chain corridor(double noise_deg, std::mt19937& rng) {
  Chain c;
  c.positions = {{0, 0}, {1.5, 0}, {3.5, 0}, {5.0, 0}, {7.2, 0}};
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), x(-2.0, 9.0), z(-1.6, 1.2);
  for (std::size_t i = 0; i < c.positions.size(); ++i) c.headings.push_back(angle(rng));
  for (int k = 0; k < 300; ++k) c.points.emplace_back(x(rng), k % 2 ? 1.0 : -1.0, z(rng));
  std::normal_distribution<double> noise(0.0, noise_deg * M_PI / 180.0);
  auto bearing = [&](int still, const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - Eigen::Vector3d(c.positions[static_cast<std::size_t>(still)].x(),
                                                  c.positions[static_cast<std::size_t>(still)].y(), 0.0);
    return (rotate_z(d, -c.headings[static_cast<std::size_t>(still)]).normalized() +
            Eigen::Vector3d(noise(rng), noise(rng), noise(rng)))
        .normalized();
  };
  for (int a = 0; a < 5; ++a)
    for (int b = a + 1; b < std::min(5, a + 3); ++b) {
      const Eigen::Vector2d d =
          c.positions[static_cast<std::size_t>(b)] - c.positions[static_cast<std::size_t>(a)];
      ViewEdge e;
      e.a = a;
      e.b = b;
      e.turn = wrap_angle(c.headings[static_cast<std::size_t>(b)] - c.headings[static_cast<std::size_t>(a)]);
      e.direction = wrap_angle(std::atan2(d.y(), d.x()) - c.headings[static_cast<std::size_t>(a)]);
      e.weight = 100;
      c.edges.push_back(e);
      EdgeDepths depths;
      depths.a = a;
      depths.b = b;
      std::vector<Eigen::Vector3d> ba, bb;
      for (int k = 0; k < static_cast<int>(c.points.size()); ++k) {
        depths.features.push_back({k, k});
        ba.push_back(bearing(a, c.points[static_cast<std::size_t>(k)]));
        bb.push_back(bearing(b, c.points[static_cast<std::size_t>(k)]));
      }
      triangulate_unit_baseline(ba, bb, e.turn, e.direction, 2.0, &depths.depth_a, &depths.depth_b);
      c.depths.push_back(depths);
    }
  return c;
}

double true_length(const Chain& c, std::size_t e) {
  return (c.positions[static_cast<std::size_t>(c.edges[e].b)] -
          c.positions[static_cast<std::size_t>(c.edges[e].a)])
      .norm();
}

TEST(EdgeLengths, RatiosOfSharedFeaturesGiveEveryLengthFromOne) {
  std::mt19937 rng(12);
  Chain c = corridor(0.0, rng);
  c.depths[0].metric_length = true_length(c, 0);  // one length from the floor
  c.depths[0].metric_weight = 20;
  const EdgeLengths lengths = solve_edge_lengths(5, c.depths);
  EXPECT_TRUE(lengths.metric);
  EXPECT_GT(lengths.ratios, 5);
  for (std::size_t e = 0; e < c.edges.size(); ++e)
    EXPECT_NEAR(lengths.length[e], true_length(c, e), 1e-6) << e;
}

TEST(EdgeLengths, WithoutAFloorLengthTheRatiosStillPlaceACorridorChain) {
  std::mt19937 rng(5);
  Chain c = corridor(0.05, rng);
  const EdgeLengths lengths = solve_edge_lengths(5, c.depths);
  EXPECT_FALSE(lengths.metric);
  const double scale = true_length(c, 0) / lengths.length[0];
  for (std::size_t e = 0; e < c.edges.size(); ++e)
    EXPECT_NEAR(scale * lengths.length[e], true_length(c, e), 0.01 * true_length(c, e)) << e;
  // The collinear chain: directions alone leave it unfixed, with the lengths it is placed.
  std::vector<bool> kept(c.edges.size(), true);
  std::vector<Eigen::Vector2d> positions;
  bool scale_known = false;
  const std::vector<int> group = {0, 1, 2, 3, 4};
  EXPECT_FALSE(solve_positions(5, group, c.edges, kept, c.headings, &positions, &scale_known));
  for (std::size_t e = 0; e < c.edges.size(); ++e) c.edges[e].length = lengths.length[e];
  ASSERT_TRUE(solve_positions(5, group, c.edges, kept, c.headings, &positions, &scale_known));
  for (int i = 0; i < 5; ++i)
    EXPECT_NEAR(
        (scale * positions[static_cast<std::size_t>(i)] - c.positions[static_cast<std::size_t>(i)]).norm(),
        0.0, 0.03)
        << i;
}

}  // namespace
}  // namespace plenopath
