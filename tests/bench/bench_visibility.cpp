// Visibility speed on a 1 000-segment plan: envelope query median for Triangular_expansion_visibility_2
// and Rotational_sweep_visibility_2 (target <= 300 us), and events + cells along a 10 000-frame path
// (target <= 2 s). Prints one JSON object.
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <iostream>
#include <random>

#include "processing/visibility.h"

using namespace plenopath;
using Clock = std::chrono::steady_clock;

namespace {

void add_wall(FloorPlan* plan, Eigen::Vector2d a, Eigen::Vector2d b) {
  PlanSegment s;
  s.a = a;
  s.b = b;
  s.layer = "WALLS";
  s.occluder = true;
  plan->segments.push_back(s);
}

// A 100 m x 60 m hall with 25 x 10 rotated square pillars (4 segments each) between corridors at
// y = 6, 12, ..., 54: 1 004 segments.
FloorPlan hall(std::mt19937* rng) {
  FloorPlan plan;
  const std::vector<Eigen::Vector2d> outer = {{0, 0}, {100, 0}, {100, 60}, {0, 60}};
  for (int i = 0; i < 4; ++i) add_wall(&plan, outer[i], outer[(i + 1) % 4]);
  std::uniform_real_distribution<double> angle(0.0, M_PI / 2), size(0.6, 1.0), jitter(-0.8, 0.8);
  for (int i = 0; i < 25; ++i)
    for (int j = 0; j < 10; ++j) {
      const Eigen::Vector2d c(2.0 + 4.0 * i + jitter(*rng), 3.0 + 6.0 * j + jitter(*rng) * 0.5);
      const Eigen::Rotation2Dd r(angle(*rng));
      const double h = size(*rng) / 2;
      const Eigen::Vector2d p[4] = {c + r * Eigen::Vector2d(-h, -h), c + r * Eigen::Vector2d(h, -h),
                                    c + r * Eigen::Vector2d(h, h), c + r * Eigen::Vector2d(-h, h)};
      for (int k = 0; k < 4; ++k) add_wall(&plan, p[k], p[(k + 1) % 4]);
    }
  return plan;
}

// An office floor, 120 m x 40 m: a corridor (y in [18, 22]) between two rows of 40 rooms 3 m wide, each
// with a 1 m door, two pillars and a dangling closet wall: 962 segments.
FloorPlan offices(std::mt19937* rng) {
  FloorPlan plan;
  const std::vector<Eigen::Vector2d> outer = {{0, 0}, {120, 0}, {120, 40}, {0, 40}};
  for (int i = 0; i < 4; ++i) add_wall(&plan, outer[i], outer[(i + 1) % 4]);
  std::uniform_real_distribution<double> angle(0.0, M_PI / 2), jitter(-0.3, 0.3);
  for (int side = 0; side < 2; ++side) {
    const double wall_y = side == 0 ? 18.0 : 22.0, back_y = side == 0 ? 0.0 : 40.0;
    for (int r = 0; r < 40; ++r) {
      const double x0 = 3.0 * r, x1 = x0 + 3.0;
      add_wall(&plan, {x0, wall_y}, {x0 + 1.0, wall_y});  // door from x0+1 to x0+2
      add_wall(&plan, {x0 + 2.0, wall_y}, {x1, wall_y});
      if (r > 0) add_wall(&plan, {x0, wall_y}, {x0, back_y});
      const double ymid = 0.5 * (wall_y + back_y);
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector2d c(x0 + 1.0 + k + jitter(*rng), ymid + (k ? 5.0 : -5.0) + jitter(*rng));
        const Eigen::Rotation2Dd rot(angle(*rng));
        const double h = 0.2;
        const Eigen::Vector2d p[4] = {c + rot * Eigen::Vector2d(-h, -h), c + rot * Eigen::Vector2d(h, -h),
                                      c + rot * Eigen::Vector2d(h, h), c + rot * Eigen::Vector2d(-h, h)};
        for (int q = 0; q < 4; ++q) add_wall(&plan, p[q], p[(q + 1) % 4]);
      }
      add_wall(&plan, {x1, ymid}, {x1 - 1.2, ymid});  // closet wall from the partition, dangling
    }
  }
  return plan;
}

double thread_cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e6 + ts.tv_nsec * 1e-3;
}

bool same_events(const VisibilityCells& a, const VisibilityCells& b) {
  if (a.events.size() != b.events.size()) return false;
  for (std::size_t i = 0; i < a.events.size(); ++i)
    if (std::abs(a.events[i].s - b.events[i].s) > 1e-9) return false;
  return true;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::vector<double> time_queries(const VisibilityIndex& index, const std::vector<Eigen::Vector2d>& points, double* area_sum) {
  index.envelope(points.front());  // per-thread setup outside the timing
  std::vector<double> us;
  *area_sum = 0.0;
  for (const auto& p : points) {
    const double t0 = thread_cpu_us();
    const Envelope e = index.envelope(p);
    us.push_back(thread_cpu_us() - t0);
    *area_sum += e.area;
  }
  return us;
}


CameraPath polyline_path(const std::vector<Eigen::Vector2d>& corners, int frames) {
  std::vector<double> cum = {0.0};
  for (std::size_t i = 1; i < corners.size(); ++i) cum.push_back(cum.back() + (corners[i] - corners[i - 1]).norm());
  CameraPath path;
  for (int f = 0; f < frames; ++f) {
    const double s = cum.back() * f / (frames - 1);
    std::size_t i = std::upper_bound(cum.begin(), cum.end(), s) - cum.begin();
    i = std::clamp<std::size_t>(i, 1, corners.size() - 1);
    const double t = (s - cum[i - 1]) / (cum[i] - cum[i - 1]);
    const Eigen::Vector2d p = corners[i - 1] + t * (corners[i] - corners[i - 1]);
    PathFrame frame;
    frame.index = f;
    frame.x = p.x();
    frame.y = p.y();
    path.frames.push_back(frame);
  }
  return path;
}

std::vector<Eigen::Vector2d> free_points(const VisibilityIndex& index, std::mt19937* rng, Eigen::Vector2d hi, int n) {
  std::uniform_real_distribution<double> ux(0.1, hi.x() - 0.1), uy(0.1, hi.y() - 0.1);
  std::vector<Eigen::Vector2d> points;
  while (static_cast<int>(points.size()) < n) {
    const Eigen::Vector2d p(ux(*rng), uy(*rng));
    if (index.classify(p) == EnvelopeStatus::ok) points.push_back(p);
  }
  return points;
}

}  // namespace

int main() {
  std::mt19937 rng(1);
  const FloorPlan plan = offices(&rng);
  VisibilityOptions tri_options;
  tri_options.algorithm = VisibilityAlgorithm::triangular_expansion;
  auto t0 = Clock::now();
  const VisibilityIndex tri(plan, tri_options);
  const double build_s = std::chrono::duration<double>(Clock::now() - t0).count();
  VisibilityOptions sweep_options;
  sweep_options.algorithm = VisibilityAlgorithm::rotational_sweep;
  const VisibilityIndex sweep(plan, sweep_options);

  const auto points = free_points(tri, &rng, {120, 40}, 300);
  double tri_area = 0.0, sweep_area = 0.0, tri_few_area = 0.0;
  const double tri_us = median(time_queries(tri, points, &tri_area));
  const std::vector<Eigen::Vector2d> few(points.begin(), points.begin() + 60);
  const double sweep_us = median(time_queries(sweep, few, &sweep_area));
  time_queries(tri, few, &tri_few_area);

  // Corridor points see into every room: the heaviest queries along the benchmark path.
  std::vector<Eigen::Vector2d> corridor;
  for (int k = 0; k < 40; ++k) corridor.push_back({1.7 + 2.9 * k, 20.3});
  double corridor_area = 0.0;
  const double corridor_us = median(time_queries(tri, corridor, &corridor_area));
  std::vector<double> area_only_us;
  double area_only_sum = 0.0;
  for (const auto& p : corridor) {
    const double c0 = thread_cpu_us();
    area_only_sum += tri.envelope_area(p);
    area_only_us.push_back(thread_cpu_us() - c0);
  }
  const double corridor_area_only_us = median(area_only_us);

  // Stress case: an open hall with 250 free-standing pillars (many holes: the triangular expansion's
  // query time grows with them).
  const FloorPlan hall_plan = hall(&rng);
  const VisibilityIndex hall_index(hall_plan);
  double hall_area = 0.0;
  const double hall_us = median(time_queries(hall_index, free_points(hall_index, &rng, {100, 60}, 200), &hall_area));

  // 10 000 frames: along the corridor and back, then into and out of a room.
  const CameraPath path = polyline_path({{1, 20.5}, {119, 20.5}, {119, 19.5}, {61.5, 19.5}, {61.5, 12}, {61.5, 19.5},
                                         {1, 19.5}}, 10000);
  VisibilityOptions events_only_options;
  events_only_options.cell_areas = false;
  const VisibilityIndex events_only(plan, events_only_options);
  t0 = Clock::now();
  std::clock_t c0 = std::clock();
  const VisibilityCells events_only_cells = events_only.cells_along_path(path);
  const double events_only_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const double events_only_cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  t0 = Clock::now();
  c0 = std::clock();
  const VisibilityCells cells = tri.cells_along_path(path);
  const double events_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const double events_cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;

  std::cout << "{\"benchmark\": \"visibility\", \"segments\": " << plan.segments.size()
            << ", \"arrangement_vertices\": " << tri.vertices().size() << ", \"build_s\": " << build_s
            << ", \"envelope_median_cpu_us\": {\"triangular_expansion\": " << tri_us
            << ", \"rotational_sweep\": " << sweep_us << "}"
            << ", \"winner\": \"" << (tri_us <= sweep_us ? "triangular_expansion" : "rotational_sweep") << "\""
            << ", \"speedup\": " << std::max(tri_us, sweep_us) / std::min(tri_us, sweep_us)
            << ", \"areas_agree\": " << (std::abs(tri_few_area - sweep_area) <= 1e-6 * tri_few_area ? "true" : "false")
            << ", \"envelope_target_us\": 300, \"envelope_target_met\": " << (tri_us <= 300 ? "true" : "false")
            << ", \"corridor_envelope_median_cpu_us\": " << corridor_us
            << ", \"corridor_area_only_median_cpu_us\": " << corridor_area_only_us
            << ", \"area_only_agrees\": " << (std::abs(area_only_sum - corridor_area) <= 1e-6 * corridor_area ? "true" : "false")
            << ", \"pillar_hall\": {\"segments\": " << hall_plan.segments.size()
            << ", \"envelope_median_cpu_us\": " << hall_us << "}"
            << ", \"path_frames\": " << path.size() << ", \"path_length_m\": " << path.length()
            << ", \"events\": " << cells.events.size() << ", \"cells\": " << cells.cells.size()
            << ", \"critical_lines\": " << cells.critical_lines.size() << ", \"events_wall_s\": " << events_s
            << ", \"events_cpu_s\": " << events_cpu_s << ", \"events_without_areas_wall_s\": " << events_only_s
            << ", \"events_without_areas_cpu_s\": " << events_only_cpu_s
            << ", \"same_events\": " << (same_events(events_only_cells, cells) ? "true" : "false")
            << ", \"events_target_s\": 2, \"events_target_met_with_areas\": " << (events_s <= 2.0 ? "true" : "false")
            << ", \"events_target_met_without_areas\": " << (events_only_s <= 2.0 ? "true" : "false") << "}\n";
  return 0;
}
