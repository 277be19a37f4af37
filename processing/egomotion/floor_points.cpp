#include "processing/egomotion/floor_points.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "model/option_check.h"
#include "processing/util/statistics.h"

namespace plenopath {

void FloorPointOptions::check() const {
  const std::string s = "FloorPointOptions.";
  require_option(min_depression_deg > 0 && min_depression_deg < 90, s + "min_depression_deg",
                 "must be in (0, 90)", min_depression_deg);
  require_option(neighbour_poses >= 0, s + "neighbour_poses", "must be >= 0", neighbour_poses);
  require_option(max_level_deviation > 0, s + "max_level_deviation", "must be > 0", max_level_deviation);
}

std::vector<float> point_parallax(const BundleProblem& problem) {
  const std::size_t n = problem.points.size();
  std::vector<float> parallax(n, 0.0f);
  std::vector<Eigen::Vector3f> first_ray(n);
  std::vector<char> seen(n, 0);
  for (const BundleObservation& o : problem.observations) {
    const std::size_t q = static_cast<std::size_t>(o.point);
    const float heading = static_cast<float>(problem.poses[static_cast<std::size_t>(o.pose)].z());
    const Eigen::Vector3f ray = Eigen::AngleAxisf(heading, Eigen::Vector3f::UnitZ()) * o.bearing_f;
    if (!seen[q]) {
      seen[q] = 1;
      first_ray[q] = ray;
      continue;
    }
    parallax[q] = std::max(parallax[q], std::atan2(first_ray[q].cross(ray).norm(), first_ray[q].dot(ray)));
  }
  return parallax;
}

double floor_depth(const std::vector<double>& depths) {
  constexpr double kBin = 0.04;
  std::map<int, int> bins;
  for (double d : depths)
    if (d > 0 && std::isfinite(d)) ++bins[static_cast<int>(std::floor(std::log(d) / kBin))];
  if (bins.empty()) return 0.0;
  auto smoothed = [&](int bin) {
    int c = 0;
    for (int b = bin - 1; b <= bin + 1; ++b) {
      const auto it = bins.find(b);
      if (it != bins.end()) c += it->second;
    }
    return c;
  };
  int most = 0, crowded = bins.begin()->first;
  for (const auto& [bin, count] : bins)
    if (smoothed(bin) > most) {
      most = smoothed(bin);
      crowded = bin;
    }
  // The deepest bin of a crowded enough level (a third of the most crowded, and a tenth of all points: a
  // few stray deep points are no level), then the fullest bin just above it (the level's middle).
  int chosen = crowded;
  const int enough = std::max((most + 2) / 3, static_cast<int>(std::ceil(0.1 * depths.size())));
  for (auto it = bins.rbegin(); it != bins.rend(); ++it)
    if (smoothed(it->first) >= enough) {
      chosen = it->first;
      for (int b = it->first - 1; b >= it->first - 2; --b)
        if (smoothed(b) > smoothed(chosen)) chosen = b;
      break;
    }
  // The median of the depths within that level's three bins, then narrowed to within 2 % and 1 % of it:
  // what stands on the floor a few cm high (shelf bottoms, skirting, cables) falls in those bins too.
  std::vector<double> near;
  for (double d : depths)
    if (d > 0 && std::abs(std::floor(std::log(d) / kBin) - chosen) <= 1) near.push_back(d);
  double level = median(near);
  for (const double within : {0.02, 0.01}) {
    std::vector<double> closer;
    for (double d : near)
      if (std::abs(d / level - 1.0) <= within) closer.push_back(d);
    if (closer.size() < 10) break;
    level = median(closer);
  }
  return level;
}

double scale_from_camera_height(const BundleProblem& problem, double camera_height_m, int* floor_points) {
  const double min_depression = 25.0 * M_PI / 180.0;
  const float min_parallax = static_cast<float>(3.0 * M_PI / 180.0);
  const std::vector<float> parallax = point_parallax(problem);
  std::vector<double> steep;
  // Steepness from the first observing keyframe.
  std::vector<char> seen(problem.points.size(), 0);
  for (const BundleObservation& o : problem.observations) {
    if (seen[o.point]) continue;
    seen[o.point] = 1;
    if (parallax[o.point] < min_parallax) continue;
    const Eigen::Vector3d& p = problem.points[o.point];
    const Eigen::Vector3d& c = problem.poses[o.pose];
    const double horizontal = std::hypot(p.x() - c.x(), p.y() - c.y());
    if (p.z() < 0 && std::atan2(-p.z(), horizontal) > min_depression) steep.push_back(-p.z());
  }
  if (steep.size() < 20) return 0.0;
  const double level = floor_depth(steep);
  if (!(level > 0)) return 0.0;
  if (floor_points) {
    *floor_points = 0;
    for (double z : steep) *floor_points += std::abs(z / level - 1.0) < 0.04;
  }
  return camera_height_m / level;
}

std::vector<int> find_floor_points(const BundleProblem& problem, const FloorPointOptions& options) {
  options.check();
  const std::size_t n = problem.points.size();
  // Per point: how many of its observations look down steeply enough, of how many, and the first pose that
  // saw it. (Counts, not lists: a long capture has millions of points.)
  const double max_sine = -std::sin(options.min_depression_deg * M_PI / 180.0);
  std::vector<int> steep(n, 0), seen(n, 0);
  std::vector<int> first_pose(n, static_cast<int>(problem.poses.size()));
  for (const BundleObservation& o : problem.observations) {
    const std::size_t q = static_cast<std::size_t>(o.point);
    steep[q] += static_cast<double>(o.bearing_f.z()) < max_sine;
    ++seen[q];
    first_pose[q] = std::min(first_pose[q], o.pose);
  }
  struct Candidate {
    int first_pose, point;
  };
  std::vector<Candidate> candidates;
  for (std::size_t q = 0; q < n; ++q)
    // The median observation (the upper one of an even count) is steep: more than half of them are.
    if (seen[q] > 0 && problem.points[q].z() < 0 && 2 * steep[q] > seen[q])
      candidates.push_back({first_pose[q], static_cast<int>(q)});
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.first_pose < b.first_pose; });
  // The local level: floor_depth() of the candidates first seen within neighbour_poses (at least 10 of
  // them; else no level, no floor there).
  std::vector<int> floor;
  std::size_t lo = 0, hi = 0;
  std::vector<double> depths;
  for (std::size_t g = 0; g < candidates.size();) {
    // The candidates first seen by one pose share a level.
    const int pose = candidates[g].first_pose;
    std::size_t group_end = g;
    while (group_end < candidates.size() && candidates[group_end].first_pose == pose) ++group_end;
    while (lo < candidates.size() && candidates[lo].first_pose < pose - options.neighbour_poses) ++lo;
    while (hi < candidates.size() && candidates[hi].first_pose <= pose + options.neighbour_poses) ++hi;
    if (hi - lo >= 10) {
      depths.clear();
      for (std::size_t k = lo; k < hi; ++k)
        depths.push_back(-problem.points[static_cast<std::size_t>(candidates[k].point)].z());
      const double level = floor_depth(depths);
      for (std::size_t k = g; k < group_end; ++k) {
        const double depth = -problem.points[static_cast<std::size_t>(candidates[k].point)].z();
        if (std::abs(depth / level - 1.0) <= options.max_level_deviation)
          floor.push_back(candidates[k].point);
      }
    }
    g = group_end;
  }
  std::sort(floor.begin(), floor.end());
  return floor;
}

FloorStep floor_step(const FloorStepInput& input, double min_depression, double min_motion) {
  FloorStep out;
  const double min_sin = std::sin(min_depression);
  const Eigen::Matrix3d world_from_a = Eigen::AngleAxisd(input.heading_a, Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Matrix3d world_from_b = Eigen::AngleAxisd(input.heading_b, Eigen::Vector3d::UnitZ()).matrix();
  std::vector<double> lengths;
  const std::vector<Eigen::Vector3d>&bearings_a = *input.bearings_a, &bearings_b = *input.bearings_b;
  for (std::size_t q = 0; q < bearings_a.size() && q < bearings_b.size(); ++q) {
    const Eigen::Vector3d& ca = bearings_a[q];
    const Eigen::Vector3d& cb = bearings_b[q];
    if (ca.z() > -min_sin || cb.z() > -min_sin) continue;
    if (std::atan2(ca.cross(cb).norm(), ca.dot(cb)) < min_motion) continue;
    // The floor point from each centre: level * (horizontal part) / (depth share) of the bearing.
    const Eigen::Vector3d a = world_from_a * ca, b = world_from_b * cb;
    const Eigen::Vector2d step = input.level * (a.head<2>() / -a.z() - b.head<2>() / -b.z());
    lengths.push_back(step.dot(input.direction));
  }
  out.points = static_cast<int>(lengths.size());
  if (lengths.empty()) return out;
  out.length = median(lengths);
  out.spread = out.length > 0 ? median_absolute_deviation(lengths, out.length) / out.length
                              : std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace plenopath
