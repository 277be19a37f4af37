#pragma once
// The view graph of a set of still panoramas (issue 20): one edge per pair whose matches a planar two-view
// pose verified, then the global steps on it, each on one connected group at a time:
//   - headings by 1-D rotation averaging on the circle (a maximum spanning tree by inliers to start, then
//     weighted circular medians per still, then Cauchy-weighted circular means; edges whose turn disagrees
//     with the result are dropped, which can split a group);
//   - positions from the pairwise directions of travel, in the averaged headings' frame, by linear least
//     squares: an edge with a metric length (from the floor seen by the pair, see stills_scale.h) is a full
//     relative position, an edge without one only says which line the other still lies on. Without any
//     metric edge the gauge is fixed by unit mean distance (the smallest eigenvector of the direction
//     constraints).
#include <Eigen/Core>
#include <utility>
#include <vector>

namespace plenopath {

struct ViewEdge {
  int a = 0, b = 0;             // still indices, a < b
  double turn = 0.0;            // heading of b minus heading of a, radians
  double direction = 0.0;       // b's position seen from a, in a's frame (CCW from a's forward), radians
  double weight = 1.0;          // trust (verified matches)
  double length = 0.0;          // metric distance a-b when known (> 0), else 0
  bool direction_known = true;  // false when the baseline is too short for the direction to be seen
};

// Groups of stills joined by edges, largest first (ties: the one with the lowest still first); each group
// sorted. Stills without edges are groups of one.
std::vector<std::vector<int>> connected_groups(int still_count, const std::vector<ViewEdge>& edges);

struct HeadingAveragingOptions {
  int iterations = 50;            // rounds of per-still circular means
  double max_residual_deg = 3.0;  // an edge whose turn disagrees more with the averaged headings is dropped
  void check() const;             // throws Error naming the bad field
};

// Headings (radians) of the stills of `group` (the group's first still keeps heading 0); `kept` (per edge,
// same order as `edges`) is false for edges dropped as outliers or outside the group.
std::vector<double> average_headings(int still_count, const std::vector<int>& group,
                                     const std::vector<ViewEdge>& edges,
                                     const HeadingAveragingOptions& options, std::vector<bool>* kept);

// Positions (x, y) of the stills of `group` in the headings' frame (the group's first still at the origin),
// from the edges with kept[e] true. Returns false when the edges do not fix the positions (e.g. a group
// held together only by edges without direction, or a chain of directions with no length). `scale_known`
// tells whether any metric edge fixed the scale.
bool solve_positions(int still_count, const std::vector<int>& group, const std::vector<ViewEdge>& edges,
                     const std::vector<bool>& kept, const std::vector<double>& headings,
                     std::vector<Eigen::Vector2d>* positions, bool* scale_known);

// solve_positions(), then the edges that disagree with the positions are dropped one at a time, worst first,
// and the positions solved again: a direction more than max_direction_residual_deg off the solved one drops
// the edge, a length more than max_length_residual (relative) off only drops the length. Wrong directions
// come with right turns (repeated texture seen from elsewhere matches as a shifted copy), so the heading
// averaging cannot see them. An edge whose removal would leave the positions unfixed stays. `kept` is
// updated.
bool solve_positions_robust(int still_count, const std::vector<int>& group, std::vector<ViewEdge> edges,
                            std::vector<bool>* kept, const std::vector<double>& headings,
                            double max_direction_residual_deg, double max_length_residual,
                            std::vector<Eigen::Vector2d>* positions, bool* scale_known);

}  // namespace plenopath
