#pragma once
// Order statistics of a set of values, by partial sort of a copy.
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace plenopath {

// The value at fraction q (clamped to 0..1) of the sorted values, nearest rank rounded down; 0 for none.
inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const std::size_t k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// The median (the upper one for an even count; 0 for none).
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The median of |v - centre| (0 for none); 1.4826 times it is the standard deviation of Gaussian scatter.
inline double median_absolute_deviation(const std::vector<double>& v, double centre) {
  std::vector<double> deviation;
  deviation.reserve(v.size());
  for (double x : v) deviation.push_back(x < centre ? centre - x : x - centre);
  return median(std::move(deviation));
}

}  // namespace plenopath
