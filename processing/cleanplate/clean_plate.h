#pragma once
// Clean plates (issue 24): a keyframe without the people who walked through it. The paper's stated next
// step ("removing of the moving parts ... to get clean static images"), done here by the scene's static
// geometry rather than by optical flow alone:
//   1. Warp: neighbouring frames along the path (both directions, spread over baselines in [min, max]) are
//   warped
//      onto the keyframe by the recovered poses and the keyframe's static depth (metres along each ray: a
//      depth map, or the plan's walls, floor and ceiling): the keyframe pixel's 3-D point is looked up in
//      the neighbour (bilinear, the seam wrapped). Where the neighbour's own static depth says the point
//      is hidden there (a wall between), its sample is dropped.
//   2. Consensus: per pixel and channel, the median of the warped samples (the keyframe's own included).
//   3. Moving regions: keyframe pixels that disagree with the consensus of the others by more than
//      `disagreement` grey levels (the best match within one pixel: a sharp edge warped half a pixel off is
//      no mover; nor is a jump of the static depth), in blobs of at least `min_region_px` pixels, closed and
//      grown by `mask_dilation_px`; they take the median of the other frames, elsewhere the keyframe stays as
//      it was (no blur from the warp where nothing moved).
// What no neighbour saw (support below min_support) stays as the keyframe has it and is reported.
#include <functional>
#include <opencv2/core.hpp>

#include "model/camera_path.h"
#include "processing/util/progress.h"

namespace plenopath {

struct CleanPlateOptions {
  int neighbours = 10;          // about this many frames each side, spread over the baselines
  double min_baseline_m = 0.2;  // nearer neighbours see a person at nearly the same place: skipped
  double max_baseline_m = 4.0;  // farther ones warp badly where the depth is approximate: skipped
  // A neighbour's sample is dropped when its own static depth at the looked-up pixel is shorter than the
  // point's distance by more than this share (the point is hidden from it).
  double occlusion_tolerance = 0.05;
  double disagreement = 28.0;       // grey levels (max over channels) between the keyframe and the consensus
  double weak_disagreement = 10.0;  // a mover grows over connected pixels that disagree this much
  // Pixels where the static depth jumps (log-depth Sobel above this) are no seeds of a moving region: a
  // small pose error moves a depth edge.
  double depth_edge = 0.6;
  int min_region_px = 40;    // smaller disagreeing blobs are noise or texture aliasing: left alone
  int mask_closing_px = 6;   // holes in a moving region up to about this wide are closed
  int mask_dilation_px = 3;  // moving regions grown by this (soft edges of people, motion blur)
  int min_support = 3;       // warped samples a pixel needs to be replaced
  void check() const;        // throws Error naming the bad field
};

struct CleanPlate {
  cv::Mat image;        // CV_8UC3, the keyframe with its moving regions replaced
  cv::Mat moving_mask;  // CV_8U, 255 where the keyframe was replaced
  cv::Mat support;      // CV_8U, warped samples per pixel (the keyframe's own not counted)
  cv::Mat consensus;    // CV_8UC3, the median of the warped neighbours (the keyframe where none saw it)
  std::vector<int> neighbours_used;  // path positions
  double moving_share = 0.0;         // of the image's pixels
  double unsupported_share = 0.0;    // moving pixels left as they were (no neighbour saw the scene there)
};

// `frame(position)`: the BGR panorama of path frame `position` (CV_8UC3, all the same size);
// `static_depth(position)`: its static depth (CV_32F metres along the ray, 0 = unknown, same size), or an
// empty Mat when unknown (the neighbour is then not checked for occlusion). The keyframe needs a depth.
// Throws Error on a position outside the path, sizes that disagree, or a keyframe without depth.
// Progress: once per neighbour ("warping frame 12"); a cancel ends it with Cancelled.
CleanPlate clean_plate(const CameraPath& path, int keyframe_position,
                       const std::function<cv::Mat(int position)>& frame,
                       const std::function<cv::Mat(int position)>& static_depth,
                       const CleanPlateOptions& options = {}, Progress& progress = null_progress());

}  // namespace plenopath
