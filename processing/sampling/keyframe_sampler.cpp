#include "processing/sampling/keyframe_sampler.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "model/error.h"
#include "processing/sampling/keyframe_placement.h"

namespace plenopath {

Keyframes every_frame_a_keyframe(const CameraPath& path) {
  Keyframes k;
  for (const PathFrame& f : path.frames) k.indices.push_back(f.index);
  std::sort(k.indices.begin(), k.indices.end());
  k.pinned = k.indices;
  const int n = static_cast<int>(k.indices.size());
  k.rank.assign(static_cast<std::size_t>(n), -1);
  // Coarse to fine: the ends, then the middle of every gap, breadth first.
  int next = 0;
  std::vector<std::pair<int, int>> gaps;
  if (n > 0) k.rank[0] = next++;
  if (n > 1) k.rank[static_cast<std::size_t>(n - 1)] = next++, gaps.push_back({0, n - 1});
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    const auto [a, b] = gaps[g];
    if (b - a < 2) continue;
    const int m = (a + b) / 2;
    k.rank[static_cast<std::size_t>(m)] = next++;
    gaps.push_back({a, m});
    gaps.push_back({m, b});
  }
  return k;
}

Keyframes sample_keyframes(const SamplingInputs& inputs, const SamplingParameters& parameters,
                           const std::vector<int>& pinned) {
  if (!inputs.path) throw Error("sampling: no camera path");
  const CameraPath& path = *inputs.path;
  switch (parameters.method) {
    case SamplingMethod::kUniform: {
      Keyframes k = place_keyframes(path, uniform_density(path.length()), parameters, pinned);
      k.parameters.method = SamplingMethod::kUniform;
      return k;
    }
    case SamplingMethod::kVisibility: {
      VisibilitySamplingInputs v;
      v.cells = inputs.cells;
      v.index = inputs.index;
      v.envelopes = inputs.envelopes;
      v.raster = inputs.raster;
      v.progress = inputs.progress;
      return sample_by_visibility(path, v, parameters, pinned, inputs.visibility);
    }
    case SamplingMethod::kDepth:
      if (!inputs.depth_volumes || inputs.depth_volumes->empty())
        throw Error("depth sampling: the capture has no depth maps (depth sampling needs one per frame)");
      return sample_by_depth(path, *inputs.depth_volumes, parameters, pinned, inputs.depth,
                             inputs.depth_envelopes);
  }
  throw Error("sampling: unknown method (" + enum_names_text<SamplingMethod>() + ")");
}

}  // namespace plenopath
