#include "processing/sampling/keyframe_sampler.h"

#include "model/error.h"
#include "processing/sampling/keyframe_placement.h"

namespace plenopath {

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
