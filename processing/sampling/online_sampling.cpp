#include "processing/sampling/online_sampling.h"

#include <algorithm>
#include <tuple>
#include <utility>

#include "model/error.h"
#include "model/option_check.h"

namespace plenopath {

void OnlineSamplingOptions::check() const {
  require_option(coarse_width >= 16 && coarse_width % 2 == 0, "OnlineSamplingOptions.coarse_width",
                 "must be even and >= 16", coarse_width);
  require_option(loss_target >= 0.0 && loss_target < 1.0, "OnlineSamplingOptions.loss_target",
                 "must be in [0, 1)", loss_target);
  depth.check();
}

OnlineSamplingResult sample_online(const CameraPath& path, const SamplingParameters& parameters,
                                   const CoarseDepthRenderer& render_coarse_depth,
                                   const FullFrameRenderer& render_full, const OnlineSamplingOptions& options,
                                   Progress& progress) {
  options.check();
  if (path.empty()) throw Error("online sampling: the path has no frames");
  OnlineSamplingResult result;
  // 1. Coarse depth of every frame, summarised as it comes (a long path's depth maps are not kept).
  std::vector<DepthVolume> volumes(path.size());
  PathEnvelopes envelopes;
  envelopes.frames.assign(path.size(), Envelope{});
  std::vector<char> seen(path.size(), 0);
  {
    SubProgress coarse_progress(progress, 0.0, 0.3, "coarse depth");
    render_coarse_depth(
        path.frames, options.coarse_width,
        [&](int k, const cv::Mat& depth) {
          if (k < 0 || k >= static_cast<int>(path.size()) || depth.empty())
            throw Error("online sampling: the renderer gave no depth for frame " + std::to_string(k));
          const std::size_t i = static_cast<std::size_t>(k);
          volumes[i] = summarise_depth(depth, path.frames[i], options.depth, &envelopes.frames[i]);
          seen[i] = 1;
          ++result.coarse_frames;
        },
        coarse_progress);
  }
  for (std::size_t i = 0; i < seen.size(); ++i)
    if (!seen[i])
      throw Error("online sampling: the renderer left out frame " + std::to_string(path.frames[i].index));
  // 2. The keyframes, as `sample --method depth` would choose them from a full render: for the budget, or
  // the fewest that meet the loss target (bisection on the count: the loss falls as keyframes are added).
  progress.checkpoint(0.3, "sampling");
  const auto sample_count = [&](int count) {
    progress.throw_if_cancelled();
    SamplingParameters p = parameters;
    if (count > 0) p.count = count;
    ++result.samplings;
    Keyframes keyframes = sample_by_depth(path, volumes, p, {}, options.depth, &envelopes);
    GeometricLoss loss = geometric_loss(path, keyframes, envelopes);
    return std::make_pair(std::move(keyframes), loss);
  };
  if (options.loss_target <= 0.0) {
    std::tie(result.keyframes, result.loss) = sample_count(0);
  } else {
    const int frames = static_cast<int>(path.size());
    int high = parameters.count > 0 ? std::min(parameters.count, frames) : frames;
    std::tie(result.keyframes, result.loss) = sample_count(high);
    result.loss_target_met = result.loss.mean <= options.loss_target;
    int low = 1;
    while (result.loss_target_met && low < high) {
      const int middle = low + (high - low) / 2;
      auto [keyframes, loss] = sample_count(middle);
      progress.report(0.3 + 0.05 * (1.0 - double(high - low) / frames),
                      "sampling: " + std::to_string(middle) + " keyframes lose " + std::to_string(loss.mean));
      if (loss.mean <= options.loss_target) {
        high = middle;
        result.keyframes = std::move(keyframes);
        result.loss = loss;
      } else {
        low = middle + 1;
      }
    }
  }
  // 3. Full frames of the keyframes only.
  std::vector<PathFrame> keyframe_poses;
  for (int index : result.keyframes.indices) {
    const PathFrame* frame = path.find_frame(index);
    if (!frame) throw Error("online sampling: keyframe " + std::to_string(index) + " is not on the path");
    keyframe_poses.push_back(*frame);
  }
  SubProgress full_progress(progress, 0.35, 1.0, "full frames");
  render_full(keyframe_poses, full_progress);
  result.full_frames = static_cast<int>(keyframe_poses.size());
  progress.report(1.0);
  return result;
}

}  // namespace plenopath
