#pragma once
// Keyframes driven by visibility in the floor plan. Two rules:
// - cell_rule (the seed's): the visibility cells along the path get keyframes in proportion to l^e / v
//   (cell_rule.h), plus the transition boost;
// - expected_loss (ours, the default): the density follows the measured rate at which the envelope changes
//   along the path. Envelopes are probed every probe_spacing_m; between probes k and k+1 the loss rate is
//   r = (1 - IoU(E_k, E_k+1)) / distance, and the density is r^loss_power. With a dropped frame's loss about
//   r times its distance to the keyframe, a stretch of length l with n keyframes loses about r l^2 / 4n;
//   minimising the sum under a fixed total n gives n proportional to l sqrt(r): loss_power 1/2.
//   Then (refine_by_loss) every frame's envelope is rasterised and the keyframes are moved to the frames
//   that minimise the estimated summed loss, and ranked by backward elimination (loss_refinement.h).
//   tests/bench/bench_sampling.cpp measures both rules against uniform sampling.
#include <functional>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"
#include "model/visibility_cells.h"
#include "processing/sampling/cell_rule.h"
#include "processing/sampling/envelope_raster.h"
#include "processing/sampling/sampling_loss.h"
#include "processing/visibility/visibility.h"

namespace plenopath {

// The rule is SamplingParameters::rule (VisibilityRule, model/keyframes.h); the sampler records these options
// in the keyframes it makes (Keyframes::sampler).
struct VisibilitySamplingOptions {
  // cell_rule: window and size floor (exponent and boost come from SamplingParameters).
  CellRuleOptions cells;
  // expected_loss: metres between envelope probes along the path.
  double probe_spacing_m = 0.25;
  // expected_loss: density = rate^loss_power (1/2 minimises the summed loss, see above).
  double loss_power = 0.5;
  // expected_loss: every stretch keeps at least this fraction of the mean density (a path never goes
  // entirely unsampled, e.g. along a blank wall where nothing changes).
  double density_floor = 0.1;
  // expected_loss: move keyframes by the loss they cause and rank them by it (needs every frame's envelope).
  bool refine_by_loss = true;
  double raster_cell_m =
      0.08;  // grid cell of the loss estimate (grown on large plans, see envelope_raster.h)
  int refine_sweeps = 6;

  void check() const;  // throws plenopath::Error saying which field is wrong
};

// The model's cells as sampling cells: v = area_mean when measured, else area_mid; cells with neither get
// the envelope area at their middle from `index` (when given).
std::vector<SamplingCell> sampling_cells_from_visibility(const CameraPath& path, const VisibilityCells& cells,
                                                         const VisibilityIndex* index = nullptr);

// The density each rule gives (exposed for tests and benchmarks).
DensityProfile expected_loss_density(const CameraPath& path, const VisibilityIndex& index,
                                     const VisibilitySamplingOptions& options = {});

// What the visibility sampler reads. cell_rule needs `cells` (and `index` only when their areas are
// missing); expected_loss needs `index`, and takes `envelopes` (every frame's, computed when absent) and
// `raster` (built from them when absent) to avoid recomputing them between resamplings.
struct VisibilitySamplingInputs {
  const VisibilityCells* cells = nullptr;
  const VisibilityIndex* index = nullptr;
  const PathEnvelopes* envelopes = nullptr;
  const EnvelopeRaster* raster = nullptr;
  Progress* progress = nullptr;  // optional
};
// Throws Error when what the rule needs is missing, and as place_keyframes does.
Keyframes sample_by_visibility(const CameraPath& path, const VisibilitySamplingInputs& inputs,
                               const SamplingParameters& parameters, const std::vector<int>& pinned,
                               const VisibilitySamplingOptions& options = {});

// The point at arc length s along the path polyline (clamped to its ends).
Eigen::Vector2d point_at_arc_length(const CameraPath& path, const std::vector<double>& arc_lengths, double s);

}  // namespace plenopath
