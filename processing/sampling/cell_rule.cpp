#include "processing/sampling/cell_rule.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "model/error.h"

namespace plenopath {

void CellRuleOptions::check() const {
  if (!std::isfinite(exponent) || exponent < 0.0 || exponent > 10.0)
    throw Error("sampling: exponent must be in [0, 10], got " + std::to_string(exponent));
  if (!std::isfinite(transition_boost) || transition_boost < 0.0)
    throw Error("sampling: transition boost must be >= 0, got " + std::to_string(transition_boost));
  if (!std::isfinite(transition_window_m) || transition_window_m < 0.0)
    throw Error("sampling: transition window must be >= 0 m");
  if (!(min_size > 0.0)) throw Error("sampling: min cell size must be > 0");
}

std::vector<double> cell_masses(const std::vector<SamplingCell>& cells, const CellRuleOptions& options) {
  options.check();
  std::vector<double> mass;
  mass.reserve(cells.size());
  for (const SamplingCell& c : cells) {
    const double l = c.length();
    mass.push_back(l > 0.0 ? std::pow(l, options.exponent) / std::max(c.size, options.min_size) : 0.0);
  }
  return mass;
}

DensityProfile cell_rule_density(const std::vector<SamplingCell>& cells, double path_length,
                                 const CellRuleOptions& options) {
  const std::vector<double> mass = cell_masses(cells, options);
  double total = 0.0;
  for (double m : mass) total += m;
  if (!(total > 0.0) || !std::isfinite(total)) return uniform_density(path_length);

  DensityProfile profile;
  profile.breaks = {0.0};
  auto close_piece = [&](double end, double density) {
    if (end <= profile.breaks.back()) return;
    profile.breaks.push_back(end);
    profile.density.push_back(density);
  };
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const SamplingCell& c = cells[i];
    close_piece(std::clamp(c.s_begin, 0.0, path_length), 0.0);  // a stretch no cell covers
    const double l = c.length();
    close_piece(std::clamp(c.s_end, 0.0, path_length), l > 0.0 ? mass[i] / total / l : 0.0);
  }
  close_piece(path_length, 0.0);
  if (profile.density.empty()) return uniform_density(path_length);

  // The transition boost: near a boundary, boost * change times the mean density is added (each side within
  // its cell), so the boost means the same whatever the exponent does to the cells' own densities.
  const double mean_density = path_length > 0.0 ? 1.0 / path_length : 0.0;
  if (options.transition_boost > 0.0 && options.transition_window_m > 0.0) {
    for (std::size_t i = 0; i + 1 < cells.size(); ++i) {
      const double v0 = std::max(cells[i].size, options.min_size);
      const double v1 = std::max(cells[i + 1].size, options.min_size);
      const double change = std::abs(std::log(v1 / v0));
      if (!(change > 0.0)) continue;
      const double factor = options.transition_boost * change;
      const double w0 = std::min(options.transition_window_m, cells[i].length());
      const double w1 = std::min(options.transition_window_m, cells[i + 1].length());
      add_density(&profile, cells[i].s_end - w0, cells[i + 1].s_begin + w1, factor * mean_density);
    }
  }
  return profile;
}

}  // namespace plenopath
