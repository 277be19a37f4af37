#pragma once
// The sampled keyframes and how they were made: the method and its parameters (what the author chose), and
// the settings of the sampler that ran (recorded by it). SamplingMethod and VisibilityRule are defined in
// resources/schema/enums.json (model/enums.h).
#include <vector>

#include "model/enums.h"

namespace plenopath {

struct SamplingParameters {
  SamplingMethod method = SamplingMethod::kVisibility;
  VisibilityRule rule = VisibilityRule::expected_loss;  // visibility: which rule makes the density
  int count = 0;                                        // budget as a keyframe count (0 = use ratio)
  double ratio = 50.0;                                  // budget as a reduction ratio (frames per keyframe)
  double exponent = 1.0;          // l^exponent / v (cell rule; 1 measures best in the plan: bench_sampling)
  double transition_boost = 1.0;  // extra samples where the envelope changes much between cells
  double min_spacing_m = 0.0;
  double max_spacing_m = 0.0;  // 0 = no limit
};
bool operator==(const SamplingParameters& l, const SamplingParameters& r);

// The settings of the sampler beyond SamplingParameters, as processing/sampling/ names and explains them.
// The samplers write them into the keyframes they make (from their options) and never read them; the
// defaults are the samplers' defaults (tests/processing/sampling/keyframe_sampler_test.cpp checks).
struct ExpectedLossSettings {  // visibility_sampler.h, rule expected_loss
  double probe_spacing_m = 0.25;
  double loss_power = 0.5;
  double density_floor = 0.1;
};
struct LossRefinementSettings {  // loss_refinement.h: keyframes moved by the loss they cause
  bool applied = false;          // whether they were (expected_loss and depth); the rest only then
  int sweeps = 6;
  double raster_cell_m = 0.08;
};
struct CellRuleSettings {  // cell_rule.h, beyond exponent and boost (visibility cell_rule and depth)
  double transition_window_m = 1.0;
  double min_size = 0.01;
};
struct DepthChangeSettings {  // depth_volume.h and depth_sampler.h: where a depth cell begins
  double log_ratio_threshold = 0.25;
  bool use_mean_range = false;
  double min_coverage = 0.5;
  int max_depth_width = 256;
};
struct SamplerSettings {
  ExpectedLossSettings expected_loss;
  LossRefinementSettings refinement;
  CellRuleSettings cell_rule;
  DepthChangeSettings depth_changes;
};
bool operator==(const SamplerSettings& l, const SamplerSettings& r);

struct Keyframes {
  std::vector<int> indices;  // frame indices, ascending
  std::vector<int> rank;     // progressive rank per entry of indices (0 = coarsest, first to download)
  std::vector<int> pinned;   // frames the author insists on
  SamplingParameters parameters;
  SamplerSettings sampler;  // how the sampler ran (only the parts its method and rule use are meaningful)

  bool empty() const { return indices.empty(); }
  // Frame indices in progressive order (coarse to fine).
  std::vector<int> progressive_order() const;
};
bool operator==(const Keyframes& l, const Keyframes& r);

}  // namespace plenopath
