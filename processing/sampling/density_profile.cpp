#include "processing/sampling/density_profile.h"

#include <algorithm>
#include <cmath>

namespace plenopath {

double DensityProfile::total_mass() const {
  double m = 0.0;
  for (std::size_t i = 0; i < density.size(); ++i) m += density[i] * (breaks[i + 1] - breaks[i]);
  return m;
}

double DensityProfile::mass_at(double s) const {
  double m = 0.0;
  for (std::size_t i = 0; i < density.size(); ++i) {
    if (s <= breaks[i]) break;
    m += density[i] * (std::min(s, breaks[i + 1]) - breaks[i]);
  }
  return m;
}

DensityProfile uniform_density(double path_length) {
  DensityProfile p;
  p.breaks = {0.0, std::max(path_length, 0.0)};
  p.density = {1.0};
  return p;
}

void add_density(DensityProfile* profile, double begin, double end, double value) {
  if (profile->breaks.empty() || !(end > begin)) return;
  begin = std::max(begin, profile->breaks.front());
  end = std::min(end, profile->breaks.back());
  if (!(end > begin)) return;
  // Split pieces at begin and end, then add to every piece inside.
  auto split_at = [&](double s) {
    const auto it = std::upper_bound(profile->breaks.begin(), profile->breaks.end(), s);
    if (it == profile->breaks.begin() || it == profile->breaks.end()) return;
    const std::size_t piece = static_cast<std::size_t>(it - profile->breaks.begin()) - 1;
    if (profile->breaks[piece] == s) return;
    profile->breaks.insert(it, s);
    profile->density.insert(profile->density.begin() + static_cast<long>(piece), profile->density[piece]);
  };
  split_at(begin);
  split_at(end);
  for (std::size_t i = 0; i < profile->density.size(); ++i)
    if (profile->breaks[i] >= begin && profile->breaks[i + 1] <= end) profile->density[i] += value;
}

}  // namespace plenopath
