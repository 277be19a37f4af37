#pragma once
// Online sampling of a CG path (issue 23; the seed paper samples complex scenes online instead of rendering
// every frame): the whole path is rendered first as coarse depth only, the depth sampler (depth_sampler.h)
// chooses the keyframes from it, and only those are rendered at full size. The depth sampler reads depth at
// most DepthSamplingOptions::max_depth_width wide (256) whatever was rendered, so a coarse pass at that width
// loses it nothing, and costs a few per cent of a full frame (no colour, no antialiasing, 1/64 of the
// pixels of a 2048-wide frame).
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"
#include "processing/sampling/depth_sampler.h"
#include "processing/sampling/sampling_loss.h"
#include "processing/util/progress.h"

namespace plenopath {

struct OnlineSamplingOptions {
  int coarse_width = 256;  // width of the depth-only pass (at least the sampler's max_depth_width is useless)
  DepthSamplingOptions depth;
  // > 0: render at full size the fewest keyframes whose geometric loss (mean 1 - IoU of each frame's
  // eye-level envelope, from the coarse depth, with its stand-in's) is at most this, the paper's "until the
  // loss target is met"; a budget count then caps them (the ratio is not used). 0: the budget alone.
  double loss_target = 0.0;
  void check() const;  // throws Error naming the bad field
};

struct OnlineSamplingResult {
  Keyframes keyframes;          // indices are path frame indices (PathFrame::index)
  int coarse_frames = 0;        // frames rendered as coarse depth (all of the path)
  int full_frames = 0;          // frames rendered at full size (the keyframes)
  GeometricLoss loss;           // of the keyframes, on the coarse depth's eye-level envelopes
  bool loss_target_met = true;  // false when the budget ran out before the loss target was met
  int samplings = 0;            // keyframe sets tried (one without a loss target)
};

// Renders the poses' depth (CV_32F metres, 0 = no hit) `width` wide, handing each to `deliver` in order.
using CoarseDepthRenderer = std::function<void(
    const std::vector<PathFrame>& poses, int width,
    const std::function<void(int position, const cv::Mat& depth)>& deliver, Progress& progress)>;
// Renders the keyframes' poses at full size (the caller keeps or writes what it renders).
using FullFrameRenderer = std::function<void(const std::vector<PathFrame>& poses, Progress& progress)>;

// `parameters`: the depth sampler's budget (count or ratio) and rule, as `sample` takes them. Throws Error or
// Cancelled (the renderers' too).
OnlineSamplingResult sample_online(const CameraPath& path, const SamplingParameters& parameters,
                                   const CoarseDepthRenderer& render_coarse_depth,
                                   const FullFrameRenderer& render_full,
                                   const OnlineSamplingOptions& options = {},
                                   Progress& progress = null_progress());

}  // namespace plenopath
