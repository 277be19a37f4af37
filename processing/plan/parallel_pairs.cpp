#include "processing/plan/parallel_pairs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

#include "model/error.h"
#include "processing/plan/grid_key.h"

namespace plenopath {

void ParallelPairOptions::check() const {
  if (!(max_gap > 0.0) || !std::isfinite(max_gap)) throw Error("ParallelPairOptions.max_gap must be > 0");
  if (!(min_gap >= 0.0) || min_gap >= max_gap)
    throw Error("ParallelPairOptions.min_gap must be >= 0 and below max_gap");
  if (!(max_angle >= 0.0) || max_angle >= M_PI / 4)
    throw Error("ParallelPairOptions.max_angle must be in [0, pi/4)");
  if (!(min_overlap_fraction >= 0.0) || min_overlap_fraction > 1.0)
    throw Error("ParallelPairOptions.min_overlap_fraction must be in [0, 1]");
  if (!(min_overlap_gaps >= 0.0)) throw Error("ParallelPairOptions.min_overlap_gaps must be >= 0");
  if (!(cell_size >= 0.0) || !std::isfinite(cell_size))
    throw Error("ParallelPairOptions.cell_size must be >= 0");
  if (max_cells_per_segment < 1) throw Error("ParallelPairOptions.max_cells_per_segment must be >= 1");
  if (max_candidates_per_segment < 1)
    throw Error("ParallelPairOptions.max_candidates_per_segment must be >= 1");
}

int ParallelPairs::nearest(int segment) const {
  const int l = left[segment], r = right[segment];
  if (l < 0) return r;
  if (r < 0) return l;
  return pairs[l].gap <= pairs[r].gap ? l : r;
}

namespace {

// Cells far beyond any drawing (a stray point at 1e20) cannot be keyed in 32 bits; those segments are left
// out.
constexpr double max_cell_coordinate = 1e9;

std::int64_t key_of(std::int64_t cx, std::int64_t cy) { return grid_cell_key(cx, cy); }

// Whether the segment can be walked on the grid: finite, on it, and spanning at most max_cells cells.
bool fits_grid(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double cell, int max_cells) {
  const Eigen::Vector2d pa = a / cell, pb = b / cell;
  if (!pa.allFinite() || !pb.allFinite() || pa.cwiseAbs().maxCoeff() > max_cell_coordinate ||
      pb.cwiseAbs().maxCoeff() > max_cell_coordinate)
    return false;
  const Eigen::Vector2d d = pb - pa;
  return std::abs(d.x()) + std::abs(d.y()) + 2.0 <= static_cast<double>(max_cells);
}

// Calls fn(cx, cy) for the cells the segment passes through, walking its major axis one column at a time.
// Returns false (and calls nothing) when it does not fit the grid (fits_grid).
template <typename Fn>
bool for_each_cell(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double cell, int max_cells, Fn fn) {
  if (!fits_grid(a, b, cell, max_cells)) return false;
  const Eigen::Vector2d pa = a / cell, pb = b / cell;
  const Eigen::Vector2d d = pb - pa;
  const int major = std::abs(d.x()) >= std::abs(d.y()) ? 0 : 1, minor = 1 - major;
  const double lo = std::min(pa[major], pb[major]), hi = std::max(pa[major], pb[major]);
  const auto c0 = static_cast<std::int64_t>(std::floor(lo)), c1 = static_cast<std::int64_t>(std::floor(hi));
  for (std::int64_t c = c0; c <= c1; ++c) {
    const double s0 = std::max(lo, static_cast<double>(c)), s1 = std::min(hi, static_cast<double>(c + 1));
    double m0 = std::min(pa[minor], pb[minor]), m1 = std::max(pa[minor], pb[minor]);
    if (d[major] != 0.0) {
      m0 = pa[minor] + (s0 - pa[major]) / d[major] * d[minor];
      m1 = pa[minor] + (s1 - pa[major]) / d[major] * d[minor];
      if (m0 > m1) std::swap(m0, m1);
    }
    const auto r0 = static_cast<std::int64_t>(std::floor(m0 - 1e-9)),
               r1 = static_cast<std::int64_t>(std::floor(m1 + 1e-9));
    for (std::int64_t r = r0; r <= r1; ++r) major == 0 ? fn(c, r) : fn(r, c);
  }
  return true;
}

struct Candidate {
  int j = -1;
  double gap = 0.0, overlap = 0.0;
};

}  // namespace

ParallelPairs find_parallel_pairs(const std::vector<Segment2>& segments, const ParallelPairOptions& options) {
  options.check();
  const int n = static_cast<int>(segments.size());
  ParallelPairs out;
  out.left.assign(n, -1);
  out.right.assign(n, -1);
  const double cell = options.cell_size > 0.0 ? options.cell_size : options.max_gap;
  const int rings = static_cast<int>(std::ceil(options.max_gap / cell));
  const double sin_max_angle = std::sin(options.max_angle);

  // Unit directions with angle in [0, pi), so "left" means the same side for both lines of a pair.
  std::vector<Eigen::Vector2d> dir(n, Eigen::Vector2d::Zero());
  std::vector<Eigen::Vector2d> origin(n, Eigen::Vector2d::Zero());  // the end the direction starts from
  std::vector<double> length(n, 0.0);
  std::vector<char> usable(n, 0);
  // Segments crossing more cells (with their neighbourhoods) than there are segments are kept out of the
  // grid and compared with every segment: the same candidates (consider() tests the gap itself), without
  // filling and probing thousands of cells (a fuzzed plan of 37 entities took 0.3 s, 10 s under the
  // sanitizers).
  const double neighbourhood = (2.0 * rings + 1) * (2.0 * rings + 1);
  std::vector<char> long_segment(n, 0);
  std::vector<int> long_segments;
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  grid.reserve(static_cast<std::size_t>(n) * 2);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector2d d = segments[i].b - segments[i].a;
    length[i] = d.norm();
    if (!(length[i] > 0.0) || !std::isfinite(length[i])) continue;
    d /= length[i];
    const bool flip = d.y() < 0.0 || (d.y() == 0.0 && d.x() < 0.0);
    dir[i] = flip ? Eigen::Vector2d(-d) : d;
    origin[i] = flip ? segments[i].b : segments[i].a;
    if (!fits_grid(segments[i].a, segments[i].b, cell, options.max_cells_per_segment)) continue;
    usable[i] = 1;
    const double cells = (segments[i].b - segments[i].a).cwiseAbs().sum() / cell + 2.0;
    if (cells * neighbourhood > static_cast<double>(n)) {
      long_segment[i] = 1;
      long_segments.push_back(i);
      continue;
    }
    for_each_cell(segments[i].a, segments[i].b, cell, options.max_cells_per_segment,
                  [&](std::int64_t cx, std::int64_t cy) { grid[key_of(cx, cy)].push_back(i); });
  }

  std::vector<int> seen(n, -1);
  // The cells segment i has probed: neighbourhoods of consecutive cells overlap, and a crowded cell's list
  // would be walked again for each (a fuzzed plan of 18 816 segments in 1 080 cells: 162 M visits, 57 M
  // of them distinct). Walking each cell once finds the same candidates in the same order.
  std::unordered_set<std::int64_t> probed;
  std::vector<Candidate> best_left(n), best_right(n);
  for (int i = 0; i < n; ++i) {
    if (!usable[i]) continue;
    const Eigen::Vector2d a = origin[i];
    const Eigen::Vector2d u = dir[i];
    const double li = length[i];
    int examined = 0;
    auto consider = [&](int j) {
      if (j == i || seen[j] == i || !usable[j]) return;
      seen[j] = i;
      ++examined;
      const Eigen::Vector2d& v = dir[j];
      if (std::abs(u.x() * v.y() - u.y() * v.x()) > sin_max_angle) return;
      const Eigen::Vector2d p0 = segments[j].a - a, p1 = segments[j].b - a;
      double t0 = p0.dot(u), t1 = p1.dot(u);
      double s0 = u.x() * p0.y() - u.y() * p0.x(), s1 = u.x() * p1.y() - u.y() * p1.x();
      if (t0 > t1) {
        std::swap(t0, t1);
        std::swap(s0, s1);
      }
      const double lo = std::max(0.0, t0), hi = std::min(li, t1);
      const double overlap = hi - lo;
      if (!(overlap > 0.0)) return;
      const double tm = 0.5 * (lo + hi);
      const double side = t1 > t0 ? s0 + (s1 - s0) * (tm - t0) / (t1 - t0) : 0.5 * (s0 + s1);
      const double gap = std::abs(side);
      if (gap < options.min_gap || gap > options.max_gap || gap == 0.0) return;
      if (overlap < options.min_overlap_fraction * std::min(li, length[j])) return;
      if (overlap < options.min_overlap_gaps * gap) return;
      Candidate& best = side > 0.0 ? best_left[i] : best_right[i];
      if (best.j < 0 || gap < best.gap) best = {j, gap, overlap};
    };
    if (long_segment[i]) {
      for (int j = 0; j < n && examined < options.max_candidates_per_segment; ++j) consider(j);
      continue;
    }
    for (int j : long_segments) consider(j);  // not in the grid
    probed.clear();
    for_each_cell(segments[i].a, segments[i].b, cell, options.max_cells_per_segment,
                  [&](std::int64_t cx, std::int64_t cy) {
                    for (int dx = -rings; dx <= rings; ++dx)
                      for (int dy = -rings; dy <= rings; ++dy) {
                        if (examined >= options.max_candidates_per_segment) return;
                        const std::int64_t key = key_of(cx + dx, cy + dy);
                        if (!probed.insert(key).second) continue;
                        auto it = grid.find(key);
                        if (it == grid.end()) continue;
                        for (int j : it->second) {
                          if (examined >= options.max_candidates_per_segment) return;
                          consider(j);
                        }
                      }
                  });
  }

  std::unordered_map<std::int64_t, int> index_of_pair;
  index_of_pair.reserve(static_cast<std::size_t>(n));
  auto record = [&](int i, const Candidate& c) -> int {
    if (c.j < 0) return -1;
    const int lo = std::min(i, c.j), hi = std::max(i, c.j);
    const std::int64_t key = (static_cast<std::int64_t>(lo) << 32) | static_cast<std::int64_t>(hi);
    auto [it, inserted] = index_of_pair.emplace(key, static_cast<int>(out.pairs.size()));
    if (inserted) out.pairs.push_back({lo, hi, c.gap, c.overlap});
    return it->second;
  };
  for (int i = 0; i < n; ++i) {
    out.left[i] = record(i, best_left[i]);
    out.right[i] = record(i, best_right[i]);
  }
  return out;
}

}  // namespace plenopath
