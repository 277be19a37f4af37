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
  SamplingMethod method;
  VisibilityRule rule;
};
const std::vector<Method> kMethods = {{SamplingMethod::kUniform, VisibilityRule::expected_loss},
                                      {SamplingMethod::kVisibility, VisibilityRule::expected_loss},
                                      {SamplingMethod::kVisibility, VisibilityRule::cell_rule},
                                      {SamplingMethod::kDepth, VisibilityRule::expected_loss}};

std::string label(const Method& m) {
  return std::string(to_string(m.method)) +
         (m.method == SamplingMethod::kVisibility ? std::string("/") + to_string(m.rule) : "");
}

SamplingParameters parameters_of(const Method& m) {
  SamplingParameters p;
  p.method = m.method;
  p.rule = m.rule;
  return p;
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
    for (int count : {2, 3, 5, 17, 40, 100, 341}) {
      SamplingParameters p = parameters_of(m);
      p.count = count;
      const Keyframes k = sample_keyframes(f.inputs, p);
      EXPECT_EQ(static_cast<int>(k.indices.size()), count) << label(m) << " count " << count;
      expect_valid(f.path, k, label(m));
      EXPECT_EQ(k.parameters.method, m.method);
      EXPECT_EQ(k.parameters.rule, m.rule);
    }
    for (double ratio : {2.0, 7.5, 50.0, 1000.0}) {
      SamplingParameters p = parameters_of(m);
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
    SamplingParameters p = parameters_of(m);
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
  p.method = SamplingMethod::kUniform;
  p.count = 5;  // 2 ends + 4 pinned > 5
  EXPECT_THROW(sample_keyframes(f.inputs, p, pinned), Error);
  EXPECT_THROW(sample_keyframes(f.inputs, p, {9999}), Error);
}

TEST(KeyframeSampler, SpacingIsHonoured) {
  Fixture& f = fixture();
  const std::vector<double> s = f.path.arc_lengths();
  for (const Method& m : kMethods) {
    SamplingParameters p = parameters_of(m);
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
  p.method = SamplingMethod::kUniform;
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
  p.method = SamplingMethod::kVisibility;
  try {
    sample_keyframes(in, p);
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("visibility"), std::string::npos) << e.what();
  }
  p.rule = VisibilityRule::cell_rule;
  EXPECT_THROW(sample_keyframes(in, p), Error);
  p.method = SamplingMethod::kDepth;
  EXPECT_THROW(sample_keyframes(in, p), Error);
  EXPECT_THROW(enum_from_string<SamplingMethod>("bogus"), Error);
  EXPECT_THROW(enum_from_string<VisibilityRule>("bogus"), Error);
}

// Every prefix of the progressive order: a valid sampling of its size (ends, sorted unique), and its
// geometric loss close to what the same method gives when asked for that size directly.
TEST(KeyframeSampler, EveryPrefixIsAGoodSampling) {
  Fixture& f = fixture();
  for (const Method& m : kMethods) {
    SamplingParameters p = parameters_of(m);
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

// The keyframes say how they were made: method, rule and the settings the sampler's options held (the
// values set here, not the defaults), and whether the loss refinement moved them.
TEST(KeyframeSampler, RecordsHowTheKeyframesWereMade) {
  Fixture& f = fixture();
  SamplingInputs in = f.inputs;
  in.raster = nullptr;
  in.visibility.probe_spacing_m = 0.5;
  in.visibility.loss_power = 0.75;
  in.visibility.density_floor = 0.2;
  in.visibility.refine_sweeps = 3;
  in.visibility.raster_cell_m = 0.1;
  in.visibility.cells.transition_window_m = 2.0;
  in.visibility.cells.min_size = 0.05;
  SamplingParameters p;
  p.method = SamplingMethod::kVisibility;
  p.rule = VisibilityRule::expected_loss;
  p.count = 12;
  Keyframes k = sample_keyframes(in, p);
  EXPECT_EQ(k.parameters, p);
  EXPECT_EQ(k.sampler.expected_loss.probe_spacing_m, 0.5);
  EXPECT_EQ(k.sampler.expected_loss.loss_power, 0.75);
  EXPECT_EQ(k.sampler.expected_loss.density_floor, 0.2);
  EXPECT_TRUE(k.sampler.refinement.applied);
  EXPECT_EQ(k.sampler.refinement.sweeps, 3);
  EXPECT_EQ(k.sampler.refinement.raster_cell_m, 0.1);  // the three rooms are small: not grown

  p.rule = VisibilityRule::cell_rule;
  p.exponent = 2.0;
  k = sample_keyframes(in, p);
  EXPECT_EQ(k.parameters, p);
  EXPECT_EQ(k.sampler.cell_rule.transition_window_m, 2.0);
  EXPECT_EQ(k.sampler.cell_rule.min_size, 0.05);
  EXPECT_FALSE(k.sampler.refinement.applied) << "the cell rule places keyframes unrefined";
  EXPECT_EQ(k.sampler.refinement.sweeps, LossRefinementSettings{}.sweeps) << "not used";
  EXPECT_EQ(k.sampler.expected_loss.probe_spacing_m, ExpectedLossSettings{}.probe_spacing_m) << "not used";

  in.depth.changes.log_ratio_threshold = 0.4;
  in.depth.changes.use_mean_range = true;
  in.depth.changes.min_coverage = 0.3;
  in.depth.max_depth_width = 128;
  in.depth_envelopes = nullptr;  // no eye-level envelopes: nothing to refine on
  p.method = SamplingMethod::kDepth;
  k = sample_keyframes(in, p);
  EXPECT_EQ(k.parameters.method, SamplingMethod::kDepth);
  EXPECT_EQ(k.sampler.depth_changes.log_ratio_threshold, 0.4);
  EXPECT_TRUE(k.sampler.depth_changes.use_mean_range);
  EXPECT_EQ(k.sampler.depth_changes.min_coverage, 0.3);
  EXPECT_EQ(k.sampler.depth_changes.max_depth_width, 128);
  EXPECT_FALSE(k.sampler.refinement.applied);
  in.depth_envelopes = &f.envelopes;  // stand-ins for the eye-level envelopes
  k = sample_keyframes(in, p);
  EXPECT_TRUE(k.sampler.refinement.applied);

  p.method = SamplingMethod::kUniform;
  EXPECT_EQ(sample_keyframes(in, p).sampler, SamplerSettings{});
}

// A project file written before the settings were recorded reads them as the samplers' defaults: the
// model's defaults must be the processing options' defaults.
TEST(KeyframeSampler, RecordedDefaultsAreTheSamplersDefaults) {
  const SamplerSettings s;
  const VisibilitySamplingOptions v;
  EXPECT_EQ(s.expected_loss.probe_spacing_m, v.probe_spacing_m);
  EXPECT_EQ(s.expected_loss.loss_power, v.loss_power);
  EXPECT_EQ(s.expected_loss.density_floor, v.density_floor);
  EXPECT_EQ(s.refinement.sweeps, v.refine_sweeps);
  EXPECT_EQ(s.refinement.raster_cell_m, v.raster_cell_m);
  EXPECT_EQ(s.cell_rule.transition_window_m, v.cells.transition_window_m);
  EXPECT_EQ(s.cell_rule.min_size, v.cells.min_size);
  const DepthSamplingOptions d;
  EXPECT_EQ(s.depth_changes.log_ratio_threshold, d.changes.log_ratio_threshold);
  EXPECT_EQ(s.depth_changes.use_mean_range, d.changes.use_mean_range);
  EXPECT_EQ(s.depth_changes.min_coverage, d.changes.min_coverage);
  EXPECT_EQ(s.depth_changes.max_depth_width, d.max_depth_width);
  EXPECT_EQ(s.refinement.sweeps, d.refine_sweeps);
  EXPECT_EQ(s.refinement.raster_cell_m, d.raster_cell_m);
  EXPECT_EQ(s.cell_rule.transition_window_m, d.cells.transition_window_m);
  EXPECT_EQ(s.cell_rule.min_size, d.cells.min_size);
  EXPECT_EQ(SamplingParameters{}.rule, VisibilityRule::expected_loss);
}

// The new uniform sampler agrees with the baseline where both apply (no pins): same frames.
TEST(KeyframeSampler, UniformMatchesTheBaseline) {
  const CameraPath path = straight_path(101, 0.1);
  SamplingInputs in;
  in.path = &path;
  SamplingParameters p;
  p.method = SamplingMethod::kUniform;
  p.count = 11;
  const Keyframes k = sample_keyframes(in, p);
  EXPECT_EQ(k.indices, (std::vector<int>{0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100}));
  // Coarse to fine: ends, then the middle, then quarters.
  const std::vector<int> order = k.progressive_order();
  EXPECT_EQ(order[0], 0);
  EXPECT_EQ(order[1], 100);
  EXPECT_EQ(order[2], 50);
}

// Still panoramas: every still a keyframe, pinned, ranked coarse to fine (worked by hand for five stills:
// the ends 0 and 4 first, then the middle 2, then 1 and 3).
TEST(EveryFrameAKeyframe, StillsAreAllKeptAndRankedCoarseToFine) {
  CameraPath path;
  for (int i : {10, 11, 12, 13, 14}) {
    PathFrame f;
    f.index = i;
    f.x = i;
    path.frames.push_back(f);
  }
  const Keyframes k = every_frame_a_keyframe(path);
  EXPECT_EQ(k.indices, (std::vector<int>{10, 11, 12, 13, 14}));
  EXPECT_EQ(k.pinned, k.indices);
  EXPECT_EQ(k.rank, (std::vector<int>{0, 3, 2, 4, 1}));
  EXPECT_EQ(k.progressive_order(), (std::vector<int>{10, 14, 12, 11, 13}));
  EXPECT_TRUE(every_frame_a_keyframe(CameraPath{}).empty());
}

}  // namespace
}  // namespace plenopath
