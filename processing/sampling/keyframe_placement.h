#pragma once
// From a density along the path to keyframes: the budget met exactly, first/last and pinned frames kept,
// min/max spacing honoured, and a progressive rank. Shared by every sampler.
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"
#include "processing/sampling/density_profile.h"

namespace plenopath {

// parameters gives the budget (count, or ratio -> keyframe_budget), min_spacing_m and max_spacing_m;
// method, exponent and boost are copied into the result but not read here. The frames that are always kept
// (first, last, pinned) use part of the budget; the `free` others go to the frames nearest to the mass
// quantiles (k + 1) / (free + 1), k = 0 .. free-1, of the density: without pins, the keyframes sit at equal
// steps of cumulative density from the first frame (step 0) to the last. Min/max spacing first clamp the
// density (where keyframes would be too close or too far apart); what snapping to frames still breaks is
// repaired (frames closer than min spacing dropped, gaps longer than max spacing split) and the count
// brought back to the budget (removing where the density is most crowded, adding in its largest gap).
// Throws plenopath::Error when the budget cannot be met: fewer keyframes than the frames that must be kept,
// a pinned frame that is not on the path, or spacing limits that need more (or allow fewer) keyframes.
Keyframes place_keyframes(const CameraPath& path, const DensityProfile& density,
                          const SamplingParameters& parameters, const std::vector<int>& pinned);

// Throws plenopath::Error when spacing limits or the budget are malformed (negative, min > max).
void check_sampling_parameters(const SamplingParameters& parameters);

}  // namespace plenopath
