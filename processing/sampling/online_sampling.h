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
#include "processing/util/progress.h"

namespace plenopath {

struct OnlineSamplingOptions {
  int coarse_width = 256;  // width of the depth-only pass (at least the sampler's max_depth_width is useless)
  DepthSamplingOptions depth;
  void check() const;  // throws Error naming the bad field
};

struct OnlineSamplingResult {
  Keyframes keyframes;    // indices are path frame indices (PathFrame::index)
  int coarse_frames = 0;  // frames rendered as coarse depth (all of the path)
  int full_frames = 0;    // frames rendered at full size (the keyframes)
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
