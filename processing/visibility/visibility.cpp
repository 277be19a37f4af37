// The plain-double half of processing/visibility/visibility.h: options, radial functions, events and cells.
// The CGAL half (arrangement, envelopes, per-vertex windows) is visibility_cgal.cpp.
#include "processing/visibility/visibility.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <thread>

#include "model/error.h"
#include "processing/plan/segment_grid.h"
#include "processing/util/parallel_for.h"
#include "processing/visibility/visibility_expansion.h"

namespace plenopath {

const char* to_string(EnvelopeStatus status) {
  switch (status) {
    case EnvelopeStatus::ok:
      return "ok";
    case EnvelopeStatus::on_wall:
      return "on_wall";
    case EnvelopeStatus::inside_obstacle:
      return "inside_obstacle";
    case EnvelopeStatus::outside:
      return "outside";
  }
  return "unknown";
}

void VisibilityOptions::check() const {
  auto fail = [](const std::string& what) { throw Error("visibility options: " + what); };
  if (!(snap_tolerance_m >= 0.0 && snap_tolerance_m <= 0.1)) fail("snap_tolerance_m must be in [0, 0.1] m");
  if (!(dangling_wall_thickness_m > 0.0 && dangling_wall_thickness_m <= 0.5))
    fail("dangling_wall_thickness_m must be in (0, 0.5] m");
  if (!(event_merge_distance_m >= 0.0 && event_merge_distance_m <= 0.1))
    fail("event_merge_distance_m must be in [0, 0.1] m");
  if (!(close_openings_up_to_m >= 0.0 && close_openings_up_to_m <= 50.0))
    fail("close_openings_up_to_m must be in [0, 50] m");
  if (threads < 0) fail("threads must be >= 0");
  if (fast_area_max_steps < 0) fail("fast_area_max_steps must be >= 0 (0 = automatic)");
}

std::vector<double> VisibilityIndex::radial_function(const Eigen::Vector2d& p, int samples) const {
  if (samples <= 0) throw Error("radial_function: samples must be positive");
  std::vector<double> radius(static_cast<std::size_t>(samples), 0.0);
  const Envelope e = envelope(p);
  if (e.status != EnvelopeStatus::ok) return radius;
  const std::size_t n = e.polygon.size();
  for (int k = 0; k < samples; ++k) {
    const double angle = 2.0 * M_PI * k / samples;
    const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
    double best = 0.0;
    bool found = false;
    // The envelope is star-shaped from p: the ray leaves it once; take the nearest crossing to be safe.
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d a = e.polygon[i] - p, b = e.polygon[(i + 1) % n] - p;
      const Eigen::Vector2d ab = b - a;
      const double denom = d.x() * ab.y() - d.y() * ab.x();
      if (denom == 0.0) continue;
      const double t = (a.x() * ab.y() - a.y() * ab.x()) / denom;  // along the ray
      const double u = (a.x() * d.y() - a.y() * d.x()) / denom;    // along the edge
      if (t <= 0.0 || u < -1e-12 || u > 1.0 + 1e-12) continue;
      if (!found || t < best) best = t, found = true;
    }
    radius[k] = best;
  }
  return radius;
}

namespace {

// Position along the path polyline at arc length s.
Eigen::Vector2d point_at(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& s_at,
                         double s) {
  if (points.size() == 1) return points.front();
  auto it = std::upper_bound(s_at.begin(), s_at.end(), s);
  std::size_t i = it == s_at.begin() ? 0 : static_cast<std::size_t>(it - s_at.begin()) - 1;
  i = std::min(i, points.size() - 2);
  const double len = s_at[i + 1] - s_at[i];
  const double t = len > 0.0 ? std::clamp((s - s_at[i]) / len, 0.0, 1.0) : 0.0;
  return points[i] + t * (points[i + 1] - points[i]);
}

// Gauss-Legendre with 2 and 3 nodes on [s0, s1]; the 3-node rule is exact for polynomials of degree 5,
// the 2-node one tells how far from that the integrand is. Refines by halving up to `depth` times while
// may_refine() says so.
template <typename F, typename R>
double integrate(const F& f, double s0, double s1, int depth, const R& may_refine) {
  const double half = 0.5 * (s1 - s0), mid = 0.5 * (s0 + s1);
  if (!(half > 0.0)) return 0.0;
  const double g2 = half * (f(mid - half / std::sqrt(3.0)) + f(mid + half / std::sqrt(3.0)));
  const double outer = half * std::sqrt(0.6);
  const double g3 = half * (5.0 / 9.0 * (f(mid - outer) + f(mid + outer)) + 8.0 / 9.0 * f(mid));
  if (depth <= 0 || std::abs(g3 - g2) <= 1e-7 * std::abs(g3) + 1e-12 * half || !may_refine()) return g3;
  return integrate(f, s0, mid, depth - 1, may_refine) + integrate(f, mid, s1, depth - 1, may_refine);
}

}  // namespace

double VisibilityIndex::envelope_area(const Eigen::Vector2d& p) const {
  std::vector<EnvelopeWedge> wedges;
  return std::max(0.0, area_and_wedges(p, &wedges));
}

double VisibilityIndex::area_and_wedges(const Eigen::Vector2d& p, std::vector<EnvelopeWedge>* wedges) const {
  wedges->clear();
  if (classify(p) != EnvelopeStatus::ok) return -1.0;
  if (options().area_method == AreaMethod::fast_with_exact_fallback) {
    const WallTriangulation& tri = triangulation();
    const long max_steps = options().fast_area_max_steps > 0
                               ? options().fast_area_max_steps
                               : 64 * static_cast<long>(tri.corners.size()) + 10000;
    double area = 0.0;
    if (expand_envelope(tri, p, max_steps, wedges, &area)) {
      count_areas(1, 0, 0);
      return area;
    }
    wedges->clear();
  }
  count_areas(0, 0, 1);
  return exact_envelope_area(p);
}

void VisibilityIndex::areas_of_cell(const std::vector<Eigen::Vector2d>& points,
                                    const std::vector<double>& s_at, double s_begin, double s_end,
                                    double* area_mid, double* area_mean) const {
  std::vector<EnvelopeWedge> wedges;
  const double mid_area = area_and_wedges(point_at(points, s_at, 0.5 * (s_begin + s_end)), &wedges);
  *area_mid = *area_mean = std::max(0.0, mid_area);
  if (mid_area < 0.0 || !(s_end > s_begin)) return;
  // The area elsewhere in the cell: from the middle's wedges in closed form, or (if they do not fit
  // there, or the middle fell back to the exact class) by a query of its own.
  std::size_t closed_form = 0, queries = 0;
  std::vector<EnvelopeWedge> other;
  auto area_at = [&](double s) {
    const Eigen::Vector2d q = point_at(points, s_at, s);
    double area = 0.0;
    if (!wedges.empty() && wedges_area(triangulation(), wedges, q, false, &area)) {
      ++closed_form;
      return area;
    }
    ++queries;
    const double a = area_and_wedges(q, &other);
    return a >= 0.0 ? a : mid_area;
  };
  // Refinement is cheap in closed form; a cell whose wedges keep missing stops refining (a bounded cost).
  auto may_refine = [&]() { return queries < 8; };
  double integral = 0.0;
  if (wedges.empty()) {
    integral = integrate(area_at, s_begin, s_end, 0, may_refine);  // three queries
  } else {
    // The area is smooth along each straight piece of the path; the pieces meet where the path turns.
    // (If the wedges keep missing, the rest of the cell is one piece.)
    double piece_begin = s_begin;
    const std::size_t first = std::upper_bound(s_at.begin(), s_at.end(), s_begin) - s_at.begin();
    for (std::size_t k = first; k + 1 < s_at.size() && s_at[k] < s_end && may_refine(); ++k) {
      const Eigen::Vector2d before = points[k] - points[k - 1], after = points[k + 1] - points[k];
      const bool straight =
          before.squaredNorm() > 0.0 && after.squaredNorm() > 0.0 && before.dot(after) > 0.0 &&
          std::abs(before.x() * after.y() - before.y() * after.x()) <= 1e-12 * before.norm() * after.norm();
      if (straight) continue;
      integral += integrate(area_at, piece_begin, s_at[k], 10, may_refine);
      piece_begin = s_at[k];
    }
    integral += integrate(area_at, piece_begin, s_end, 10, may_refine);
  }
  count_areas(0, closed_form, 0);
  *area_mean = integral / (s_end - s_begin);
}

VisibilityCells VisibilityIndex::cells_along_path(const CameraPath& path, Progress& progress) const {
  VisibilityCells result;
  if (path.frames.empty()) return result;
  require_placed(path, "visibility");
  std::vector<Eigen::Vector2d> points;
  for (const auto& f : path.frames) points.push_back(f.position());
  const std::vector<double> s_at = path.arc_lengths();
  const double total = s_at.back();

  // Path segments in a grid; windows and walls are walked through it.
  std::vector<Segment2> path_segments;
  std::vector<int> path_frame;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if ((points[i + 1] - points[i]).norm() <= 0.0) continue;
    path_segments.push_back({points[i], points[i + 1]});
    path_frame.push_back(static_cast<int>(i));
  }
  const auto timing_start = std::chrono::steady_clock::now();
  // Progress: the windows take about 60 % of the time, the cells' envelopes the rest.
  SubProgress windows_progress(progress, 0.0, 0.6, "visibility windows");
  const std::vector<CriticalLine> windows = vertex_windows(windows_progress);
  const bool timing = std::getenv("PLENOPATH_VISIBILITY_TIMING") != nullptr;
  auto lap = [&](const char* what) {
    if (timing)
      std::fprintf(stderr, "visibility timing: %s %.3f s\n", what,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - timing_start).count());
  };
  lap("windows");
  if (!path_segments.empty()) {
    const SegmentGrid grid(path_segments);
    std::vector<VisibilityEvent> raw;
    auto add_crossings = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      for (int k : grid.along(a, b)) {
        const Segment2& ps = path_segments[k];
        double t = 0.0;
        if (!intersect_segments(ps.a, ps.b, a, b, &t, nullptr)) continue;
        const int i = path_frame[k];
        raw.push_back({i, s_at[i] + t * (s_at[i + 1] - s_at[i])});
      }
    };
    for (const auto& w : windows) add_crossings(w.a, w.b);
    for (const auto& wall : effective_segments()) add_crossings(wall.a, wall.b);
    // (s, frame): a total order, so the result does not depend on the threads' order of the windows.
    std::sort(raw.begin(), raw.end(), [](const VisibilityEvent& l, const VisibilityEvent& r) {
      return l.s != r.s ? l.s < r.s : l.frame < r.frame;
    });
    for (const auto& e : raw) {
      if (!result.events.empty() && e.s - result.events.back().s <= options().event_merge_distance_m)
        continue;
      result.events.push_back(e);
    }
  }

  lap("crossings");
  // Critical lines for display: all of them, or an even subsample when there are too many.
  const std::size_t cap = options().max_critical_lines;
  if (windows.size() <= cap) {
    result.critical_lines = windows;
  } else if (cap > 0) {
    for (std::size_t k = 0; k < cap; ++k) result.critical_lines.push_back(windows[k * windows.size() / cap]);
  }

  // Cells between consecutive events.
  std::vector<double> bounds = {0.0};
  for (const auto& e : result.events)
    if (e.s > bounds.back() + options().event_merge_distance_m &&
        e.s < total - options().event_merge_distance_m)
      bounds.push_back(e.s);
  bounds.push_back(total);
  const bool fast = options().area_method == AreaMethod::fast_with_exact_fallback;
  const std::size_t cell_count = bounds.size() - 1;
  auto area_at = [&](double s) -> double {
    const Eigen::Vector2d q = point_at(points, s_at, s);
    return classify(q) == EnvelopeStatus::ok ? exact_envelope_area(q) : -1.0;
  };
  // Exact method: envelope areas at each cell's middle (and at the events for Simpson's rule). Fast
  // method: one task per cell (its middle's expansion, then its mean area from the wedges).
  std::vector<double> queries_s;
  if (!fast) {
    for (std::size_t c = 0; c < cell_count; ++c) queries_s.push_back(0.5 * (bounds[c] + bounds[c + 1]));
    if (options().area_mean_simpson) queries_s.insert(queries_s.end(), bounds.begin(), bounds.end());
  }
  std::vector<double> query_area(queries_s.size(), -1.0);
  std::vector<double> cell_mid(fast ? cell_count : 0, 0.0), cell_mean(fast ? cell_count : 0, 0.0);
  const std::size_t tasks = fast ? cell_count : queries_s.size();
  if (options().cell_areas) {
    const int threads = std::min(resolve_thread_count(options().threads), static_cast<int>(tasks / 16) + 1);
    parallel_for_each(static_cast<int>(tasks), threads, [&](int i) {
      progress.checkpoint(0.6 + 0.4 * static_cast<double>(i) / tasks, i == 0 ? "visibility cells" : "");
      if (fast) {
        areas_of_cell(points, s_at, bounds[i], bounds[i + 1], &cell_mid[i], &cell_mean[i]);
      } else {
        query_area[i] = area_at(queries_s[i]);
        if (query_area[i] >= 0.0) count_areas(0, 0, 1);
      }
    });
  }
  for (std::size_t c = 0; c + 1 < bounds.size(); ++c) {
    VisibilityCell cell;
    cell.s_begin = bounds[c];
    cell.s_end = bounds[c + 1];
    cell.length = cell.s_end - cell.s_begin;
    const double mid_area = fast ? cell_mid[c] : query_area[c];
    cell.area_mid = std::max(0.0, mid_area);
    cell.area_mean = fast ? cell_mean[c] : cell.area_mid;
    if (!fast && options().area_mean_simpson && mid_area >= 0.0) {
      const double b0 = query_area[cell_count + c], b1 = query_area[cell_count + c + 1];
      const double a0 = b0 >= 0.0 ? b0 : mid_area;
      const double a1 = b1 >= 0.0 ? b1 : mid_area;
      cell.area_mean = (a0 + 4.0 * mid_area + a1) / 6.0;
    }
    // Frames inside [s_begin, s_end) (the last cell includes its end).
    const bool last = c + 2 == bounds.size();
    int first = static_cast<int>(std::lower_bound(s_at.begin(), s_at.end(), cell.s_begin) - s_at.begin());
    int end = last ? static_cast<int>(s_at.size())
                   : static_cast<int>(std::lower_bound(s_at.begin(), s_at.end(), cell.s_end) - s_at.begin());
    if (end > first) {
      cell.first_frame = first;
      cell.last_frame = end - 1;
    } else {
      const double mid = 0.5 * (cell.s_begin + cell.s_end);
      int nearest = std::clamp(first, 0, static_cast<int>(s_at.size()) - 1);
      if (nearest > 0 && std::abs(s_at[nearest - 1] - mid) < std::abs(s_at[nearest] - mid)) --nearest;
      cell.first_frame = cell.last_frame = nearest;
    }
    result.cells.push_back(cell);
  }
  lap("cells");
  if (timing) std::fprintf(stderr, "visibility timing: %zu windows\n", windows.size());
  return result;
}

}  // namespace plenopath
