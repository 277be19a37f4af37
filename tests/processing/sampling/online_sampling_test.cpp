// Online sampling: the keyframes chosen from a coarse depth-only pass must be as many as, and lose no more
// than, those chosen from a full render of every frame, while only they are rendered at full size. Depth
// from the synthetic camera; the loss is judged on the plan's exact envelopes (CGAL), which neither sampler
// saw.
#include "processing/sampling/online_sampling.h"

#include <gtest/gtest.h>

#include "model/error.h"
#include "processing/visibility/visibility.h"
#include "rig/synthetic_camera.h"
#include "sampling_test_util.h"

namespace plenopath {
namespace {

TEST(OnlineSampling, KeepsWhatAFullRenderKeepsRenderingOnlyTheKeyframes) {
  const FloorPlan plan = sampling_test::three_rooms();
  const SyntheticScene scene = build_synthetic_scene(plan);
  const CameraPath path = sampling_test::straight_path(114, 0.15, 0.5, 2.0);  // x = 0.5 .. 17.45
  SamplingParameters parameters;
  parameters.method = SamplingMethod::kDepth;
  parameters.ratio = 10.0;
  // The judge: each frame's exact envelope from the plan (CGAL), neither sampler's own input.
  const PathEnvelopes truth = compute_path_envelopes(VisibilityIndex(plan), path, 1);
  RenderOptions full;
  full.width = 1024;
  full.height = 512;
  full.threads = 1;
  // The reference: every frame at full size.
  PathEnvelopes full_envelopes;
  const std::vector<DepthVolume> volumes = depth_volumes_along_path(
      path, [&](int index) { return render_panorama(scene, *path.find_frame(index), full).depth; }, {},
      null_progress(), &full_envelopes);
  const Keyframes reference = sample_by_depth(path, volumes, parameters, {}, {}, &full_envelopes);

  std::vector<int> rendered_full;
  int coarse_width_seen = 0;
  const OnlineSamplingResult online = sample_online(
      path, parameters,
      [&](const std::vector<PathFrame>& poses, int width,
          const std::function<void(int, const cv::Mat&)>& deliver, Progress&) {
        coarse_width_seen = width;
        RenderOptions coarse = full;
        coarse.width = width;
        coarse.height = width / 2;
        for (std::size_t k = 0; k < poses.size(); ++k)
          deliver(static_cast<int>(k), render_panorama(scene, poses[k], coarse).depth);
      },
      [&](const std::vector<PathFrame>& poses, Progress&) {
        for (const PathFrame& pose : poses) rendered_full.push_back(pose.index);
      });
  const GeometricLoss loss_full = geometric_loss(path, reference, truth, 1);
  const GeometricLoss loss_online = geometric_loss(path, online.keyframes, truth, 1);
  std::printf(
      "online sampling: %zu keyframes (full render %zu), %d of %zu frames at full size; loss %.4f "
      "(full render %.4f)\n",
      online.keyframes.indices.size(), reference.indices.size(), online.full_frames, path.size(),
      loss_online.mean, loss_full.mean);
  EXPECT_EQ(coarse_width_seen, 256);
  EXPECT_EQ(online.coarse_frames, static_cast<int>(path.size()));
  EXPECT_EQ(online.keyframes.indices.size(), reference.indices.size());
  EXPECT_EQ(rendered_full, online.keyframes.indices);  // exactly the keyframes, nothing else
  EXPECT_LE(online.full_frames, static_cast<int>(path.size()) / 4);
  // Seen over paths at y = 1.7, 2.0, 2.4 and ratios 8-20: 0.96 to 1.04 times the full render's loss. (Judged
  // on the full render's own envelopes instead, which its loss refinement optimised, it looks 1.01-1.2.)
  EXPECT_LE(loss_online.mean, 1.1 * loss_full.mean);
}

TEST(OnlineSampling, ARendererThatLeavesOutAFrameIsAnError) {
  const CameraPath path = sampling_test::straight_path(10, 0.2);
  SamplingParameters parameters;
  parameters.method = SamplingMethod::kDepth;
  parameters.count = 3;
  auto skip_last = [](const std::vector<PathFrame>& poses, int width,
                      const std::function<void(int, const cv::Mat&)>& deliver, Progress&) {
    for (std::size_t k = 0; k + 1 < poses.size(); ++k)
      deliver(static_cast<int>(k), cv::Mat(width / 2, width, CV_32F, cv::Scalar(2.0f)));
  };
  EXPECT_THROW(sample_online(path, parameters, skip_last, [](const std::vector<PathFrame>&, Progress&) {}),
               Error);
  OnlineSamplingOptions bad;
  bad.coarse_width = 7;
  EXPECT_THROW(bad.check(), Error);
}

}  // namespace
}  // namespace plenopath
