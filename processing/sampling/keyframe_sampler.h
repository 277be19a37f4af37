#pragma once
// One entry point for every sampling method (uniform | visibility | depth), used by the command line and
// the studio. Each method builds a density along the path (density_profile.h) and keyframe_placement.h
// turns it into keyframes: budget met exactly, first/last and pinned kept, spacing honoured, progressive
// rank.
#include <functional>
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"
#include "model/visibility_cells.h"
#include "processing/sampling/depth_sampler.h"
#include "processing/sampling/depth_volume.h"
#include "processing/sampling/visibility_sampler.h"

namespace plenopath {

// What the methods may need; only `path` is required. visibility: index (expected_loss rule) or cells
// (cell_rule); depth: one depth volume per path frame.
struct SamplingInputs {
  const CameraPath* path = nullptr;
  const VisibilityIndex* index = nullptr;
  const VisibilityCells* cells = nullptr;
  const std::vector<DepthVolume>* depth_volumes = nullptr;
  const PathEnvelopes* depth_envelopes = nullptr;  // depth: every frame's eye-level envelope (optional)
  const PathEnvelopes* envelopes = nullptr;        // visibility: every frame's envelope, if already computed
  const EnvelopeRaster* raster = nullptr;          // visibility: their raster, if already built
  Progress* progress = nullptr;                    // optional
  VisibilitySamplingOptions visibility;
  DepthSamplingOptions depth;
};

// parameters.method (and .rule) pick the sampler. Throws plenopath::Error for a method whose input
// is missing (saying what to compute first), or a budget that cannot be met.
Keyframes sample_keyframes(const SamplingInputs& inputs, const SamplingParameters& parameters,
                           const std::vector<int>& pinned = {});

// Still panoramas (Capture::stills): every still is a keyframe, and pinned, so that no later sampling drops
// one; the progressive rank halves the spacing level by level (first, last, middle, quarters, ...).
Keyframes every_frame_a_keyframe(const CameraPath& path);

}  // namespace plenopath
