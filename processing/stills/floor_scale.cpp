#include "processing/stills/floor_scale.h"

#include <cmath>
#include <map>

#include "processing/util/statistics.h"

namespace plenopath {

FloorLevel floor_level(const std::vector<double>& depths, int min_points) {
  FloorLevel out;
  // Mode of log depth in bins of 2 % (with both neighbours), then the median within 4 % of it.
  std::map<int, int> bins;
  for (double z : depths)
    if (z > 0) ++bins[static_cast<int>(std::floor(std::log(z) / 0.02))];
  int best_bin = 0, best_count = -1;
  for (const auto& [bin, count] : bins) {
    const auto below = bins.find(bin - 1), above = bins.find(bin + 1);
    const int c =
        count + (below != bins.end() ? below->second : 0) + (above != bins.end() ? above->second : 0);
    if (c > best_count) {
      best_count = c;
      best_bin = bin;
    }
  }
  if (best_count < 0) return out;
  const double mode = std::exp((best_bin + 0.5) * 0.02);
  std::vector<double> near;
  for (double z : depths)
    if (z > 0 && std::abs(z / mode - 1.0) < 0.04) near.push_back(z);
  if (static_cast<int>(near.size()) < min_points) return out;
  out.depth = median(near);
  out.points = static_cast<int>(near.size());
  return out;
}

double baseline_from_floor(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                           double turn, double direction, double camera_height_m, int min_points,
                           double min_parallax_deg, int* floor_points) {
  if (floor_points) *floor_points = 0;
  const Eigen::Vector3d t(std::cos(direction), std::sin(direction), 0.0);
  const double c = std::cos(turn), s = std::sin(turn);
  const double steep = std::sin(kFloorSteepnessDeg * M_PI / 180.0);
  const double min_parallax = min_parallax_deg * M_PI / 180.0;
  std::vector<double> depths;
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) {
    const Eigen::Vector3d ra = a[k].normalized();
    const Eigen::Vector3d rb =
        Eigen::Vector3d(c * b[k].x() - s * b[k].y(), s * b[k].x() + c * b[k].y(), b[k].z()).normalized();
    if (ra.z() > -steep || rb.z() > -steep) continue;
    if (std::acos(std::min(1.0, ra.dot(rb))) < min_parallax) continue;
    // Nearest points of the rays lambda ra and t + mu rb.
    const double ab = ra.dot(rb), det = 1.0 - ab * ab;
    if (det < 1e-10) continue;
    const double at = ra.dot(t), bt = rb.dot(t);
    const double lambda = (at - ab * bt) / det, mu = (ab * at - bt) / det;
    if (lambda <= 0 || mu <= 0) continue;
    const Eigen::Vector3d p = 0.5 * (lambda * ra + t + mu * rb);
    depths.push_back(-p.z());
  }
  const FloorLevel level = floor_level(depths, min_points);
  if (!(level.depth > 0)) return 0.0;
  if (floor_points) *floor_points = level.points;
  return camera_height_m / level.depth;
}

}  // namespace plenopath
