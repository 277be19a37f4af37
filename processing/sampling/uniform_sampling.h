#pragma once
// Keyframes spaced evenly by arc length along the path: the baseline sampler, and the one the studio offers
// until visibility-driven sampling exists. Also the statistics the sampling panel shows for any keyframe set.
#include "model/camera_path.h"
#include "model/keyframes.h"

namespace plenopath {

// Number of keyframes a budget asks for on a path of `frame_count` frames: parameters.count when > 0, else
// round(frame_count / parameters.ratio); at least 2 (first and last) and at most frame_count.
int keyframe_budget(const SamplingParameters& parameters, int frame_count);

// Keyframes at the frames nearest to `budget` arc-length positions spread evenly from the first frame to the
// last; pinned frames (capture indices present in the path) are always kept. Ranks are coarse to fine:
// first and last frame, then repeatedly the middle of each interval. Throws Error on bad parameters
// (ratio <= 0, count < 0).
Keyframes sample_uniform_by_arc_length(const CameraPath& path, const SamplingParameters& parameters,
                                       const std::vector<int>& pinned = {});

struct SamplingStatistics {
  int kept = 0;             // keyframes that are frames of the path
  int total = 0;            // frames in the path
  double ratio = 0.0;       // total / kept (0 when nothing is kept)
  double max_gap_m = 0.0;   // longest arc length between consecutive keyframes
  double mean_gap_m = 0.0;  // path length / (kept - 1)
};
SamplingStatistics sampling_statistics(const CameraPath& path, const Keyframes& keyframes);

}  // namespace plenopath
