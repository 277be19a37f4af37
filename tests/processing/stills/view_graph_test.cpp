// The view graph's global steps on synthetic pairwise measurements with known truth: noisy turns and
// directions, wrong edges among them, lengths on some edges or none.
#include "processing/stills/view_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/camera_path.h"
#include "tests/processing/stills/similarity_2d.h"

namespace plenopath {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Truth {
  std::vector<Eigen::Vector2d> positions;
  std::vector<double> headings;
};

Truth random_stills(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> x(0.0, 8.0), y(0.0, 6.0), angle(-M_PI, M_PI);
  Truth t;
  for (int i = 0; i < n; ++i) {
    t.positions.emplace_back(x(rng), y(rng));
    t.headings.push_back(angle(rng));
  }
  return t;
}

// The measurement of pair (a, b) with noise; `wrong_turn` adds a gross error to the turn.
ViewEdge measure(const Truth& t, int a, int b, double turn_noise_deg, double direction_noise_deg, bool length,
                 double wrong_turn, std::mt19937& rng) {
  std::normal_distribution<double> turn_noise(0.0, turn_noise_deg * kDeg),
      dir_noise(0.0, direction_noise_deg * kDeg), length_noise(0.0, 0.01);
  const Eigen::Vector2d d =
      t.positions[static_cast<std::size_t>(b)] - t.positions[static_cast<std::size_t>(a)];
  ViewEdge e;
  e.a = a;
  e.b = b;
  e.turn = wrap_angle(t.headings[static_cast<std::size_t>(b)] - t.headings[static_cast<std::size_t>(a)] +
                      turn_noise(rng) + wrong_turn);
  e.direction =
      wrap_angle(std::atan2(d.y(), d.x()) - t.headings[static_cast<std::size_t>(a)] + dir_noise(rng));
  e.weight = 100;
  e.length = length ? d.norm() * (1.0 + length_noise(rng)) : 0.0;
  return e;
}

// The similarity taking `estimate` onto `truth`, then the residuals.
struct Alignment {
  double scale = 1, rotation = 0, worst_position = 0, worst_heading = 0;
};
Alignment align(const std::vector<Eigen::Vector2d>& estimate, const std::vector<double>& est_headings,
                const Truth& truth) {
  const Similarity2d T = fit_similarity_2d(estimate, truth.positions);
  Alignment out;
  out.scale = T.scale;
  out.rotation = T.rotation;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    out.worst_position = std::max(out.worst_position, (T.apply(estimate[i]) - truth.positions[i]).norm());
    out.worst_heading =
        std::max(out.worst_heading, std::abs(wrap_angle(est_headings[i] + T.rotation - truth.headings[i])));
  }
  return out;
}

TEST(ViewGraph, GroupsAreTheConnectedComponentsLargestFirst) {
  std::vector<ViewEdge> edges(3);
  edges[0].a = 3;
  edges[0].b = 5;
  edges[1].a = 0;
  edges[1].b = 1;
  edges[2].a = 1;
  edges[2].b = 4;
  const std::vector<std::vector<int>> groups = connected_groups(6, edges);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0], (std::vector<int>{0, 1, 4}));
  EXPECT_EQ(groups[1], (std::vector<int>{3, 5}));
  EXPECT_EQ(groups[2], (std::vector<int>{2}));
}

TEST(ViewGraph, HeadingsAndPositionsFromNoisyPairsWithWrongEdges) {
  std::mt19937 rng(21);
  const int n = 10;
  const Truth truth = random_stills(n, rng);
  std::vector<ViewEdge> edges;
  std::vector<bool> wrong;
  int k = 0;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b, ++k) {
      const bool bad = k % 9 == 4;  // 5 of 45 edges with a gross turn error
      edges.push_back(measure(truth, a, b, 0.1, 0.3, k % 3 == 0, bad ? (k % 2 ? 25 : -40) * kDeg : 0.0, rng));
      wrong.push_back(bad);
    }
  std::vector<int> group(n);
  for (int i = 0; i < n; ++i) group[static_cast<std::size_t>(i)] = i;
  std::vector<bool> kept;
  const std::vector<double> headings = average_headings(n, group, edges, HeadingAveragingOptions{}, &kept);
  for (std::size_t e = 0; e < edges.size(); ++e) EXPECT_EQ(kept[e], !wrong[e]) << "edge " << e;
  EXPECT_EQ(headings[0], 0.0);
  std::vector<Eigen::Vector2d> positions;
  bool scale_known = false;
  ASSERT_TRUE(solve_positions(n, group, edges, kept, headings, &positions, &scale_known));
  EXPECT_TRUE(scale_known);
  EXPECT_EQ(positions[0], Eigen::Vector2d::Zero());
  const Alignment a = align(positions, headings, truth);
  EXPECT_LT(a.worst_heading, 0.15 * kDeg);
  EXPECT_LT(a.worst_position, 0.05);
  EXPECT_NEAR(a.scale, 1.0, 0.01);  // the lengths are metric
}

TEST(ViewGraph, DirectionsAloneFixThePositionsUpToScale) {
  std::mt19937 rng(4);
  const int n = 8;
  const Truth truth = random_stills(n, rng);
  std::vector<ViewEdge> edges;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) edges.push_back(measure(truth, a, b, 0.05, 0.2, false, 0.0, rng));
  std::vector<int> group(n);
  for (int i = 0; i < n; ++i) group[static_cast<std::size_t>(i)] = i;
  std::vector<bool> kept;
  const std::vector<double> headings = average_headings(n, group, edges, HeadingAveragingOptions{}, &kept);
  std::vector<Eigen::Vector2d> positions;
  bool scale_known = true;
  ASSERT_TRUE(solve_positions(n, group, edges, kept, headings, &positions, &scale_known));
  EXPECT_FALSE(scale_known);
  const Alignment a = align(positions, headings, truth);
  EXPECT_GT(a.scale, 0);
  EXPECT_LT(a.worst_position, 0.05);
  EXPECT_LT(a.worst_heading, 0.1 * kDeg);
}

TEST(ViewGraph, AChainOfDirectionsWithoutLengthsIsNotFixed) {
  // Three stills in a chain 0-1-2: the directions say nothing about the ratio of the two steps.
  std::mt19937 rng(8);
  Truth truth;
  truth.positions = {{0, 0}, {2, 0}, {3, 1.5}};
  truth.headings = {0.1, 0.5, -0.3};
  const std::vector<ViewEdge> edges = {measure(truth, 0, 1, 0, 0, false, 0, rng),
                                       measure(truth, 1, 2, 0, 0, false, 0, rng)};
  std::vector<bool> kept;
  const std::vector<int> group = {0, 1, 2};
  const std::vector<double> headings = average_headings(3, group, edges, HeadingAveragingOptions{}, &kept);
  std::vector<Eigen::Vector2d> positions;
  bool scale_known = false;
  EXPECT_FALSE(solve_positions(3, group, edges, kept, headings, &positions, &scale_known));
  // One length: the other step's is still free. Both: fixed.
  std::vector<ViewEdge> metric = edges;
  metric[0].length = 2.0;
  EXPECT_FALSE(solve_positions(3, group, metric, kept, headings, &positions, &scale_known));
  metric[1].length = std::hypot(1.0, 1.5);
  ASSERT_TRUE(solve_positions(3, group, metric, kept, headings, &positions, &scale_known));
  EXPECT_NEAR((positions[2] - positions[0]).norm(), std::hypot(3.0, 1.5), 1e-6);
}

}  // namespace
}  // namespace plenopath
