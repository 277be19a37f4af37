// The grid search for close parallel pairs against hand-computed cases and an all-pairs oracle.
#include "processing/plan/parallel_pairs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/error.h"

namespace plenopath {
namespace {

TEST(ParallelPairs, AWallDrawnAsTwoLines) {
  // Two faces 0.2 apart, overlapping over 3 of their 4 and 3.5 units; a third line 1.0 away (too far); a
  // collinear piece of the first (gap 0) that no other line overlaps; a line at 30 degrees (not parallel).
  const std::vector<Segment2> s = {{{0, 0}, {4, 0}},
                                   {{1, 0.2}, {4.5, 0.2}},
                                   {{0, 1.2}, {4, 1.2}},
                                   {{0, 0}, {0.8, 0}},
                                   {{0, 0}, {2, 1.1547}}};
  const ParallelPairs p = find_parallel_pairs(s, {});
  ASSERT_EQ(p.pairs.size(), 1u);
  EXPECT_EQ(p.pairs[0].i, 0);
  EXPECT_EQ(p.pairs[0].j, 1);
  EXPECT_NEAR(p.pairs[0].gap, 0.2, 1e-12);
  EXPECT_NEAR(p.pairs[0].overlap, 3.0, 1e-12);
  EXPECT_EQ(p.left[0], 0);   // segment 1 lies on the left of segment 0's +x direction
  EXPECT_EQ(p.right[1], 0);  // and segment 0 on the right of segment 1
  EXPECT_EQ(p.right[0], -1);
  EXPECT_EQ(p.nearest(0), 0);
  EXPECT_EQ(p.nearest(2), -1);
  // Reversed direction is the same line: sides are taken with the direction's angle in [0, pi).
  const ParallelPairs q = find_parallel_pairs({{{4, 0}, {0, 0}}, {{4.5, 0.2}, {1, 0.2}}}, {});
  ASSERT_EQ(q.pairs.size(), 1u);
  EXPECT_EQ(q.left[0], 0);
}

TEST(ParallelPairs, AStackOfCopiesElsewhereDoesNotHideAWall) {
  // 5000 copies of one line (a fuzzed file, a block arrayed in place) and, 3 units away, a wall drawn as two
  // faces 0.2 apart: the search bounds its work per segment, and the wall's faces still pair.
  std::vector<Segment2> s(5000, Segment2{{0, 0}, {2, 0}});
  s.push_back({{0, 3}, {4, 3}});
  s.push_back({{0, 3.2}, {4, 3.2}});
  ParallelPairOptions options;
  options.max_candidates_per_segment = 64;
  const ParallelPairs p = find_parallel_pairs(s, options);
  EXPECT_EQ(p.nearest(5000), p.nearest(5001));
  ASSERT_GE(p.nearest(5000), 0);
  EXPECT_NEAR(p.pairs[static_cast<std::size_t>(p.nearest(5000))].gap, 0.2, 1e-12);
  options.max_candidates_per_segment = 0;
  EXPECT_THROW(options.check(), Error);
}

TEST(ParallelPairs, ShortOverlapsAndBadOptions) {
  // 0.5 apart but overlapping 0.6 only: less than 2 gaps long, not a wall.
  EXPECT_TRUE(find_parallel_pairs({{{0, 0}, {0.6, 0}}, {{0, 0.5}, {0.6, 0.5}}}, {}).pairs.empty());
  ParallelPairOptions o;
  o.max_gap = 0.0;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.min_overlap_fraction = 2.0;
  EXPECT_THROW(find_parallel_pairs({}, o), Error);
}

TEST(ParallelPairs, StraysFarAwayAreLeftOut) {
  const std::vector<Segment2> s = {
      {{0, 0}, {4, 0}}, {{0, 0.2}, {4, 0.2}}, {{1e20, 0}, {1e20 + 1e6, 0}}, {{-1e15, 5}, {1e15, 5}}};
  const ParallelPairs p = find_parallel_pairs(s, {});
  ASSERT_EQ(p.pairs.size(), 1u);
  EXPECT_EQ(p.left[2], -1);
  EXPECT_EQ(p.left[3], -1);
}

// All-pairs search with the same definition, for random axis-near segments.
struct Best {
  int j = -1;
  double gap = 0.0;
};
void brute_force(const std::vector<Segment2>& s, const ParallelPairOptions& o, std::vector<Best>* left,
                 std::vector<Best>* right) {
  const int n = static_cast<int>(s.size());
  left->assign(n, {});
  right->assign(n, {});
  auto dir = [&](int i) {
    Eigen::Vector2d d = (s[i].b - s[i].a).normalized();
    if (d.y() < 0 || (d.y() == 0 && d.x() < 0)) d = -d;
    return d;
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      const Eigen::Vector2d u = dir(i), v = dir(j);
      if (std::abs(u.x() * v.y() - u.y() * v.x()) > std::sin(o.max_angle)) continue;
      const double li = (s[i].b - s[i].a).norm(), lj = (s[j].b - s[j].a).norm();
      // Both segments as intervals along u; the overlap; j's point at the overlap's middle, and its signed
      // distance from i's line.
      const double ia = s[i].a.dot(u), ib = s[i].b.dot(u), ja = s[j].a.dot(u), jb = s[j].b.dot(u);
      const double lo = std::max(std::min(ia, ib), std::min(ja, jb));
      const double hi = std::min(std::max(ia, ib), std::max(ja, jb));
      if (hi - lo <= 0) continue;
      const double tm = 0.5 * (lo + hi);
      const Eigen::Vector2d q = s[j].a + (tm - ja) / (jb - ja) * (s[j].b - s[j].a);
      const Eigen::Vector2d r = q - s[i].a;
      const double side = u.x() * r.y() - u.y() * r.x();
      const double gap = std::abs(side);
      if (gap < o.min_gap || gap > o.max_gap || hi - lo < o.min_overlap_fraction * std::min(li, lj) ||
          hi - lo < o.min_overlap_gaps * gap)
        continue;
      Best& b = side > 0 ? (*left)[i] : (*right)[i];
      if (b.j < 0 || gap < b.gap) b = {j, gap};
    }
}

TEST(ParallelPairs, GridAgreesWithAllPairs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(0, 30), len(0.3, 5), jitter(-0.01, 0.01);
  std::vector<Segment2> s;
  for (int k = 0; k < 1500; ++k) {
    const Eigen::Vector2d a(pos(rng), pos(rng));
    const double angle = (k % 3) * M_PI / 2 + jitter(rng) + (k % 7 == 0 ? 0.7 : 0.0);
    s.push_back({a, a + len(rng) * Eigen::Vector2d(std::cos(angle), std::sin(angle))});
  }
  ParallelPairOptions o;
  o.cell_size = 0.25;  // several rings of cells, to exercise the neighbourhood walk
  const ParallelPairs grid = find_parallel_pairs(s, o);
  std::vector<Best> left, right;
  brute_force(s, o, &left, &right);
  int found = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    for (int side = 0; side < 2; ++side) {
      const Best& b = side == 0 ? left[i] : right[i];
      const int index = side == 0 ? grid.left[i] : grid.right[i];
      ASSERT_EQ(index >= 0, b.j >= 0) << i;
      if (index < 0) continue;
      ++found;
      const ParallelPair& p = grid.pairs[static_cast<std::size_t>(index)];
      ASSERT_TRUE(p.i == static_cast<int>(i) || p.j == static_cast<int>(i));
      EXPECT_EQ(p.i == static_cast<int>(i) ? p.j : p.i, b.j) << i;  // the same nearest partner
    }
  }
  EXPECT_GT(found, 100);  // the random set has plenty of close parallel neighbours
}

// Few segments, some crossing thousands of cells (a fine grid, long walls): compared with every segment
// rather than through the grid, with the same outcome.
TEST(ParallelPairs, LongSegmentsAmongFewAgreeWithAllPairs) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(0, 60), len(0.3, 5), jitter(-0.01, 0.01);
  std::vector<Segment2> s = {
      {{0, 0}, {400, 0}}, {{10, 0.3}, {300, 0.31}}, {{0, 40}, {0, -50}}, {{0.2, 30}, {0.2, -20}}};
  for (int k = 0; k < 60; ++k) {
    const Eigen::Vector2d a(pos(rng), pos(rng) - 30);
    const double angle = (k % 2) * M_PI / 2 + jitter(rng);
    s.push_back({a, a + len(rng) * Eigen::Vector2d(std::cos(angle), std::sin(angle))});
  }
  ParallelPairOptions o;
  o.cell_size = 0.02;
  const ParallelPairs grid = find_parallel_pairs(s, o);
  std::vector<Best> left, right;
  brute_force(s, o, &left, &right);
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int side = 0; side < 2; ++side) {
      const Best& b = side == 0 ? left[i] : right[i];
      const int index = side == 0 ? grid.left[i] : grid.right[i];
      ASSERT_EQ(index >= 0, b.j >= 0) << i;
      if (index < 0) continue;
      const ParallelPair& p = grid.pairs[static_cast<std::size_t>(index)];
      EXPECT_EQ(p.i == static_cast<int>(i) ? p.j : p.i, b.j) << i;
    }
  EXPECT_TRUE(grid.left[0] >= 0 || grid.right[0] >= 0);  // the two long walls pair
}

}  // namespace
}  // namespace plenopath
