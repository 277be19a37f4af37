#include "processing/sampling/progressive_order.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plenopath {

std::vector<int> progressive_ranks(const std::vector<double>& coordinate, const std::vector<bool>& fixed) {
  const int n = static_cast<int>(coordinate.size());
  std::vector<int> rank(n, -1);
  if (n == 0) return rank;
  int next = 0;
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());  // to the nearest ranked keyframe
  auto take = [&](int k) {
    rank[k] = next++;
    for (int j = 0; j < n; ++j) distance[j] = std::min(distance[j], std::abs(coordinate[j] - coordinate[k]));
  };
  take(0);
  if (n > 1) take(n - 1);
  for (int k = 1; k + 1 < n; ++k)
    if (k < static_cast<int>(fixed.size()) && fixed[k]) take(k);
  while (next < n) {
    int best = -1;
    for (int j = 0; j < n; ++j)
      if (rank[j] < 0 && (best < 0 || distance[j] > distance[best])) best = j;
    take(best);
  }
  return rank;
}

}  // namespace plenopath
