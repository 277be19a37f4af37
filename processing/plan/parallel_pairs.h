#pragma once
// Close parallel line pairs that overlap along their length: walls drawn as two lines. Each segment keeps
// its nearest partner on either side, found through a hash grid (cells of about max_gap), so the work is
// near-linear in the number of segments. Units are whatever the segments are in.
#include <vector>

#include "processing/plan/segment_grid.h"

namespace plenopath {

struct ParallelPairOptions {
  double max_gap = 0.6;               // largest distance between the two lines
  double min_gap = 1e-9;              // closer pairs (collinear duplicates) are not pairs
  double max_angle = 0.035;           // radians (2 degrees) between the directions
  double min_overlap_fraction = 0.5;  // the overlap covers at least this share of the shorter segment
  double min_overlap_gaps = 2.0;      // and is at least this many gaps long (a wall is longer than thick)
  double cell_size = 0.0;             // grid cell; 0 = max_gap
  // Segments spanning more cells than this (strays at 1e20, a 60 km line) are left out of the search.
  int max_cells_per_segment = 100000;
  // Neighbours examined per segment (then the search moves on to the next segment). Real drawings stay far
  // below it (a wall line has a few dozen neighbours); thousands of lines stacked in one place (a block
  // inserted as a dense array, a fuzzed file) would make the search quadratic: 78 620 segments took minutes
  // before this bound, and 18 816 in 1 080 cells took 45 s under the sanitizers at 4 096 (7 s at 512).
  int max_candidates_per_segment = 512;

  void check() const;  // throws plenopath::Error naming the field
};

struct ParallelPair {
  int i = -1, j = -1;    // i < j
  double gap = 0.0;      // distance between the lines at the middle of their overlap
  double overlap = 0.0;  // length along the lines where both are present
};

struct ParallelPairs {
  std::vector<ParallelPair> pairs;  // each pair once
  // Per segment: index into `pairs` of its nearest partner on the left / right of its direction (the
  // direction taken with angle in [0, pi)), -1 when none.
  std::vector<int> left, right;
  // Index into `pairs` of the nearer of the two, -1 when none.
  int nearest(int segment) const;
};

ParallelPairs find_parallel_pairs(const std::vector<Segment2>& segments, const ParallelPairOptions& options);

}  // namespace plenopath
