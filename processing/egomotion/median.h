#pragma once
// The median of a set of values (the upper one for an even count; 0 for none), by partial sort of a copy.
#include <algorithm>
#include <vector>

namespace plenopath {

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace plenopath
