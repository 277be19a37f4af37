#pragma once
// Lengths of the view graph's edges beyond what the floor measures (issue 20). Two views give the direction
// of their baseline, not its length; two edges that meet at a still and triangulate the same features of
// that still give the ratio of their lengths: a point at distance D from still j is at depth d1 = D / L1
// along j's ray in the first pair's unit-baseline triangulation and d2 = D / L2 in the second's, so
// L1 / L2 = d2 / d1. Every such ratio (the median over the shared features) and every metric length from
// the floor is one equation in the log lengths, solved by weighted least squares. Without it a chain of
// stills down a corridor (all directions along one line) or a group whose floor shows no texture has no
// positions.
#include <Eigen/Core>
#include <utility>
#include <vector>

namespace plenopath {

// One edge's verified matches, triangulated with a unit baseline: depth along a's ray and along b's (NaN
// where the rays are too parallel or meet behind a camera).
struct EdgeDepths {
  int a = 0, b = 0;
  std::vector<std::pair<int, int>> features;  // (feature of a, feature of b)
  std::vector<double> depth_a, depth_b;
  double metric_length = 0.0;  // from the floor, 0 when not measured
  double metric_weight = 0.0;  // its trust (floor points)
};

// Unit-baseline depths of correspondences (planar_two_point.h's conventions: B at (cos phi, sin phi, 0)
// turned by psi); rays less than min_parallax_deg apart get NaN.
void triangulate_unit_baseline(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                               double turn, double direction, double min_parallax_deg,
                               std::vector<double>* depth_a, std::vector<double>* depth_b);

struct EdgeLengths {
  std::vector<double> length;  // per edge, > 0 where fixed, 0 where not (the direction alone is known)
  bool metric = false;         // the fixed lengths are in metres (tied to a floor length), else relative
  int ratios = 0;              // ratio equations used
};

// Lengths of the edges tied by ratios (min_shared features at least, spread below max_log_spread as a
// median absolute deviation of log ratios) to each other: of the sets of edges so tied, the one with a
// metric length (the most floor points) wins, else the largest, whose first edge gets length 1. Edges
// outside it keep length 0. still_count: the number of stills.
EdgeLengths solve_edge_lengths(int still_count, const std::vector<EdgeDepths>& edges, int min_shared = 8,
                               double max_log_spread = 0.1);

}  // namespace plenopath
