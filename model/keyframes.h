#pragma once
// The sampled keyframes and the parameters that produced them.
#include <string>
#include <vector>

namespace plenopath {

struct SamplingParameters {
  std::string method = "visibility";  // uniform | visibility | depth
  int count = 0;                      // budget as a keyframe count (0 = use ratio)
  double ratio = 50.0;                // budget as a reduction ratio (frames per keyframe)
  double exponent = 1.0;          // l^exponent / v (cell rule; 1 measures best in the plan: bench_sampling)
  double transition_boost = 1.0;  // extra samples where the envelope changes much between cells
  double min_spacing_m = 0.0;
  double max_spacing_m = 0.0;  // 0 = no limit
};
bool operator==(const SamplingParameters& l, const SamplingParameters& r);

struct Keyframes {
  std::vector<int> indices;  // frame indices, ascending
  std::vector<int> rank;     // progressive rank per entry of indices (0 = coarsest, first to download)
  std::vector<int> pinned;   // frames the author insists on
  SamplingParameters parameters;

  bool empty() const { return indices.empty(); }
  // Frame indices in progressive order (coarse to fine).
  std::vector<int> progressive_order() const;
};
bool operator==(const Keyframes& l, const Keyframes& r);

}  // namespace plenopath
