#pragma once
// Clean-up of imported line work, layer by layer: snap endpoints, drop zero-length and duplicate segments,
// merge collinear overlaps, split at intersections and T-junctions.
#include <vector>

#include "model/floor_plan.h"

namespace plenopath {

struct CleanupCounts {
  int snapped_endpoints = 0;
  int zero_length_dropped = 0;
  int duplicates_dropped = 0;
  int collinear_merged = 0;
  int intersections_split = 0;
};

// Segments interact only with segments of the same layer. tolerance in metres.
std::vector<PlanSegment> clean_segments(const std::vector<PlanSegment>& input, double tolerance,
                                        CleanupCounts* counts);

}  // namespace plenopath
