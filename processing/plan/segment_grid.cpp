#include "processing/plan/segment_grid.h"

#include <algorithm>
#include <cmath>

namespace plenopath {

double distance_point_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return (p - a).norm();
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

bool intersect_segments(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                        const Eigen::Vector2d& b1, double* t, double* u) {
  const Eigen::Vector2d r = a1 - a0, s = b1 - b0, q = b0 - a0;
  const double denom = r.x() * s.y() - r.y() * s.x();
  const double scale = r.norm() * s.norm();
  if (scale <= 0.0 || std::abs(denom) <= 1e-14 * scale) return false;
  const double tt = (q.x() * s.y() - q.y() * s.x()) / denom;
  const double uu = (q.x() * r.y() - q.y() * r.x()) / denom;
  if (tt < 0.0 || tt > 1.0 || uu < 0.0 || uu > 1.0) return false;
  if (t) *t = tt;
  if (u) *u = uu;
  return true;
}

// Walks along the major axis one column (or row) at a time and visits the cells the segment spans there.
template <typename Fn>
void SegmentGrid::for_each_cell_along(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Fn fn) const {
  const Eigen::Vector2d d = b - a;
  const bool along_x = std::abs(d.x()) >= std::abs(d.y());
  const int major = along_x ? 0 : 1, minor = 1 - major;
  const int n_major = along_x ? nx_ : ny_;
  const double lo = std::min(a[major], b[major]), hi = std::max(a[major], b[major]);
  const int c0 = std::clamp(static_cast<int>(std::floor((lo - origin_[major]) / cell_size_)), 0, n_major - 1);
  const int c1 = std::clamp(static_cast<int>(std::floor((hi - origin_[major]) / cell_size_)), 0, n_major - 1);
  for (int c = c0; c <= c1; ++c) {
    const double s0 = std::max(lo, origin_[major] + c * cell_size_);
    const double s1 = std::min(hi, origin_[major] + (c + 1) * cell_size_);
    double m0 = a[minor], m1 = a[minor];
    if (d[major] != 0.0) {
      m0 = a[minor] + (s0 - a[major]) / d[major] * d[minor];
      m1 = a[minor] + (s1 - a[major]) / d[major] * d[minor];
    } else {
      m0 = std::min(a[minor], b[minor]);
      m1 = std::max(a[minor], b[minor]);
    }
    if (m0 > m1) std::swap(m0, m1);
    const double margin = cell_size_ * 1e-6;
    const int r0 = along_x ? cell_y(m0 - margin) : cell_x(m0 - margin);
    const int r1 = along_x ? cell_y(m1 + margin) : cell_x(m1 + margin);
    for (int r = r0; r <= r1; ++r) along_x ? fn(c, r) : fn(r, c);
  }
}

SegmentGrid::SegmentGrid(std::vector<Segment2> segments, int cells_hint) : segments_(std::move(segments)) {
  Eigen::Vector2d lo(0, 0), hi(1, 1);
  if (!segments_.empty()) {
    lo = hi = segments_.front().a;
    for (const auto& s : segments_) {
      lo = lo.cwiseMin(s.a).cwiseMin(s.b);
      hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    }
  }
  const double span = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-6});
  if (cells_hint <= 0)
    cells_hint = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(segments_.size())) * 2.0), 1, 512);
  cell_size_ = span / cells_hint * 1.0000001;
  origin_ = lo - Eigen::Vector2d(cell_size_ * 0.5, cell_size_ * 0.5);
  nx_ = static_cast<int>((hi.x() - origin_.x()) / cell_size_) + 2;
  ny_ = static_cast<int>((hi.y() - origin_.y()) / cell_size_) + 2;
  cells_.assign(static_cast<std::size_t>(nx_) * ny_, {});
  for (int i = 0; i < static_cast<int>(segments_.size()); ++i)
    for_each_cell_along(segments_[i].a, segments_[i].b, [&](int cx, int cy) {
      cells_[static_cast<std::size_t>(cy) * nx_ + cx].push_back(i);
    });
}

int SegmentGrid::cell_x(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - origin_.x()) / cell_size_)), 0, nx_ - 1);
}
int SegmentGrid::cell_y(double y) const {
  return std::clamp(static_cast<int>(std::floor((y - origin_.y()) / cell_size_)), 0, ny_ - 1);
}

void SegmentGrid::collect_cell(int cx, int cy, std::vector<int>* out) const {
  if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return;
  const auto& cell = cells_[static_cast<std::size_t>(cy) * nx_ + cx];
  out->insert(out->end(), cell.begin(), cell.end());
}

static void sort_unique(std::vector<int>* v) {
  std::sort(v->begin(), v->end());
  v->erase(std::unique(v->begin(), v->end()), v->end());
}

std::vector<int> SegmentGrid::near(const Eigen::Vector2d& p, double radius) const {
  std::vector<int> out;
  const int x0 = cell_x(p.x() - radius), x1 = cell_x(p.x() + radius);
  const int y0 = cell_y(p.y() - radius), y1 = cell_y(p.y() + radius);
  for (int cy = y0; cy <= y1; ++cy)
    for (int cx = x0; cx <= x1; ++cx) collect_cell(cx, cy, &out);
  sort_unique(&out);
  return out;
}

std::vector<int> SegmentGrid::along(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  std::vector<int> out;
  for_each_cell_along(a, b, [&](int cx, int cy) { collect_cell(cx, cy, &out); });
  sort_unique(&out);
  return out;
}

double SegmentGrid::distance_within(const Eigen::Vector2d& p, double radius) const {
  double best = radius;
  for (int i : near(p, radius))
    best = std::min(best, distance_point_segment(p, segments_[i].a, segments_[i].b));
  return best;
}

}  // namespace plenopath
