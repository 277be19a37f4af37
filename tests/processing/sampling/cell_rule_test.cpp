// The seed's rule on hand-built cells: counts per cell computed by hand.
#include "processing/sampling/cell_rule.h"

#include <gtest/gtest.h>

#include "model/error.h"
#include "processing/sampling/keyframe_sampler.h"
#include "processing/visibility/visibility.h"
#include "sampling_test_util.h"

namespace plenopath {
namespace {

using sampling_test::straight_path;

// Keyframes (by arc length) falling inside [begin, end).
int count_in(const CameraPath& path, const Keyframes& k, double begin, double end) {
  int n = 0;
  for (int index : k.indices) {
    const double x = path.find_frame(index)->x;
    if (x >= begin && x < end) ++n;
  }
  return n;
}

// An 8 m straight path (801 frames, 1 cm apart) crossing three cells: [0, 2) v = 4, [2, 6) v = 32,
// [6, 8] v = 1.
VisibilityCells hand_cells() {
  VisibilityCells cells;
  auto cell = [](double a, double b, double v) {
    VisibilityCell c;
    c.s_begin = a;
    c.s_end = b;
    c.length = b - a;
    c.area_mid = v;
    return c;
  };
  cells.cells = {cell(0, 2, 4), cell(2, 6, 32), cell(6, 8, 1)};
  return cells;
}

TEST(CellRule, MassesAreLengthToTheExponentOverSize) {
  std::vector<SamplingCell> cells = {{0, 2, 4}, {2, 6, 32}, {6, 8, 1}};
  CellRuleOptions o;
  o.exponent = 3.0;
  const auto m = cell_masses(cells, o);
  EXPECT_DOUBLE_EQ(m[0], 2.0);  // 2^3 / 4
  EXPECT_DOUBLE_EQ(m[1], 2.0);  // 4^3 / 32
  EXPECT_DOUBLE_EQ(m[2], 8.0);  // 2^3 / 1
  o.exponent = 1.0;
  const auto m1 = cell_masses(cells, o);
  EXPECT_DOUBLE_EQ(m1[1], 0.125);
  o.exponent = -1.0;
  EXPECT_THROW(cell_masses(cells, o), Error);
}

TEST(CellRule, AllocatesByHandComputedCounts) {
  const CameraPath path = straight_path(801, 0.01);
  const VisibilityCells cells = hand_cells();
  SamplingInputs in;
  in.path = &path;
  in.cells = &cells;
  SamplingParameters p;
  p.method = SamplingMethod::kVisibility;
  p.rule = VisibilityRule::cell_rule;
  p.transition_boost = 0.0;
  // Keyframes sit at equal steps k / (count - 1) of cumulative mass, the ends included.
  // e = 3: masses 2 : 2 : 8, boundaries at 1/6 and 1/3. count 14, steps k/13: cell 1 holds k = 0..2,
  // cell 2 k = 3..4, cell 3 k = 5..13.
  p.exponent = 3.0;
  p.count = 14;
  Keyframes k = sample_keyframes(in, p);
  ASSERT_EQ(k.indices.size(), 14u);
  EXPECT_EQ(count_in(path, k, 0.0, 2.0), 3);
  EXPECT_EQ(count_in(path, k, 2.0, 6.0), 2);
  EXPECT_EQ(count_in(path, k, 6.0, 8.5), 9);
  // e = 2: masses 1 : 0.5 : 4, boundaries at 2/11 and 3/11. count 13, steps k/12: k = 0..2, 3, 4..12.
  p.exponent = 2.0;
  p.count = 13;
  k = sample_keyframes(in, p);
  EXPECT_EQ(count_in(path, k, 0.0, 2.0), 3);
  EXPECT_EQ(count_in(path, k, 2.0, 6.0), 1);
  EXPECT_EQ(count_in(path, k, 6.0, 8.5), 9);
  // e = 1: masses 0.5 : 0.125 : 2 = 4 : 1 : 16, boundaries at 4/21 and 5/21. count 21, steps k/20:
  // k = 0..3, 4, 5..20.
  p.exponent = 1.0;
  p.count = 21;
  k = sample_keyframes(in, p);
  EXPECT_EQ(count_in(path, k, 0.0, 2.0), 4);
  EXPECT_EQ(count_in(path, k, 2.0, 6.0), 1);
  EXPECT_EQ(count_in(path, k, 6.0, 8.5), 16);
  // The one in the middle cell (mass 4/21 .. 5/21 over 4 m) sits at step 4/20: s = 2 + 4 (0.2 * 21 - 4).
  for (int index : k.indices) {
    const double x = path.find_frame(index)->x;
    if (x >= 2.0 && x < 6.0) {
      EXPECT_NEAR(x, 2.8, 0.011);
    }
  }
}

TEST(CellRule, TransitionBoostAddsKeyframesAtBigChanges) {
  const CameraPath path = straight_path(801, 0.01);
  const VisibilityCells cells = hand_cells();  // v: 4 -> 32 (ln 8) and 32 -> 1 (ln 32)
  SamplingInputs in;
  in.path = &path;
  in.cells = &cells;
  SamplingParameters p;
  p.method = SamplingMethod::kVisibility;
  p.rule = VisibilityRule::cell_rule;
  p.exponent = 1.0;  // masses 0.5, 0.125, 2 -> densities per metre 0.25, 0.03125, 1 (relative)
  p.count = 42;
  p.transition_boost = 0.0;
  const Keyframes plain = sample_keyframes(in, p);
  p.transition_boost = 2.0;
  const Keyframes boosted = sample_keyframes(in, p);
  // Within 1 m of the boundary at 6 m (the larger change) the boost adds keyframes.
  EXPECT_GT(count_in(path, boosted, 5.0, 7.0), count_in(path, plain, 5.0, 7.0));
  EXPECT_EQ(boosted.indices.size(), 42u);
  // Hand check of the density: total mass before boost is 1 over 8 m, so the mean density is 1/8; the boost
  // adds 2 * ln(32) / 8 per metre on [5, 7].
  CellRuleOptions o;
  o.exponent = 1.0;
  o.transition_boost = 2.0;
  const DensityProfile d = cell_rule_density({{0, 2, 4}, {2, 6, 32}, {6, 8, 1}}, 8.0, o);
  const double added = 2.0 * std::log(32.0) / 8.0 * 2.0 + 2.0 * std::log(8.0) / 8.0 * 2.0;
  EXPECT_NEAR(d.total_mass(), 1.0 + added, 1e-9);
  // On [6, 6.5]: the last cell's own density (mass 2 of 2.625 over 2 m) plus the boost.
  EXPECT_NEAR(d.mass_at(6.5) - d.mass_at(6.0), 0.5 * (2.0 / 2.625 / 2.0) + 0.5 * 2.0 * std::log(32.0) / 8.0,
              1e-9);
}

// On a real plan, the cells the index finds get the counts the rule gives for their own l and v.
TEST(CellRule, FollowsTheRuleOnAPlan) {
  const FloorPlan plan = sampling_test::three_rooms();
  const CameraPath path = sampling_test::three_rooms_path();
  const VisibilityIndex index(plan);
  const VisibilityCells cells = index.cells_along_path(path);
  ASSERT_GE(cells.cells.size(), 3u);
  SamplingInputs in;
  in.path = &path;
  in.cells = &cells;
  in.index = &index;
  SamplingParameters p;
  p.method = SamplingMethod::kVisibility;
  p.rule = VisibilityRule::cell_rule;
  p.exponent = 2.0;
  p.transition_boost = 0.0;
  p.count = 60;
  const Keyframes k = sample_keyframes(in, p);
  ASSERT_EQ(k.indices.size(), 60u);
  // Expected count per cell, by hand from its l and v: its share of the 59 steps between the ends.
  // v is the cell's mean envelope area (its middle's when the mean was not measured).
  auto v = [](const VisibilityCell& c) {
    return std::max(c.area_mean > 0.0 ? c.area_mean : c.area_mid, 0.01);
  };
  double total = 0.0;
  for (const auto& c : cells.cells) total += c.length * c.length / v(c);
  for (const auto& c : cells.cells) {
    const double expected = 59.0 * c.length * c.length / v(c) / total;
    const bool last = c.s_end >= path.length() - 1e-9;
    const int got = count_in(path, k, 0.5 + c.s_begin, last ? 1e9 : 0.5 + c.s_end);
    // Quantile placement: each cell gets its share rounded up or down (frames are 5 cm apart, so a
    // quantile near a boundary can snap across it).
    EXPECT_NEAR(got, expected, 1.5) << "cell " << c.s_begin << " .. " << c.s_end << " v " << c.area_mid;
  }
}

}  // namespace
}  // namespace plenopath
