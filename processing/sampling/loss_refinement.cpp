#include "processing/sampling/loss_refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "model/error.h"

namespace plenopath {

void LossRefinementOptions::check() const {
  if (sweeps < 0) throw Error("loss refinement: sweeps must be >= 0");
  if (coarse_candidates < 2) throw Error("loss refinement: coarse_candidates must be >= 2");
  if (!(min_spacing_m >= 0.0) || !(max_spacing_m >= 0.0))
    throw Error("loss refinement: spacing must be >= 0");
}

double interval_loss(const EnvelopeRaster& raster, const std::vector<double>& s, int a, int b) {
  double sum = 0.0;
  for (int i = a + 1; i < b; ++i) sum += (s[i] - s[a] <= s[b] - s[i]) ? raster.loss(i, a) : raster.loss(i, b);
  return sum;
}

std::vector<int> refine_by_loss(const EnvelopeRaster& raster, const std::vector<double>& s,
                                std::vector<int> positions, const std::vector<bool>& fixed,
                                const LossRefinementOptions& options, Progress& progress) {
  options.check();
  const int k = static_cast<int>(positions.size());
  auto spacing_ok = [&](int a, int c, int b) {
    if (options.min_spacing_m > 0.0 &&
        (s[c] - s[a] < options.min_spacing_m || s[b] - s[c] < options.min_spacing_m))
      return false;
    if (options.max_spacing_m > 0.0 &&
        (s[c] - s[a] > options.max_spacing_m || s[b] - s[c] > options.max_spacing_m))
      return false;
    return true;
  };
  for (int sweep = 0; sweep < options.sweeps; ++sweep) {
    bool moved = false;
    for (int j = 1; j + 1 < k; ++j) {
      if (j % 16 == 0)
        progress.checkpoint((sweep + static_cast<double>(j) / k) / std::max(options.sweeps, 1));
      if (fixed[j]) continue;
      const int a = positions[j - 1], b = positions[j + 1];
      if (b - a < 3) continue;
      auto cost = [&](int c) { return interval_loss(raster, s, a, c) + interval_loss(raster, s, c, b); };
      int best = positions[j];
      double best_cost = cost(best);
      // Coarse: evenly spread candidates; fine: every frame around the best coarse one.
      const int stride = std::max(1, (b - a) / options.coarse_candidates);
      auto consider = [&](int c) {
        if (c <= a || c >= b || c == best || !spacing_ok(a, c, b)) return;
        const double value = cost(c);
        if (value < best_cost - 1e-12) best = c, best_cost = value;
      };
      for (int c = a + 1; c < b; c += stride) consider(c);
      const int centre = best;
      for (int c = centre - stride + 1; c < centre + stride; ++c) consider(c);
      if (best != positions[j]) {
        positions[j] = best;
        moved = true;
      }
    }
    progress.checkpoint(static_cast<double>(sweep + 1) / std::max(options.sweeps, 1));
    if (!moved) break;
  }
  return positions;
}

std::vector<int> loss_ranks(const EnvelopeRaster& raster, const std::vector<double>& s,
                            const std::vector<int>& positions, const std::vector<bool>& fixed) {
  const int k = static_cast<int>(positions.size());
  std::vector<int> rank(k, -1);
  if (k == 0) return rank;
  std::vector<int> prev(k), next(k);
  for (int j = 0; j < k; ++j) prev[j] = j - 1, next[j] = j + 1;
  std::vector<double> added(k, 0.0);
  std::set<std::pair<double, int>> queue;  // (added loss if removed, keyframe)
  auto removal_cost = [&](int j) {
    const int a = positions[prev[j]], c = positions[j], b = positions[next[j]];
    return interval_loss(raster, s, a, b) - interval_loss(raster, s, a, c) - interval_loss(raster, s, c, b);
  };
  for (int j = 1; j + 1 < k; ++j)
    if (!fixed[j]) queue.insert({added[j] = removal_cost(j), j});
  std::vector<int> removed;  // cheapest first
  while (!queue.empty()) {
    const int j = queue.begin()->second;
    queue.erase(queue.begin());
    removed.push_back(j);
    const int p = prev[j], n = next[j];
    next[p] = n;
    prev[n] = p;
    for (int q : {p, n}) {
      if (q <= 0 || q >= k - 1 || fixed[q]) continue;
      queue.erase({added[q], q});
      queue.insert({added[q] = removal_cost(q), q});
    }
  }
  int next_rank = 0;
  rank[0] = next_rank++;
  if (k > 1) rank[k - 1] = next_rank++;
  for (int j = 1; j + 1 < k; ++j)
    if (fixed[j]) rank[j] = next_rank++;
  for (auto it = removed.rbegin(); it != removed.rend(); ++it) rank[*it] = next_rank++;
  return rank;
}

Keyframes refine_keyframes_by_loss(const CameraPath& path, const Keyframes& keyframes,
                                   const std::vector<int>& pinned, const EnvelopeRaster& raster,
                                   const LossRefinementOptions& options, Progress& progress) {
  if (raster.frames() != static_cast<int>(path.size()))
    throw Error("loss refinement: the envelope raster has " + std::to_string(raster.frames()) +
                " frames, the path " + std::to_string(path.size()));
  if (keyframes.indices.size() < 3) return keyframes;
  const std::vector<double> s = path.arc_lengths();
  std::vector<int> positions;
  std::vector<bool> fixed;
  for (int index : keyframes.indices) {
    const PathFrame* frame = path.find_frame(index);
    if (!frame) throw Error("loss refinement: keyframe " + std::to_string(index) + " is not on the path");
    const int i = static_cast<int>(frame - path.frames.data());
    positions.push_back(i);
    fixed.push_back(i == 0 || i + 1 == static_cast<int>(path.size()) ||
                    std::find(pinned.begin(), pinned.end(), index) != pinned.end());
  }
  positions = refine_by_loss(raster, s, positions, fixed, options, progress);
  Keyframes out = keyframes;
  out.indices.clear();
  for (int i : positions) out.indices.push_back(path.frames[i].index);
  out.rank = loss_ranks(raster, s, positions, fixed);
  return out;
}

}  // namespace plenopath
