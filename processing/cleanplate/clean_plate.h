#pragma once
// Clean plates (issue 24): a keyframe without the people who walked through it. The paper's stated next
// step ("removing of the moving parts ... to get clean static images"), done here by the scene's static
// geometry rather than by optical flow alone:
//   1. Warp: neighbouring frames along the path (both directions, spread over baselines in [min, max]) are
//      warped onto the keyframe by the recovered poses and the keyframe's static depth (metres along each
//      ray: a depth map, or the plan's walls, floor and ceiling): the keyframe pixel's 3-D point is looked up
//      in the neighbour (bilinear, the seam wrapped). Where the neighbour's own static depth says the point
//      is hidden there (a wall between), its sample is dropped.
//   2. Consensus: per pixel and channel, the median of the warped samples (the keyframe's own included).
//   3. Moving regions: keyframe pixels that disagree with the consensus of the others by more than
//      `disagreement` grey levels where the others agree among themselves (their spread at most max_spread)
//      (the best match within one pixel: a sharp edge warped half a pixel off is no mover; nor is a jump of
//      the static depth), in blobs of at least `min_region_px` pixels, closed and grown by
//      `mask_dilation_px`; they take the median of the other frames, elsewhere the keyframe stays as it was
//      (no blur from the warp where nothing moved).
// What no neighbour saw (support below min_support) stays as the keyframe has it and is reported.
//   4. The rig (rig_mask: the trolley, the operator, a tripod; what moves with the camera and so covers the
//      same pixels in every frame; joined by what the keyframe itself shows moving with the camera: the same
//      in the neighbours' own images at that pixel, unlike what the geometry brings there) is filled from
//      frames further along and back along the path (baselines rig_min..rig_max) that saw the scene there,
//      their own rig pixels not used: the keyframe's depth there is the scene behind the rig (its
//      surroundings' depth carried in, and the floor plane below the lens when the camera height is known).
//      What none of them saw is reported (rig_unfilled) for a nadir patch.
// Each warped neighbour is brought to the keyframe's exposure first (a gain per channel from the pixels both
// see), so that auto-exposure between frames is no mover and leaves no seam round a fill.
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
  // ... nor where the other frames disagree among themselves (median absolute deviation above this, grey
  // levels): the warp is unsure there, as on furniture the static depth does not know of.
  int max_spread = 10;
  // A disagreeing blob is static geometry the static depth does not know of (furniture off the plan) when the
  // neighbours' own images agree with more than this share of its pixels at another depth along their rays
  // (a plane sweep): it stays as the keyframe has it.
  double max_explained_share = 0.5;
  int min_region_px = 40;    // smaller disagreeing blobs are noise or texture aliasing: left alone
  int mask_closing_px = 6;   // holes in a moving region up to about this wide are closed
  int mask_dilation_px = 3;  // moving regions grown by this (soft edges of people, motion blur)
  int min_support = 3;       // warped samples a pixel needs to be replaced
  // The rig's fill. Nearer frames see the keyframe's rig region through their own rig (the operator walks
  // behind the camera, the trolley covers the floor round it).
  int rig_neighbours = 8;  // about this many frames each side
  double rig_min_baseline_m = 0.5;
  double rig_max_baseline_m = 5.0;
  int rig_min_support = 2;
  // The rig is also found in the keyframe itself: pixels that agree with at least 60 % of the neighbours'
  // own images at the same pixel (within rig_tolerance grey levels) and with at most 30 % of the samples
  // the scene's geometry warps there, in blobs of at least min_rig_region of the image.
  bool detect_rig = true;
  int rig_tolerance = 14;
  double min_rig_region = 0.002;
  double rig_margin_deg = 4.0;   // the rig is looked past with this margin in the other frames' images
  double camera_height_m = 0.0;  // > 0: the floor below the rig is a plane this far below the lens
  // Wider frames are searched for movers and the rig at this width (pixel sizes above are at it), then
  // warped and filled at their own width only there.
  int detection_width = 1024;
  void check() const;  // throws Error naming the bad field
};

struct CleanPlate {
  cv::Mat image;        // CV_8UC3, the keyframe with its moving regions replaced
  cv::Mat moving_mask;  // CV_8U, 255 where the keyframe was replaced
  cv::Mat support;      // CV_8U, warped samples per pixel (the keyframe's own not counted)
  cv::Mat consensus;    // CV_8UC3, the median of the warped neighbours (the keyframe where none saw it)
  std::vector<int> neighbours_used;  // path positions
  double moving_share = 0.0;         // of the image's pixels
  double unsupported_share = 0.0;    // moving pixels left as they were (no neighbour saw the scene there)
  cv::Mat detected_rig;  // CV_8U, 255 where the keyframe's pixels moved with the camera (empty: none)
  cv::Mat rig_filled;    // CV_8U, 255 where the rig was replaced by the scene behind it (empty: no rig)
  cv::Mat rig_unfilled;  // CV_8U, 255 where the rig stays (no neighbour saw behind it): for a nadir patch
  std::vector<int> rig_neighbours_used;  // path positions
  double rig_share = 0.0;                // of the image's pixels
  double rig_unfilled_share = 0.0;       // of the rig's pixels
};

// `frame(position)`: the BGR panorama of path frame `position` (CV_8UC3, all the same size);
// `static_depth(position)`: its static depth (CV_32F metres along the ray, 0 = unknown, same size), or an
// empty Mat when unknown (the neighbour is then not checked for occlusion). The keyframe needs a depth; at
// the rig's pixels it may show the rig (a depth sensor sees it): it is not used there.
// `rig_mask`: CV_8U of the frames' size, non-zero where the rig covers every frame (the tracker's static
// mask inverted), or empty when there is no rig.
// Throws Error on a position outside the path, sizes that disagree, or a keyframe without depth.
// Progress: once per neighbour ("warping frame 12"); a cancel ends it with Cancelled.
CleanPlate clean_plate(const CameraPath& path, int keyframe_position,
                       const std::function<cv::Mat(int position)>& frame,
                       const std::function<cv::Mat(int position)>& static_depth, const cv::Mat& rig_mask,
                       const CleanPlateOptions& options = {}, Progress& progress = null_progress());

}  // namespace plenopath
