#pragma once
// A planar similarity pose graph: each node a pose (x, y, heading) and the log scale of the map around it,
// each edge a measured relative pose of one node seen from another. For long captures the global
// refinement removes the drift between revisited places on the keyframes alone (a bundle over all points
// of 100 000 frames does not fit in memory): consecutive keyframes are tied by their windowed solution,
// revisited places by local bundles (path_refinement.cpp), and the graph spreads each loop's discrepancy
// over the stretch between. The scale is a node variable because a monocular tracker drifts in scale too
// (Strasdat et al., "Scale drift-aware large scale monocular SLAM", RSS 2010, in the plane).
#include <Eigen/Core>
#include <vector>

#include "processing/util/progress.h"

namespace plenopath {

struct PoseGraphEdge {
  int from = 0, to = 0;
  // `to`'s position in `from`'s frame (rotated by -heading of `from`), in the units of the map at `from`.
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();
  double turn = 0.0;       // heading of `to` minus that of `from`, radians
  double log_scale = 0.0;  // log of the map's scale at `to` over that at `from`
  // Standard deviations of the measurement: translation in the poses' units, turn in radians.
  double translation_sigma = 1.0, turn_sigma = 1.0, log_scale_sigma = 1.0;
  bool robust = false;  // a Huber loss (a loop edge may be wrong; a chain edge is not)
};

struct PoseGraphNode {
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();  // x, y, heading
  double log_scale = 0.0;
};

struct PoseGraphReport {
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0;
};

// Solves in place with node 0 held (the gauge: position, heading and scale). Edges must name existing,
// distinct nodes. Throws Cancelled.
PoseGraphReport solve_pose_graph(std::vector<PoseGraphNode>& nodes, const std::vector<PoseGraphEdge>& edges,
                                 int max_iterations, Progress& progress = null_progress());

}  // namespace plenopath
