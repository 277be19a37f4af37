// Visibility speed on a 1 000-segment plan: envelope query median for Triangular_expansion_visibility_2
// and Rotational_sweep_visibility_2 (target <= 300 us), the fast area path (triangular expansion in doubles,
// exact fallback) against the exact class, and events + cells with areas along a 10 000-frame path
// (target <= 2 s), with how many expansions per cell and how far the fast areas are from the exact ones.
// `--with-exact` also times cells_along_path with AreaMethod::exact (the previous method, ~7 s CPU).
// Prints one JSON object.
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <iostream>
#include <random>

#include "processing/visibility/visibility.h"
#include "tests/processing/plan/plan_oracle.h"

using namespace plenopath;
using Clock = std::chrono::steady_clock;

namespace {

using test::add_wall;

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

std::vector<double> time_queries(const VisibilityIndex& index, const std::vector<Eigen::Vector2d>& points,
                                 double* area_sum) {
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
  for (std::size_t i = 1; i < corners.size(); ++i)
    cum.push_back(cum.back() + (corners[i] - corners[i - 1]).norm());
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

std::vector<Eigen::Vector2d> free_points(const VisibilityIndex& index, std::mt19937* rng, Eigen::Vector2d hi,
                                         int n) {
  std::uniform_real_distribution<double> ux(0.1, hi.x() - 0.1), uy(0.1, hi.y() - 0.1);
  std::vector<Eigen::Vector2d> points;
  while (static_cast<int>(points.size()) < n) {
    const Eigen::Vector2d p(ux(*rng), uy(*rng));
    if (index.classify(p) == EnvelopeStatus::ok) points.push_back(p);
  }
  return points;
}

}  // namespace

int main(int argc, char** argv) {
  const bool with_exact = argc > 1 && std::strcmp(argv[1], "--with-exact") == 0;
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
  VisibilityOptions exact_options;
  exact_options.area_method = AreaMethod::exact;
  const VisibilityIndex exact(plan, exact_options);
  std::vector<double> exact_area_us;
  double exact_area_sum = 0.0;
  exact.envelope_area(corridor.front());
  for (const auto& p : corridor) {
    const double c0 = thread_cpu_us();
    exact_area_sum += exact.envelope_area(p);
    exact_area_us.push_back(thread_cpu_us() - c0);
  }
  const double corridor_exact_area_us = median(exact_area_us);
  // Fast against exact areas at the random free points.
  double fast_max_rel = 0.0;
  std::vector<double> fast_us;
  for (const auto& p : points) {
    const double c0 = thread_cpu_us();
    const double a = tri.envelope_area(p);
    fast_us.push_back(thread_cpu_us() - c0);
    const double b = exact.envelope_area(p);
    fast_max_rel = std::max(fast_max_rel, std::abs(a - b) / b);
  }

  // Stress case: an open hall with 250 free-standing pillars (many holes: the triangular expansion's
  // query time grows with them).
  const FloorPlan hall_plan = hall(&rng);
  const VisibilityIndex hall_index(hall_plan);
  double hall_area = 0.0;
  const auto hall_points = free_points(hall_index, &rng, {100, 60}, 200);
  const double hall_us = median(time_queries(hall_index, hall_points, &hall_area));
  std::vector<double> hall_fast_us;
  for (const auto& p : hall_points) {
    const double c0 = thread_cpu_us();
    hall_index.envelope_area(p);
    hall_fast_us.push_back(thread_cpu_us() - c0);
  }
  // A 2 000-frame wobbly walk across the hall: ~100 000 windows, ~13 000 cells.
  CameraPath hall_path;
  for (int f = 0; f < 2000; ++f) {
    PathFrame frame;
    frame.index = f;
    frame.x = 1.0 + 98.0 * f / 1999;
    frame.y = 6.0 + 0.5 * std::sin(f * 0.01);
    hall_path.frames.push_back(frame);
  }
  auto h0 = Clock::now();
  std::clock_t hc0 = std::clock();
  const VisibilityCells hall_cells = hall_index.cells_along_path(hall_path);
  const double hall_cells_s = std::chrono::duration<double>(Clock::now() - h0).count();
  const double hall_cells_cpu_s = static_cast<double>(std::clock() - hc0) / CLOCKS_PER_SEC;

  // 10 000 frames: along the corridor and back, then into and out of a room.
  const CameraPath path = polyline_path(
      {{1, 20.5}, {119, 20.5}, {119, 19.5}, {61.5, 19.5}, {61.5, 12}, {61.5, 19.5}, {1, 19.5}}, 10000);
  VisibilityOptions events_only_options;
  events_only_options.cell_areas = false;
  const VisibilityIndex events_only(plan, events_only_options);
  t0 = Clock::now();
  std::clock_t c0 = std::clock();
  const VisibilityCells events_only_cells = events_only.cells_along_path(path);
  const double events_only_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const double events_only_cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  const EnvelopeAreaCounts counts_before = tri.area_counts();
  t0 = Clock::now();
  c0 = std::clock();
  const VisibilityCells cells = tri.cells_along_path(path);
  const double events_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const double events_cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  const EnvelopeAreaCounts counts_after = tri.area_counts();
  const std::size_t expansions = counts_after.fast - counts_before.fast;
  const std::size_t fallbacks = counts_after.exact - counts_before.exact;
  const std::size_t closed_forms = counts_after.closed_form - counts_before.closed_form;
  const bool repeatable = tri.cells_along_path(path) == cells;
  // The cells' areas against the exact class: area_mid at every 10th cell; area_mean at every 100th
  // against Simpson's rule over 16 exact envelopes.
  const std::vector<double> s_at = path.arc_lengths();
  auto point_at = [&](double s) {
    std::size_t i = std::upper_bound(s_at.begin(), s_at.end(), s) - s_at.begin();
    i = std::clamp<std::size_t>(i, 1, s_at.size() - 1);
    const double t = (s - s_at[i - 1]) / std::max(1e-300, s_at[i] - s_at[i - 1]);
    return Eigen::Vector2d(path.frames[i - 1].position() +
                           t * (path.frames[i].position() - path.frames[i - 1].position()));
  };
  double mid_max_rel = 0.0, mean_max_rel = 0.0, mean_vs_mid_max_rel = 0.0;
  for (std::size_t c = 0; c < cells.cells.size(); c += 10) {
    const auto& cell = cells.cells[c];
    const double truth = exact.envelope_area(point_at(0.5 * (cell.s_begin + cell.s_end)));
    if (truth > 0) mid_max_rel = std::max(mid_max_rel, std::abs(cell.area_mid - truth) / truth);
    if (cell.area_mid > 0)
      mean_vs_mid_max_rel =
          std::max(mean_vs_mid_max_rel, std::abs(cell.area_mean - cell.area_mid) / cell.area_mid);
    if (c % 100 != 0) continue;
    double simpson = 0.0;
    for (int k = 0; k <= 16; ++k)
      simpson += (k == 0 || k == 16 ? 1 : (k % 2 ? 4 : 2)) *
                 exact.envelope_area(point_at(cell.s_begin + (cell.s_end - cell.s_begin) * k / 16.0));
    simpson /= 48.0;
    if (simpson > 0) mean_max_rel = std::max(mean_max_rel, std::abs(cell.area_mean - simpson) / simpson);
  }
  double exact_s = 0.0, exact_cpu_s = 0.0;
  if (with_exact) {
    t0 = Clock::now();
    c0 = std::clock();
    const VisibilityCells exact_cells = exact.cells_along_path(path);
    exact_s = std::chrono::duration<double>(Clock::now() - t0).count();
    exact_cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  }

  std::cout << "{\"benchmark\": \"visibility\", \"segments\": " << plan.segments.size()
            << ", \"arrangement_vertices\": " << tri.vertices().size() << ", \"build_s\": " << build_s
            << ", \"envelope_median_cpu_us\": {\"triangular_expansion\": " << tri_us
            << ", \"rotational_sweep\": " << sweep_us << "}"
            << ", \"winner\": \"" << (tri_us <= sweep_us ? "triangular_expansion" : "rotational_sweep")
            << "\""
            << ", \"speedup\": " << std::max(tri_us, sweep_us) / std::min(tri_us, sweep_us)
            << ", \"areas_agree\": "
            << (std::abs(tri_few_area - sweep_area) <= 1e-6 * tri_few_area ? "true" : "false")
            << ", \"envelope_target_us\": 300, \"envelope_target_met\": "
            << (tri_us <= 300 ? "true" : "false") << ", \"corridor_envelope_median_cpu_us\": " << corridor_us
            << ", \"corridor_area_only_median_cpu_us\": " << corridor_area_only_us
            << ", \"corridor_exact_area_median_cpu_us\": " << corridor_exact_area_us
            << ", \"area_only_agrees\": "
            << (std::abs(area_only_sum - corridor_area) <= 1e-6 * corridor_area &&
                        std::abs(exact_area_sum - corridor_area) <= 1e-6 * corridor_area
                    ? "true"
                    : "false")
            << ", \"fast_area_median_cpu_us\": " << median(fast_us)
            << ", \"fast_area_max_rel_diff_vs_exact\": " << fast_max_rel
            << ", \"pillar_hall\": {\"segments\": " << hall_plan.segments.size()
            << ", \"envelope_median_cpu_us\": " << hall_us
            << ", \"fast_area_median_cpu_us\": " << median(hall_fast_us)
            << ", \"path_frames\": " << hall_path.size() << ", \"cells\": " << hall_cells.cells.size()
            << ", \"cells_wall_s\": " << hall_cells_s << ", \"cells_cpu_s\": " << hall_cells_cpu_s
            << ", \"exact_fallbacks\": " << hall_index.area_counts().exact << "}"
            << ", \"path_frames\": " << path.size() << ", \"path_length_m\": " << path.length()
            << ", \"events\": " << cells.events.size() << ", \"cells\": " << cells.cells.size()
            << ", \"critical_lines\": " << cells.critical_lines.size() << ", \"events_wall_s\": " << events_s
            << ", \"events_cpu_s\": " << events_cpu_s << ", \"expansions\": " << expansions
            << ", \"exact_fallbacks\": " << fallbacks << ", \"closed_form_areas\": " << closed_forms
            << ", \"area_mid_max_rel_diff_vs_exact\": " << mid_max_rel
            << ", \"area_mean_max_rel_diff_vs_exact_simpson16\": " << mean_max_rel
            << ", \"area_mean_vs_mid_max_rel\": " << mean_vs_mid_max_rel
            << ", \"repeatable\": " << (repeatable ? "true" : "false")
            << ", \"events_without_areas_wall_s\": " << events_only_s
            << ", \"events_without_areas_cpu_s\": " << events_only_cpu_s
            << ", \"same_events\": " << (same_events(events_only_cells, cells) ? "true" : "false")
            << ", \"events_target_s\": 2, \"events_target_met_with_areas\": "
            << (events_s <= 2.0 ? "true" : "false")
            << ", \"events_target_met_without_areas\": " << (events_only_s <= 2.0 ? "true" : "false");
  if (with_exact)
    std::cout << ", \"exact_method_wall_s\": " << exact_s << ", \"exact_method_cpu_s\": " << exact_cpu_s;
  std::cout << "}\n";
  return 0;
}
