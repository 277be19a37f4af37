// The plain-double half of processing/visibility.h: options, radial functions, events and cells. The CGAL
// half (arrangement, envelopes, per-vertex windows) is visibility_cgal.cpp.
#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>

#include "model/error.h"
#include "processing/segment_grid.h"
#include "processing/visibility.h"

namespace plenopath {

const char* to_string(EnvelopeStatus status) {
  switch (status) {
    case EnvelopeStatus::ok: return "ok";
    case EnvelopeStatus::on_wall: return "on_wall";
    case EnvelopeStatus::inside_obstacle: return "inside_obstacle";
    case EnvelopeStatus::outside: return "outside";
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
  if (threads < 0) fail("threads must be >= 0");
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
Eigen::Vector2d point_at(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& s_at, double s) {
  if (points.size() == 1) return points.front();
  auto it = std::upper_bound(s_at.begin(), s_at.end(), s);
  std::size_t i = it == s_at.begin() ? 0 : static_cast<std::size_t>(it - s_at.begin()) - 1;
  i = std::min(i, points.size() - 2);
  const double len = s_at[i + 1] - s_at[i];
  const double t = len > 0.0 ? std::clamp((s - s_at[i]) / len, 0.0, 1.0) : 0.0;
  return points[i] + t * (points[i + 1] - points[i]);
}

}  // namespace

VisibilityCells VisibilityIndex::cells_along_path(const CameraPath& path,
                                                  const std::function<void(double)>& progress) const {
  VisibilityCells result;
  if (path.frames.empty()) return result;
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
  const std::vector<CriticalLine> windows =
      vertex_windows(progress ? std::function<void(double)>([&](double f) { progress(0.6 * f); })
                              : std::function<void(double)>());
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
      if (!result.events.empty() && e.s - result.events.back().s <= options().event_merge_distance_m) continue;
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
    if (e.s > bounds.back() + options().event_merge_distance_m && e.s < total - options().event_merge_distance_m)
      bounds.push_back(e.s);
  bounds.push_back(total);
  auto area_at = [&](double s) -> double {
    const Eigen::Vector2d q = point_at(points, s_at, s);
    return classify(q) == EnvelopeStatus::ok ? envelope_area(q) : -1.0;
  };
  // Envelope areas: at each cell's middle (and at the events for Simpson's rule), on several threads.
  std::vector<double> queries_s;
  for (std::size_t c = 0; c + 1 < bounds.size(); ++c) queries_s.push_back(0.5 * (bounds[c] + bounds[c + 1]));
  if (options().area_mean_simpson) queries_s.insert(queries_s.end(), bounds.begin(), bounds.end());
  std::vector<double> query_area(queries_s.size(), -1.0);
  if (options().cell_areas) {
    int threads = options().threads > 0 ? options().threads
                                        : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::max(1, std::min<int>(threads, static_cast<int>(queries_s.size() / 16) + 1));
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto work = [&]() {
      try {
        for (std::size_t i = next++; i < queries_s.size(); i = next++) {
          if (progress) progress(0.6 + 0.4 * static_cast<double>(i) / queries_s.size());
          query_area[i] = area_at(queries_s[i]);
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = queries_s.size();
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& th : pool) th.join();
    if (failure) std::rethrow_exception(failure);
  }
  const std::size_t cell_count = bounds.size() - 1;
  for (std::size_t c = 0; c + 1 < bounds.size(); ++c) {
    VisibilityCell cell;
    cell.s_begin = bounds[c];
    cell.s_end = bounds[c + 1];
    cell.length = cell.s_end - cell.s_begin;
    const double mid_area = query_area[c];
    cell.area_mid = std::max(0.0, mid_area);
    cell.area_mean = cell.area_mid;
    if (options().area_mean_simpson && mid_area >= 0.0) {
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
