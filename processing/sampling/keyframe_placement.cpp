#include "processing/sampling/keyframe_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <string>

#include "model/error.h"
#include "processing/sampling/progressive_order.h"
#include "processing/sampling/uniform_sampling.h"

namespace plenopath {

void check_sampling_parameters(const SamplingParameters& p) {
  if (p.count < 0) throw Error("sampling: keyframe count must be >= 0, got " + std::to_string(p.count));
  if (p.count == 0 && !(p.ratio > 0.0)) throw Error("sampling: reduction ratio must be > 0");
  if (!(p.min_spacing_m >= 0.0)) throw Error("sampling: min spacing must be >= 0 m");
  if (!(p.max_spacing_m >= 0.0)) throw Error("sampling: max spacing must be >= 0 m (0 = no limit)");
  if (p.max_spacing_m > 0.0 && p.min_spacing_m > p.max_spacing_m)
    throw Error("sampling: min spacing " + std::to_string(p.min_spacing_m) + " m exceeds max spacing " +
                std::to_string(p.max_spacing_m) + " m");
}

namespace {

std::string metres(double m) {
  std::ostringstream out;
  out.precision(3);
  out << m << " m";
  return out.str();
}

// The keyframe set as positions in path.frames, with what each sampler needs to repair it.
struct Placement {
  const std::vector<double>& s;  // arc length per frame
  const std::vector<double>& u;  // cumulative density per frame (the sampler's coordinate)
  std::vector<bool> fixed;       // per frame: must be kept
  std::set<int> chosen;          // positions

  bool removable(int i) const { return !fixed[i]; }
};

// Nearest frame to the target coordinate that is not chosen yet (the frames' u is non-decreasing).
int nearest_free_frame(const Placement& p, double target) {
  const int n = static_cast<int>(p.u.size());
  int at = static_cast<int>(std::lower_bound(p.u.begin(), p.u.end(), target) - p.u.begin());
  at = std::clamp(at, 0, n - 1);
  if (at > 0 && target - p.u[at - 1] <= p.u[at] - target) --at;
  int best = -1;
  double best_cost = std::numeric_limits<double>::infinity();
  for (int d = 0; d < n; ++d) {
    bool any_in_range = false;
    for (int i : {at - d, at + d}) {
      if (i < 0 || i >= n) continue;
      any_in_range = true;
      if (p.chosen.count(i)) continue;
      const double cost = std::abs(p.u[i] - target);
      if (cost < best_cost) best = i, best_cost = cost;
    }
    if (best >= 0 || !any_in_range) break;
  }
  return best;
}

void enforce_min_spacing(Placement& p, double min_spacing) {
  if (!(min_spacing > 0.0)) return;
  bool changed = true;
  while (changed) {
    changed = false;
    for (auto it = p.chosen.begin(); std::next(it) != p.chosen.end(); ++it) {
      const int a = *it, b = *std::next(it);
      if (p.s[b] - p.s[a] >= min_spacing) continue;
      const int drop = p.removable(b) ? b : (p.removable(a) ? a : -1);
      if (drop < 0) continue;  // two kept frames close together: the author's choice
      p.chosen.erase(drop);
      changed = true;
      break;
    }
  }
}

void enforce_max_spacing(Placement& p, double max_spacing, const CameraPath& path) {
  if (!(max_spacing > 0.0)) return;
  bool changed = true;
  while (changed) {
    changed = false;
    for (auto it = p.chosen.begin(); std::next(it) != p.chosen.end(); ++it) {
      const int a = *it, b = *std::next(it);
      if (p.s[b] - p.s[a] <= max_spacing) continue;
      if (b - a < 2)
        throw Error("sampling: frames " + std::to_string(path.frames[a].index) + " and " +
                    std::to_string(path.frames[b].index) + " are " + metres(p.s[b] - p.s[a]) +
                    " apart, more than the max spacing " + metres(max_spacing));
      const double middle = 0.5 * (p.s[a] + p.s[b]);
      int best = a + 1;
      for (int i = a + 1; i < b; ++i)
        if (std::abs(p.s[i] - middle) < std::abs(p.s[best] - middle)) best = i;
      p.chosen.insert(best);
      changed = true;
      break;
    }
  }
}

// Drops the removable keyframe whose neighbours are closest in coordinate (the most crowded), as long as
// the gap it leaves stays within max spacing.
bool remove_one(Placement& p, double max_spacing) {
  const std::vector<int> k(p.chosen.begin(), p.chosen.end());
  int best = -1;
  double best_gap = std::numeric_limits<double>::infinity();
  for (std::size_t j = 1; j + 1 < k.size(); ++j) {
    if (!p.removable(k[j])) continue;
    if (max_spacing > 0.0 && p.s[k[j + 1]] - p.s[k[j - 1]] > max_spacing) continue;
    const double gap = p.u[k[j + 1]] - p.u[k[j - 1]] + 1e-12 * (p.s[k[j + 1]] - p.s[k[j - 1]]);
    if (gap < best_gap) best = k[j], best_gap = gap;
  }
  if (best < 0) return false;
  p.chosen.erase(best);
  return true;
}

// Adds a frame in the largest coordinate gap (arc length breaks ties) that can take one within min spacing.
bool add_one(Placement& p, double min_spacing) {
  const std::vector<int> k(p.chosen.begin(), p.chosen.end());
  int best = -1;
  double best_gap = -1.0;
  for (std::size_t j = 0; j + 1 < k.size(); ++j) {
    const int a = k[j], b = k[j + 1];
    if (b - a < 2) continue;
    const double gap = p.u[b] - p.u[a] + 1e-12 * (p.s[b] - p.s[a]);
    if (gap <= best_gap) continue;
    const double middle = 0.5 * (p.u[a] + p.u[b]), middle_s = 0.5 * (p.s[a] + p.s[b]);
    int candidate = -1;
    for (int i = a + 1; i < b; ++i) {
      if (min_spacing > 0.0 && (p.s[i] - p.s[a] < min_spacing || p.s[b] - p.s[i] < min_spacing)) continue;
      auto cost = [&](int f) { return std::abs(p.u[f] - middle) + 1e-12 * std::abs(p.s[f] - middle_s); };
      if (candidate < 0 || cost(i) < cost(candidate)) candidate = i;
    }
    if (candidate < 0) continue;
    best = candidate;
    best_gap = gap;
  }
  if (best < 0) return false;
  p.chosen.insert(best);
  return true;
}

// Spacing limits as density limits: keyframes at equal steps of cumulative density D over `gaps` steps are
// about D / (gaps * d(s)) apart, so min/max spacing bound d to [D / (gaps * max), D / (gaps * min)]. D
// changes with the clamping, hence a few rounds; 10 % margins leave room for snapping to frames.
DensityProfile clamp_for_spacing(DensityProfile density, int gaps, double min_spacing, double max_spacing) {
  if (gaps < 1 || (!(min_spacing > 0.0) && !(max_spacing > 0.0))) return density;
  for (int round = 0; round < 30; ++round) {
    const double total = density.total_mass();
    if (!(total > 0.0)) return density;
    double lo = max_spacing > 0.0 ? total / (gaps * 0.9 * max_spacing) : 0.0;
    double hi =
        min_spacing > 0.0 ? total / (gaps * 1.1 * min_spacing) : std::numeric_limits<double>::infinity();
    if (lo > hi) lo = hi = 0.5 * (lo + hi);  // tight budget: as even as it gets
    for (double& d : density.density) d = std::clamp(d, lo, hi);
  }
  return density;
}

}  // namespace

Keyframes place_keyframes(const CameraPath& path, const DensityProfile& density_in,
                          const SamplingParameters& parameters, const std::vector<int>& pinned) {
  check_sampling_parameters(parameters);
  Keyframes result;
  result.parameters = parameters;
  result.pinned = pinned;
  const int n = static_cast<int>(path.size());
  const int budget = keyframe_budget(parameters, n);
  if (budget == 0) return result;

  const std::vector<double> s = path.arc_lengths();
  const DensityProfile density =
      clamp_for_spacing(density_in, budget - 1, parameters.min_spacing_m, parameters.max_spacing_m);
  std::vector<double> u(n);
  const double total = density.total_mass();
  const bool flat = !(total > 0.0) || !(s.back() > 0.0);
  for (int i = 0; i < n; ++i) u[i] = flat ? static_cast<double>(i) : density.mass_at(s[i]);
  // Frames in a stretch of zero density share a coordinate: arc length (tiny weight) keeps them ordered.
  const double tie = flat ? 0.0 : 1e-9 * total / std::max(s.back(), 1e-9);
  for (int i = 0; i < n; ++i) u[i] += tie * s[i];
  const double u_total = u.back() - u.front();

  Placement p{s, u, std::vector<bool>(n, false), {}};
  p.fixed[0] = p.fixed[n - 1] = true;
  for (int index : pinned) {
    const PathFrame* frame = path.find_frame(index);
    if (!frame) throw Error("sampling: pinned frame " + std::to_string(index) + " is not on the path");
    p.fixed[static_cast<std::size_t>(frame - path.frames.data())] = true;
  }
  for (int i = 0; i < n; ++i)
    if (p.fixed[i]) p.chosen.insert(i);
  const int kept = static_cast<int>(p.chosen.size());
  if (kept > budget)
    throw Error("sampling: a budget of " + std::to_string(budget) + " keyframes is fewer than the " +
                std::to_string(kept) + " frames that must be kept (first, last and pinned)");

  const int free = budget - kept;
  for (int k = 0; k < free; ++k) {
    const int i = nearest_free_frame(p, u.front() + u_total * (k + 1.0) / (free + 1.0));
    if (i >= 0) p.chosen.insert(i);
  }

  enforce_min_spacing(p, parameters.min_spacing_m);
  enforce_max_spacing(p, parameters.max_spacing_m, path);
  while (static_cast<int>(p.chosen.size()) > budget)
    if (!remove_one(p, parameters.max_spacing_m))
      throw Error("sampling: the max spacing " + metres(parameters.max_spacing_m) + " needs more than " +
                  std::to_string(budget) + " keyframes on this " + metres(s.back()) + " path");
  while (static_cast<int>(p.chosen.size()) < budget)
    if (!add_one(p, parameters.min_spacing_m))
      throw Error("sampling: the min spacing " + metres(parameters.min_spacing_m) + " allows fewer than " +
                  std::to_string(budget) + " keyframes on this " + metres(s.back()) + " path");

  std::vector<double> coordinate;
  std::vector<bool> fixed;
  for (int i : p.chosen) {
    result.indices.push_back(path.frames[i].index);
    coordinate.push_back(u[i]);
    fixed.push_back(p.fixed[i]);
  }
  result.rank = progressive_ranks(coordinate, fixed);
  return result;
}

}  // namespace plenopath
