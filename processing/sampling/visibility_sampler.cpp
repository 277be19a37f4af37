#include "processing/sampling/visibility_sampler.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "model/error.h"
#include "processing/sampling/keyframe_placement.h"
#include "processing/sampling/loss_refinement.h"
#include "processing/sampling/polygon_iou.h"

namespace plenopath {

void VisibilitySamplingOptions::check() const {
  cells.check();
  if (!(probe_spacing_m > 0.0)) throw Error("sampling: probe spacing must be > 0 m");
  if (!(loss_power > 0.0) || loss_power > 4.0) throw Error("sampling: loss power must be in (0, 4]");
  if (!(density_floor >= 0.0)) throw Error("sampling: density floor must be >= 0");
  if (!(raster_cell_m > 0.0)) throw Error("sampling: raster cell must be > 0 m");
  if (refine_sweeps < 0) throw Error("sampling: refine sweeps must be >= 0");
}

Eigen::Vector2d point_at_arc_length(const CameraPath& path, const std::vector<double>& s, double at) {
  if (path.empty()) return Eigen::Vector2d::Zero();
  if (at <= s.front()) return path.frames.front().position();
  if (at >= s.back()) return path.frames.back().position();
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), at) - s.begin());  // s[i] > at
  const double span = s[i] - s[i - 1];
  const double t = span > 0.0 ? (at - s[i - 1]) / span : 0.0;
  return (1.0 - t) * path.frames[i - 1].position() + t * path.frames[i].position();
}

std::vector<SamplingCell> sampling_cells_from_visibility(const CameraPath& path, const VisibilityCells& cells,
                                                         const VisibilityIndex* index) {
  const std::vector<double> s = path.arc_lengths();
  std::vector<SamplingCell> out;
  out.reserve(cells.cells.size());
  for (const VisibilityCell& c : cells.cells) {
    SamplingCell cell;
    cell.s_begin = c.s_begin;
    cell.s_end = c.s_end;
    cell.size = c.area_mean > 0.0 ? c.area_mean : c.area_mid;
    if (!(cell.size > 0.0) && index)
      cell.size = index->envelope_area(point_at_arc_length(path, s, 0.5 * (c.s_begin + c.s_end)));
    out.push_back(cell);
  }
  return out;
}

DensityProfile expected_loss_density(const CameraPath& path, const VisibilityIndex& index,
                                     const VisibilitySamplingOptions& options) {
  options.check();
  const std::vector<double> s = path.arc_lengths();
  const double length = s.empty() ? 0.0 : s.back();
  if (!(length > 0.0)) return uniform_density(length);
  const int pieces = std::max(1, static_cast<int>(std::ceil(length / options.probe_spacing_m)));
  std::vector<Envelope> probe(pieces + 1);
  for (int k = 0; k <= pieces; ++k)
    probe[k] = index.envelope(point_at_arc_length(path, s, length * k / pieces));
  DensityProfile profile;
  profile.breaks.push_back(0.0);
  const double step = length / pieces;
  for (int k = 0; k < pieces; ++k) {
    const Envelope& a = probe[k];
    const Envelope& b = probe[k + 1];
    double change = 0.0;
    if (a.status == EnvelopeStatus::ok && b.status == EnvelopeStatus::ok)
      change = 1.0 - polygon_iou(a.polygon, b.polygon);
    else if ((a.status == EnvelopeStatus::ok) != (b.status == EnvelopeStatus::ok))
      change = 1.0;
    profile.breaks.push_back(length * (k + 1) / pieces);
    profile.density.push_back(std::pow(change / step, options.loss_power));
  }
  const double mean = profile.total_mass() / length;
  if (!(mean > 0.0)) return uniform_density(length);
  for (double& d : profile.density) d = std::max(d, options.density_floor * mean);
  return profile;
}

Keyframes sample_by_visibility(const CameraPath& path, const VisibilitySamplingInputs& inputs,
                               const SamplingParameters& parameters, const std::vector<int>& pinned,
                               const VisibilitySamplingOptions& options_in) {
  const VisibilityCells* cells = inputs.cells;
  const VisibilityIndex* index = inputs.index;
  VisibilitySamplingOptions options = options_in;
  options.cells.exponent = parameters.exponent;
  options.cells.transition_boost = parameters.transition_boost;
  options.check();
  check_sampling_parameters(parameters);
  DensityProfile density;
  if (parameters.rule == VisibilityRule::cell_rule) {
    if (!cells || cells->cells.empty())
      throw Error("visibility sampling: no visibility cells along the path (compute visibility first)");
    density =
        cell_rule_density(sampling_cells_from_visibility(path, *cells, index), path.length(), options.cells);
  } else {
    if (!index) throw Error("visibility sampling: the expected-loss rule needs the floor plan's visibility");
    density = expected_loss_density(path, *index, options);
  }
  Keyframes k = place_keyframes(path, density, parameters, pinned);
  k.parameters.method = SamplingMethod::kVisibility;
  if (parameters.rule == VisibilityRule::cell_rule) {
    k.sampler.cell_rule = {options.cells.transition_window_m, options.cells.min_size};
  } else {
    k.sampler.expected_loss = {options.probe_spacing_m, options.loss_power, options.density_floor};
  }
  if (parameters.rule != VisibilityRule::expected_loss || !options.refine_by_loss || k.indices.size() < 3)
    return k;

  // Refinement by the loss each keyframe position causes, on the rasterised envelopes of every frame.
  Progress& progress = inputs.progress ? *inputs.progress : null_progress();
  PathEnvelopes computed;
  const PathEnvelopes* envelopes = inputs.envelopes;
  if (!envelopes || envelopes->frames.size() != path.size()) {
    SubProgress envelopes_progress(progress, 0.0, 0.6, "envelopes");
    computed = compute_path_envelopes(*index, path, 0, envelopes_progress);
    envelopes = &computed;
  }
  std::unique_ptr<EnvelopeRaster> built;
  const EnvelopeRaster* raster = inputs.raster;
  if (!raster || raster->frames() != static_cast<int>(path.size())) {
    built = std::make_unique<EnvelopeRaster>(*envelopes, options.raster_cell_m);
    raster = built.get();
  }
  LossRefinementOptions refine;
  refine.sweeps = options.refine_sweeps;
  refine.min_spacing_m = parameters.min_spacing_m;
  refine.max_spacing_m = parameters.max_spacing_m;
  SubProgress refine_progress(progress, 0.6, 0.95, "refining by loss");
  k = refine_keyframes_by_loss(path, k, pinned, *raster, refine, refine_progress);
  k.sampler.refinement = {true, options.refine_sweeps, raster->cell_m()};  // the cell as used (may be grown)
  progress.checkpoint(1.0);
  return k;
}

}  // namespace plenopath
