#pragma once
// The last step of solving still panoramas (issue 20): one Ceres refinement of all poses (x, y, heading)
// of a connected group and the points their verified matches triangulate, on the angle between each
// observed bearing and the predicted one (processing/egomotion/bearing_cost.h), with a robust loss.
// Tracks are the pairwise verified matches joined across stills (a feature of still i matched to one of j
// and that to one of k is one point); a track that would hold two features of one still is dropped.
// Gauge: the group's first still is held fixed and the distance to the still farthest from it is held at
// its starting value (the metric scale, when the starting positions have it, is kept).
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "processing/util/progress.h"

namespace plenopath {

// Verified correspondences of one pair of stills: (feature of still a, feature of still b).
struct PairMatches {
  int a = 0, b = 0;
  std::vector<std::pair<int, int>> features;
};

struct StillObservation {
  int still = 0, point = 0;
  Eigen::Vector3d bearing = Eigen::Vector3d::UnitX();  // unit, camera frame
};

struct StillsBundle {
  std::vector<Eigen::Vector3d> poses;  // per still: (x, y, heading)
  std::vector<Eigen::Vector3d> points;
  std::vector<int> point_views;  // per point: stills observing it
  std::vector<StillObservation> observations;
};

struct StillsRefinementOptions {
  double loss_scale_deg = 0.15;  // Cauchy loss scale on the angular residual
  double max_error_deg = 0.6;    // after the first solve, observations this far off are dropped, then again
  double min_triangulation_deg = 1.5;  // a track's rays must span this angle to become a point
  int max_iterations = 100;
  void check() const;  // throws Error naming the bad field
};

struct StillsRefinementReport {
  int points = 0, observations = 0, dropped_observations = 0, iterations = 0;
  double initial_rms_deg = 0.0, final_rms_deg = 0.0;  // angular residual over the observations kept
};

// Joins the matches of the pairs into tracks, triangulates them from `poses` (per still; only the stills
// of `group` are used) and builds the bundle. bearings[still][feature] are the features' unit bearings.
StillsBundle build_stills_bundle(const std::vector<std::vector<Eigen::Vector3d>>& bearings,
                                 const std::vector<PairMatches>& pairs, const std::vector<int>& group,
                                 const std::vector<Eigen::Vector3d>& poses,
                                 const StillsRefinementOptions& options);

// Refines the bundle's poses (the stills of `group`) and points in place. Checks `progress` for cancellation
// between iterations (then throws Cancelled).
StillsRefinementReport refine_stills(StillsBundle* bundle, const std::vector<int>& group,
                                     const StillsRefinementOptions& options,
                                     Progress& progress = null_progress());

}  // namespace plenopath
