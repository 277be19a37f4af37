#pragma once
// A sampling density along the path: piecewise constant over arc length. Every sampler (uniform,
// visibility, depth) is "place keyframes at equal steps of the cumulative density"; they differ only in
// the density they build.
#include <vector>

namespace plenopath {

struct DensityProfile {
  std::vector<double> breaks;   // ascending arc lengths (metres), size = density.size() + 1, 0 .. path length
  std::vector<double> density;  // per piece, >= 0, in "keyframe mass" per metre (scale does not matter)

  double length() const { return breaks.empty() ? 0.0 : breaks.back(); }
  double total_mass() const;
  // Cumulative mass from 0 to s (clamped to the path).
  double mass_at(double s) const;
};

// Constant density over [0, path_length]: sampling by arc length.
DensityProfile uniform_density(double path_length);

// Pieces with density `value` over [begin, end], added on top of `profile` (which keeps its breaks).
void add_density(DensityProfile* profile, double begin, double end, double value);

}  // namespace plenopath
