// The plain-double half of processing/visibility.h: options, radial functions, events and cells. The CGAL
// half (arrangement, envelopes, per-vertex windows) is visibility_cgal.cpp.
#include <algorithm>
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

VisibilityCells VisibilityIndex::cells_along_path(const CameraPath& path) const {
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
  const std::vector<CriticalLine> windows = vertex_windows();
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
    std::sort(raw.begin(), raw.end(), [](const VisibilityEvent& l, const VisibilityEvent& r) { return l.s < r.s; });
    for (const auto& e : raw) {
      if (!result.events.empty() && e.s - result.events.back().s <= options().event_merge_distance_m) continue;
      result.events.push_back(e);
    }
  }

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
    const Envelope e = envelope(point_at(points, s_at, s));
    return e.status == EnvelopeStatus::ok ? e.area : -1.0;
  };
  std::vector<double> bound_area;
  if (options().area_mean_simpson)
    for (double b : bounds) bound_area.push_back(area_at(b));
  for (std::size_t c = 0; c + 1 < bounds.size(); ++c) {
    VisibilityCell cell;
    cell.s_begin = bounds[c];
    cell.s_end = bounds[c + 1];
    cell.length = cell.s_end - cell.s_begin;
    const double mid_area = area_at(0.5 * (cell.s_begin + cell.s_end));
    cell.area_mid = std::max(0.0, mid_area);
    cell.area_mean = cell.area_mid;
    if (options().area_mean_simpson && mid_area >= 0.0) {
      const double a0 = bound_area[c] >= 0.0 ? bound_area[c] : mid_area;
      const double a1 = bound_area[c + 1] >= 0.0 ? bound_area[c + 1] : mid_area;
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
  return result;
}

}  // namespace plenopath
