#include "processing/sampling/uniform_sampling.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "model/error.h"

namespace plenopath {
namespace {

// A straight path along +X: frame i at x = spacing(i).
CameraPath straight_path(int n, double step) {
  CameraPath path;
  for (int i = 0; i < n; ++i) path.frames.push_back({i, "", i * step, 0.0, 0.0, 1.0, kFrameOk, ""});
  return path;
}

TEST(UniformSampling, BudgetFromCountOrRatio) {
  SamplingParameters p;
  p.count = 0;
  p.ratio = 10.0;
  EXPECT_EQ(keyframe_budget(p, 101), 10);  // round(10.1)
  p.ratio = 1000.0;
  EXPECT_EQ(keyframe_budget(p, 101), 2);  // never fewer than the two ends
  p.count = 500;
  EXPECT_EQ(keyframe_budget(p, 101), 101);  // never more than the frames
  EXPECT_EQ(keyframe_budget(p, 0), 0);
  p.count = -1;
  EXPECT_THROW(keyframe_budget(p, 10), Error);
  p.count = 0;
  p.ratio = 0.0;
  EXPECT_THROW(keyframe_budget(p, 10), Error);
}

TEST(UniformSampling, EvenlySpacedFramesOnAnEvenPath) {
  SamplingParameters p;
  p.count = 11;
  const Keyframes k = sample_uniform_by_arc_length(straight_path(101, 0.1), p);
  const std::vector<int> expected{0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100};
  EXPECT_EQ(k.indices, expected);
  EXPECT_EQ(k.parameters.method, SamplingMethod::kUniform);
  // Ranks: the two ends first, then the middle (frame 50 sits at position 5).
  ASSERT_EQ(k.rank.size(), 11u);
  EXPECT_EQ(k.rank[0], 0);
  EXPECT_EQ(k.rank[10], 1);
  EXPECT_EQ(k.rank[5], 2);
  std::vector<int> sorted = k.rank;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < 11; ++i) EXPECT_EQ(sorted[i], i);
}

TEST(UniformSampling, SpacingFollowsArcLengthNotFrameNumber) {
  // Frames 0..10 crawl 0.01 m apart (the trolley was slow), frames 10..20 are 1 m apart.
  CameraPath path;
  double x = 0.0;
  for (int i = 0; i <= 20; ++i) {
    path.frames.push_back({i, "", x, 0.0, 0.0, 1.0, kFrameOk, ""});
    x += i < 10 ? 0.01 : 1.0;
  }
  // Length 0.1 + 10 = 10.1 m; 3 keyframes at 0, 5.05 m, 10.1 m -> frames 0, 15 (s = 5.1), 20.
  SamplingParameters p;
  p.count = 3;
  const Keyframes k = sample_uniform_by_arc_length(path, p);
  EXPECT_EQ(k.indices, (std::vector<int>{0, 15, 20}));
}

TEST(UniformSampling, PinnedFramesAreKeptAndIndicesAreCaptureIndices) {
  CameraPath path = straight_path(11, 1.0);
  for (auto& f : path.frames) f.index = 100 + 2 * f.index;  // capture indices 100, 102, ..., 120
  SamplingParameters p;
  p.count = 2;
  const Keyframes k = sample_uniform_by_arc_length(path, p, {106, 999});
  EXPECT_EQ(k.indices, (std::vector<int>{100, 106, 120}));  // 999 is not a frame of the path
  EXPECT_EQ(k.pinned, (std::vector<int>{106, 999}));
}

TEST(UniformSampling, StatisticsByHand) {
  const CameraPath path = straight_path(11, 1.0);  // 10 m
  Keyframes k;
  k.indices = {0, 2, 10};
  const SamplingStatistics s = sampling_statistics(path, k);
  EXPECT_EQ(s.kept, 3);
  EXPECT_EQ(s.total, 11);
  EXPECT_DOUBLE_EQ(s.ratio, 11.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.max_gap_m, 8.0);
  EXPECT_DOUBLE_EQ(s.mean_gap_m, 5.0);
}

TEST(UniformSampling, DegeneratePaths) {
  SamplingParameters p;
  p.count = 5;
  EXPECT_TRUE(sample_uniform_by_arc_length(CameraPath{}, p).indices.empty());
  // The camera never moved: spread over frame numbers instead.
  const Keyframes k = sample_uniform_by_arc_length(straight_path(9, 0.0), p);
  EXPECT_EQ(k.indices, (std::vector<int>{0, 2, 4, 6, 8}));
}

}  // namespace
}  // namespace plenopath
