// Budgets met exactly, pinned frames kept, spacing honoured, and every prefix of the progressive order a
// valid sampling of its size whose loss is close to a direct sampling of that size - for every method.
#include "processing/sampling/keyframe_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "model/error.h"
#include "processing/sampling/sampling_loss.h"
#include "processing/sampling/uniform_sampling.h"
#include "sampling_test_util.h"

namespace plenopath {
namespace {

using sampling_test::straight_path;

struct Fixture {
  FloorPlan plan = sampling_test::three_rooms();
  CameraPath path = sampling_test::three_rooms_path();
  VisibilityIndex index{plan};
  VisibilityCells cells = index.cells_along_path(path);
  PathEnvelopes envelopes = compute_path_envelopes(index, path);
  // Depth volumes by hand: each room a different box volume (the middle one bigger).
  std::vector<DepthVolume> volumes;
  SamplingInputs inputs;

  Fixture() {
    for (const PathFrame& f : path.frames) {
      DepthVolume v;
      v.star_volume = (f.x > 6.0 && f.x < 12.0) ? 90.0 : 40.0;
      v.mean_range = 3.0;
      v.covered_solid_angle = 4 * M_PI;
      v.valid_pixels = 100;
      volumes.push_back(v);
    }
    inputs.path = &path;
    inputs.index = &index;
    inputs.cells = &cells;
    inputs.depth_volumes = &volumes;
    inputs.envelopes = &envelopes;
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

struct Method {
  std::string name;
  VisibilityRule rule;
};
const std::vector<Method> kMethods = {{"uniform", VisibilityRule::expected_loss},
                                      {"visibility", VisibilityRule::expected_loss},
                                      {"visibility", VisibilityRule::cell_rule},
                                      {"depth", VisibilityRule::expected_loss}};

std::string label(const Method& m) {
  return m.name + (m.name == "visibility" ? std::string("/") + to_string(m.rule) : "");
}

void expect_valid(const CameraPath& path, const Keyframes& k, const std::string& what) {
  ASSERT_FALSE(k.indices.empty()) << what;
  EXPECT_TRUE(std::is_sorted(k.indices.begin(), k.indices.end())) << what;
  EXPECT_EQ(std::set<int>(k.indices.begin(), k.indices.end()).size(), k.indices.size()) << what;
  EXPECT_EQ(k.indices.front(), path.frames.front().index) << what;
  EXPECT_EQ(k.indices.back(), path.frames.back().index) << what;
  ASSERT_EQ(k.rank.size(), k.indices.size()) << what;
  std::vector<int> ranks = k.rank;
  std::sort(ranks.begin(), ranks.end());
  for (std::size_t i = 0; i < ranks.size(); ++i) ASSERT_EQ(ranks[i], static_cast<int>(i)) << what;
}

TEST(KeyframeSampler, BudgetsAreMetExactly) {
  Fixture& f = fixture();
  for (const Method& m : kMethods) {
    f.inputs.visibility.rule = m.rule;
    for (int count : {2, 3, 5, 17, 40, 100, 341}) {
      SamplingParameters p;
      p.method = m.name;
      p.count = count;
      const Keyframes k = sample_keyframes(f.inputs, p);
      EXPECT_EQ(static_cast<int>(k.indices.size()), count) << label(m) << " count " << count;
      expect_valid(f.path, k, label(m));
      EXPECT_EQ(k.parameters.method, m.name);
    }
    for (double ratio : {2.0, 7.5, 50.0, 1000.0}) {
      SamplingParameters p;
      p.method = m.name;
      p.ratio = ratio;
      const Keyframes k = sample_keyframes(f.inputs, p);
      EXPECT_EQ(static_cast<int>(k.indices.size()), keyframe_budget(p, 341))
          << label(m) << " ratio " << ratio;
    }
  }
}

TEST(KeyframeSampler, PinnedFramesAreKeptWithinTheBudget) {
  Fixture& f = fixture();
  const std::vector<int> pinned = {3, 4, 170, 333};
  for (const Method& m : kMethods) {
    f.inputs.visibility.rule = m.rule;
    SamplingParameters p;
    p.method = m.name;
    p.count = 12;
    const Keyframes k = sample_keyframes(f.inputs, p, pinned);
    EXPECT_EQ(k.indices.size(), 12u) << label(m);
    for (int i : pinned)
      EXPECT_TRUE(std::count(k.indices.begin(), k.indices.end(), i)) << label(m) << " lost pinned " << i;
    EXPECT_EQ(k.pinned, pinned);
    // Pinned frames are ranked right after the ends.
    const std::vector<int> order = k.progressive_order();
    EXPECT_EQ(std::set<int>(order.begin() + 2, order.begin() + 6),
              std::set<int>(pinned.begin(), pinned.end()))
        << label(m);
    expect_valid(f.path, k, label(m));
  }
  SamplingParameters p;
  p.method = "uniform";
  p.count = 5;  // 2 ends + 4 pinned > 5
  EXPECT_THROW(sample_keyframes(f.inputs, p, pinned), Error);
  EXPECT_THROW(sample_keyframes(f.inputs, p, {9999}), Error);
}

TEST(KeyframeSampler, SpacingIsHonoured) {
  Fixture& f = fixture();
  const std::vector<double> s = f.path.arc_lengths();
  for (const Method& m : kMethods) {
    f.inputs.visibility.rule = m.rule;
    SamplingParameters p;
    p.method = m.name;
    p.count = 20;
    p.min_spacing_m = 0.6;
    p.max_spacing_m = 1.2;
    const Keyframes k = sample_keyframes(f.inputs, p);
    ASSERT_EQ(k.indices.size(), 20u) << label(m);
    for (std::size_t j = 1; j < k.indices.size(); ++j) {
      const double gap = s[k.indices[j]] - s[k.indices[j - 1]];
      EXPECT_GE(gap, 0.6 - 1e-9) << label(m);
      EXPECT_LE(gap, 1.2 + 1e-9) << label(m);
    }
  }
  SamplingParameters p;
  p.method = "uniform";
  p.count = 5;
  p.max_spacing_m = 1.0;  // 17 m needs at least 18 keyframes
  EXPECT_THROW(sample_keyframes(f.inputs, p), Error);
  p.count = 100;
  p.max_spacing_m = 0.0;
  p.min_spacing_m = 0.5;  // at most 35 keyframes fit
  EXPECT_THROW(sample_keyframes(f.inputs, p), Error);
  p.min_spacing_m = 2.0;
  p.max_spacing_m = 1.0;
  EXPECT_THROW(sample_keyframes(f.inputs, p), Error);
}

TEST(KeyframeSampler, MissingInputsAreReported) {
  CameraPath path = straight_path(50, 0.1);
  SamplingInputs in;
  in.path = &path;
  SamplingParameters p;
  p.method = "visibility";
  try {
    sample_keyframes(in, p);
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("visibility"), std::string::npos) << e.what();
  }
  in.visibility.rule = VisibilityRule::cell_rule;
  EXPECT_THROW(sample_keyframes(in, p), Error);
  p.method = "depth";
  EXPECT_THROW(sample_keyframes(in, p), Error);
  p.method = "bogus";
  EXPECT_THROW(sample_keyframes(in, p), Error);
  EXPECT_THROW(visibility_rule_from_string("bogus"), Error);
}

// Every prefix of the progressive order: a valid sampling of its size (ends, sorted unique), and its
// geometric loss close to what the same method gives when asked for that size directly.
TEST(KeyframeSampler, EveryPrefixIsAGoodSampling) {
  Fixture& f = fixture();
  for (const Method& m : kMethods) {
    f.inputs.visibility.rule = m.rule;
    SamplingParameters p;
    p.method = m.name;
    p.count = 34;
    const Keyframes full = sample_keyframes(f.inputs, p);
    const std::vector<int> order = full.progressive_order();
    ASSERT_EQ(order.size(), 34u);
    for (int size : {2, 3, 4, 6, 9, 13, 20, 34}) {
      Keyframes prefix;
      prefix.indices.assign(order.begin(), order.begin() + size);
      std::sort(prefix.indices.begin(), prefix.indices.end());
      EXPECT_EQ(prefix.indices.front(), 0) << label(m) << " prefix " << size;
      EXPECT_EQ(prefix.indices.back(), 340) << label(m) << " prefix " << size;
      EXPECT_EQ(std::set<int>(prefix.indices.begin(), prefix.indices.end()).size(),
                static_cast<std::size_t>(size));
      p.count = size;
      const Keyframes direct = sample_keyframes(f.inputs, p);
      const double prefix_loss = geometric_loss(f.path, prefix, f.envelopes).mean;
      const double direct_loss = geometric_loss(f.path, direct, f.envelopes).mean;
      // Close: within 35 % or 0.03 of the direct sampling (a prefix cannot move its keyframes).
      EXPECT_LE(prefix_loss, std::max(1.35 * direct_loss, direct_loss + 0.03))
          << label(m) << " prefix " << size << ": " << prefix_loss << " vs direct " << direct_loss;
    }
  }
}

// The new uniform sampler agrees with the baseline where both apply (no pins): same frames.
TEST(KeyframeSampler, UniformMatchesTheBaseline) {
  const CameraPath path = straight_path(101, 0.1);
  SamplingInputs in;
  in.path = &path;
  SamplingParameters p;
  p.method = "uniform";
  p.count = 11;
  const Keyframes k = sample_keyframes(in, p);
  EXPECT_EQ(k.indices, (std::vector<int>{0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100}));
  // Coarse to fine: ends, then the middle, then quarters.
  const std::vector<int> order = k.progressive_order();
  EXPECT_EQ(order[0], 0);
  EXPECT_EQ(order[1], 100);
  EXPECT_EQ(order[2], 50);
}

}  // namespace
}  // namespace plenopath
