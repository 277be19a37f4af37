#include "processing/sampling/uniform_sampling.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>
#include <utility>

#include "model/error.h"

namespace plenopath {

int keyframe_budget(const SamplingParameters& parameters, int frame_count) {
  if (parameters.count < 0)
    throw Error("sampling: keyframe count must be >= 0, got " + std::to_string(parameters.count));
  if (!(parameters.ratio > 0.0)) throw Error("sampling: reduction ratio must be > 0");
  if (frame_count <= 0) return 0;
  const int wanted =
      parameters.count > 0 ? parameters.count : static_cast<int>(std::lround(frame_count / parameters.ratio));
  return std::clamp(wanted, std::min(2, frame_count), frame_count);
}

namespace {

// Coarse-to-fine rank of n ordered keyframes: ends first, then interval midpoints breadth first.
std::vector<int> progressive_ranks(int n) {
  std::vector<int> rank(n, -1);
  if (n == 0) return rank;
  int next = 0;
  rank[0] = next++;
  if (n == 1) return rank;
  rank[n - 1] = next++;
  std::deque<std::pair<int, int>> intervals{{0, n - 1}};
  while (!intervals.empty()) {
    const auto [a, b] = intervals.front();
    intervals.pop_front();
    if (b - a < 2) continue;
    const int mid = (a + b) / 2;
    rank[mid] = next++;
    intervals.push_back({a, mid});
    intervals.push_back({mid, b});
  }
  return rank;
}

}  // namespace

Keyframes sample_uniform_by_arc_length(const CameraPath& path, const SamplingParameters& parameters,
                                       const std::vector<int>& pinned) {
  Keyframes result;
  result.parameters = parameters;
  result.parameters.method = SamplingMethod::kUniform;
  result.pinned = pinned;
  const int n = static_cast<int>(path.size());
  const int budget = keyframe_budget(parameters, n);
  if (budget == 0) return result;

  const std::vector<double> s = path.arc_lengths();
  const double length = s.back();
  std::set<int> positions;  // positions in path.frames
  for (int k = 0; k < budget; ++k) {
    if (budget == 1 || length <= 0.0) {
      // No arc length to spread over (one frame, or the camera never moved): spread by frame number.
      positions.insert(budget == 1 ? 0 : static_cast<int>(std::lround(k * (n - 1.0) / (budget - 1))));
      continue;
    }
    const double target = length * k / (budget - 1);
    const auto it = std::lower_bound(s.begin(), s.end(), target);
    int i = static_cast<int>(it - s.begin());
    if (i >= n) i = n - 1;
    if (i > 0 && target - s[i - 1] <= s[i] - target) --i;
    positions.insert(i);
  }
  for (int frame_index : pinned)
    for (int i = 0; i < n; ++i)
      if (path.frames[i].index == frame_index) positions.insert(i);

  for (int i : positions) result.indices.push_back(path.frames[i].index);
  result.rank = progressive_ranks(static_cast<int>(result.indices.size()));
  return result;
}

SamplingStatistics sampling_statistics(const CameraPath& path, const Keyframes& keyframes) {
  SamplingStatistics stats;
  stats.total = static_cast<int>(path.size());
  const std::vector<double> s = path.arc_lengths();
  std::vector<double> at;  // arc length of each keyframe that is on the path
  for (int index : keyframes.indices)
    for (std::size_t i = 0; i < path.size(); ++i)
      if (path.frames[i].index == index) {
        at.push_back(s[i]);
        break;
      }
  std::sort(at.begin(), at.end());
  stats.kept = static_cast<int>(at.size());
  if (stats.kept > 0) stats.ratio = static_cast<double>(stats.total) / stats.kept;
  for (std::size_t k = 1; k < at.size(); ++k) stats.max_gap_m = std::max(stats.max_gap_m, at[k] - at[k - 1]);
  if (stats.kept > 1) stats.mean_gap_m = (at.back() - at.front()) / (stats.kept - 1);
  return stats;
}

}  // namespace plenopath
