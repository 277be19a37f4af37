#pragma once
// What a keyframe set loses, so authors and benchmarks can compare samplers at equal budgets:
// - geometric: for each dropped frame, 1 - IoU of its envelope with the envelope of its stand-in (the
//   keyframe nearest along the path); mean, 95th percentile and max;
// - photometric: PSNR and SSIM between a dropped frame and its stand-in turned to the same heading, on an
//   even subsample of the dropped frames;
// - the reduction ratio and the largest gap along the path.
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"
#include "processing/util/progress.h"
#include "processing/visibility/visibility.h"

namespace plenopath {

// The envelope of every frame of a path, computed once and shared by every loss evaluation on that path.
struct PathEnvelopes {
  std::vector<Envelope> frames;  // one per path frame, same order
};
// threads: 0 = hardware concurrency, 1 = the calling thread only. `progress` gets the fraction done, from
// worker threads too; a cancel ends it with Cancelled.
PathEnvelopes compute_path_envelopes(const VisibilityIndex& index, const CameraPath& path, int threads = 0,
                                     Progress& progress = null_progress());

// For each path frame, the position (in path.frames) of its stand-in: the keyframe nearest by arc length
// (ties: the earlier one). A keyframe stands in for itself. Empty when there are no keyframes on the path.
std::vector<int> stand_in_positions(const CameraPath& path, const Keyframes& keyframes);

struct GeometricLoss {
  double mean = 0.0;  // mean of 1 - IoU over the dropped frames that have envelopes
  double p95 = 0.0;   // 95th percentile (nearest rank)
  double max = 0.0;
  int dropped = 0;    // frames that are not keyframes
  int evaluated = 0;  // dropped frames whose envelope and stand-in's envelope both exist
  int inexact = 0;    // IoUs measured on a grid because a polygon was not simple after rounding
};
GeometricLoss geometric_loss(const CameraPath& path, const Keyframes& keyframes,
                             const PathEnvelopes& envelopes, int threads = 0);

struct PhotometricOptions {
  int max_frames = 40;   // dropped frames compared at most (spread evenly over the dropped frames)
  int max_width = 1024;  // frames are shrunk to at most this width before comparing (speed)
  void check() const;    // throws plenopath::Error saying which field is wrong
};
struct PhotometricLoss {
  double psnr_mean_db = 0.0;  // identical pairs count as 100 dB so the mean stays finite
  double psnr_min_db = 0.0;
  double ssim_mean = 0.0;
  double ssim_min = 0.0;
  int frames = 0;  // pairs compared
};
// read_frame(capture index) returns the frame (BGR 8-bit equirectangular); it may throw Error.
PhotometricLoss photometric_loss(const CameraPath& path, const Keyframes& keyframes,
                                 const std::function<cv::Mat(int index)>& read_frame,
                                 const PhotometricOptions& options = {});

struct SamplingLoss {
  int kept = 0;
  int total = 0;
  double reduction_ratio = 0.0;  // total / kept
  double largest_gap_m = 0.0;    // longest arc length between consecutive keyframes
  bool has_geometric = false;
  GeometricLoss geometric;
  bool has_photometric = false;
  PhotometricLoss photometric;
};

}  // namespace plenopath
