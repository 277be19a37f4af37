#pragma once
// Coarse-to-fine ranking of keyframes, so that every prefix of the ranking is itself a good sampling of
// its size (progressive download of a tour): the ends and the fixed frames first, then greedy farthest-point
// insertion in the sampler's own coordinate (arc length for uniform, cumulative density for the others).
#include <vector>

namespace plenopath {

// coordinate: one value per keyframe, ascending (keyframes in path order). fixed: keyframes ranked right
// after the first and last (pinned frames), in path order; may be empty. Returns rank per keyframe:
// 0 = first frame, 1 = last frame, then the fixed ones, then repeatedly the keyframe farthest (in
// coordinate) from every keyframe ranked so far (ties: the earlier one).
std::vector<int> progressive_ranks(const std::vector<double>& coordinate,
                                   const std::vector<bool>& fixed = {});

}  // namespace plenopath
