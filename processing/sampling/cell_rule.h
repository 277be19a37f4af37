#pragma once
// The seed's rule: a cell of size v crossed by the path for a length l gets keyframes in proportion to
// l^exponent / v, plus a local increase where the cell size changes much between neighbours (going from
// one large cell into another). Cells come from visibility events (v = envelope area, m^2) or from
// significant changes of a depth panorama's volume (v = star volume, m^3).
#include <vector>

#include "processing/sampling/density_profile.h"

namespace plenopath {

struct SamplingCell {
  double s_begin = 0.0;  // arc length where the cell starts, metres
  double s_end = 0.0;    // arc length where it ends
  double size = 0.0;     // v: envelope area (m^2) or depth volume (m^3)
  double length() const { return s_end - s_begin; }
};

struct CellRuleOptions {
  // Mass of a cell = l^exponent / v. The seed's 3-D form is 3. In the plan (v an area) tests/bench/
  // bench_sampling.cpp measures 0.5 .. 1 best (lowest geometric loss at 50x on the office sample and on
  // random plans) and 3 worst: the loss comes from the envelope changing, which is fast where v is small
  // and where events crowd (short cells near doors and pillars); l^3 pours the budget into the few long
  // cells instead (long corridor stretches), where a keyframe covers a lot of path anyway.
  double exponent = 1.0;
  // Near each boundary between two cells, boost * |ln(v_next / v)| times the path's mean density is added
  // (0 = the plain rule): a transition between very different cells gets about that many extra keyframes
  // per window.
  double transition_boost = 1.0;
  // Half-width (metres) of the stretch around a boundary that the boost raises; clipped to each cell.
  double transition_window_m = 1.0;
  // Sizes below this count as this (a cell whose envelope could not be measured must not swallow the budget).
  double min_size = 0.01;

  void check() const;  // throws plenopath::Error saying which field is wrong
};

// l^exponent / v per cell (0 for a cell of no length).
std::vector<double> cell_masses(const std::vector<SamplingCell>& cells, const CellRuleOptions& options);

// The density whose integral over each cell is its share l^e/v of the total (constant inside the cell),
// times the transition boost near boundaries. Stretches of [0, path_length] that no cell covers get no
// mass; if no cell has mass the density is uniform. Cells must be ordered and not overlap.
DensityProfile cell_rule_density(const std::vector<SamplingCell>& cells, double path_length,
                                 const CellRuleOptions& options);

}  // namespace plenopath
