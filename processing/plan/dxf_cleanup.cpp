#include "processing/plan/dxf_cleanup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>

#include "processing/plan/segment_grid.h"

namespace plenopath {
namespace {

struct Seg {
  Eigen::Vector2d a, b;
};

// floor(v / cell) as an integer cell index; clamped so that absurd coordinates (1e20) cannot overflow.
std::int64_t cell_index(double v, double cell) {
  const double c = std::floor(v / cell);
  constexpr double kLimit = 4e18;
  if (!(c > -kLimit)) return static_cast<std::int64_t>(-kLimit);
  if (!(c < kLimit)) return static_cast<std::int64_t>(kLimit);
  return static_cast<std::int64_t>(c);
}

std::uint64_t cell_key(std::int64_t x, std::int64_t y) {
  return static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^ static_cast<std::uint64_t>(y);
}

std::uint64_t mix(std::uint64_t k) {  // splitmix64's finaliser: spreads cell keys over the table
  k ^= k >> 30;
  k *= 0xBF58476D1CE4E5B9ULL;
  k ^= k >> 27;
  k *= 0x94D049BB133111EBULL;
  return k ^ (k >> 31);
}

// A fixed multimap from cell keys to ints, built once: the values sorted by key in one array, and an
// open-addressing table from a key to its range. One allocation instead of one vector per cell (the cells
// are many and small, and allocating and chasing them was most of the time on large plans).
class CellTable {
 public:
  struct Range {
    std::uint64_t key = 0;
    int begin = 0, end = -1;  // end < 0: empty slot
  };

  explicit CellTable(std::vector<std::pair<std::uint64_t, int>> entries) {
    std::sort(entries.begin(), entries.end());
    std::size_t size = 16;
    while (size < entries.size() * 2) size *= 2;
    slots_.assign(size, Range{});
    values_.reserve(entries.size());
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (i == 0 || entries[i].first != entries[i - 1].first) {
        Range* r = slot(entries[i].first);
        r->key = entries[i].first;
        r->begin = r->end = static_cast<int>(values_.size());
      }
      values_.push_back(entries[i].second);
      ++slot(entries[i].first)->end;
    }
  }

  // The range of `key`, or nullptr. Its values are values()[begin, end); callers may shrink end.
  Range* find(std::uint64_t key) {
    Range* r = slot(key);
    return r->end < 0 ? nullptr : r;
  }
  std::vector<int>& values() { return values_; }

 private:
  Range* slot(std::uint64_t key) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = mix(key) & mask;
    while (slots_[i].end >= 0 && slots_[i].key != key) i = (i + 1) & mask;
    return &slots_[i];
  }

  std::vector<Range> slots_;
  std::vector<int> values_;
};

// Endpoints within `tolerance` of an earlier endpoint move onto it. A hashed grid of tolerance-sized cells:
// a cell holds only points further than the tolerance apart, so each lookup sees a handful. The table maps
// a cell to the head of its list of kept points (open addressing, grown at half load).
void snap(std::vector<Seg>* segs, double tolerance, CleanupCounts* counts) {
  if (tolerance <= 0.0) return;
  struct Slot {
    std::uint64_t key = 0;
    int head = -1;  // -1: empty slot
  };
  std::vector<Slot> table(16);
  std::size_t used_slots = 0;
  std::vector<Eigen::Vector2d> points;
  std::vector<int> next;  // the next point of the same cell, or -1
  auto slot = [&](std::uint64_t key) -> Slot& {
    const std::size_t mask = table.size() - 1;
    std::size_t i = mix(key) & mask;
    while (table[i].head >= 0 && table[i].key != key) i = (i + 1) & mask;
    return table[i];
  };
  auto insert = [&](std::uint64_t key, const Eigen::Vector2d& p) {
    if (2 * (used_slots + 1) > table.size()) {
      std::vector<Slot> old(table.size() * 2);
      old.swap(table);
      for (const Slot& o : old)
        if (o.head >= 0) slot(o.key) = o;
    }
    Slot& s = slot(key);
    if (s.head < 0) ++used_slots;
    s.key = key;
    next.push_back(s.head);
    s.head = static_cast<int>(points.size());
    points.push_back(p);
  };
  points.reserve(segs->size() * 2);
  next.reserve(segs->size() * 2);
  auto snap_point = [&](Eigen::Vector2d* p) {
    const std::int64_t cx = cell_index(p->x(), tolerance), cy = cell_index(p->y(), tolerance);
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        // The list runs newest first, so the last match is the oldest: the one an earlier endpoint kept.
        int found = -1;
        for (int q = slot(cell_key(cx + dx, cy + dy)).head; q >= 0; q = next[q])
          if ((points[q] - *p).norm() <= tolerance) found = q;
        if (found >= 0) {
          if (points[found] != *p) ++counts->snapped_endpoints;
          *p = points[found];
          return;
        }
      }
    insert(cell_key(cx, cy), *p);
  };
  for (auto& s : *segs) {
    snap_point(&s.a);
    snap_point(&s.b);
  }
}

// A hashed uniform grid for the merge's and the split's neighbour queries. The cell size follows the
// segments' median length (not the bounding box, which one stray entity far away would blow up); a segment
// spanning more than kMaxCellsPerSegment cells is kept in a short list that every query checks instead.
class SegmentCells {
 public:
  static constexpr std::int64_t kMaxCellsPerSegment = 4096;

  SegmentCells(const std::vector<Seg>& segs, double tolerance) : segs_(segs), margin_(tolerance * 1.5) {
    std::vector<double> lengths;
    lengths.reserve(segs.size());
    for (const auto& s : segs) lengths.push_back((s.b - s.a).norm());
    double typical = 1.0;
    if (!lengths.empty()) {
      std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
      typical = lengths[lengths.size() / 2];
    }
    cell_ = std::max({typical, 8.0 * tolerance, 1e-6});
    // Past as many cells as there are segments, checking every segment is cheaper than walking the cells
    // (fuzzed plans of a few hundred long lines spent 10 s under the sanitizers filling and probing them).
    long_cells_ =
        std::min(static_cast<double>(kMaxCellsPerSegment), std::max(64.0, static_cast<double>(segs.size())));
    std::vector<std::pair<std::uint64_t, int>> entries;
    entries.reserve(segs.size() * 4);
    for (int i = 0; i < static_cast<int>(segs.size()); ++i) {
      if (cells_along(segs[i], 0.0) > long_cells_) {
        long_.push_back(i);
        continue;
      }
      for_each_cell(segs[i], 0.0, [&](std::uint64_t key) { entries.push_back({key, i}); });
    }
    cells_ = CellTable(std::move(entries));
    seen_.assign(segs.size(), -1);
  }

  // Indices of the segments that may cross `query` or end within the tolerance of it (each once).
  void candidates(int query, std::vector<int>* out) {
    out->clear();
    auto take = [&](int j) {
      if (j == query || seen_[j] == query) return;
      seen_[j] = query;
      out->push_back(j);
    };
    const Seg& s = segs_[query];
    if (cells_along(s, margin_) > long_cells_) {
      for (int j = 0; j < static_cast<int>(segs_.size()); ++j) take(j);  // a very long segment meets anything
      return;
    }
    for_each_cell(s, margin_, [&](std::uint64_t key) {
      if (const CellTable::Range* r = cells_.find(key))
        for (int v = r->begin; v < r->end; ++v) take(cells_.values()[v]);
    });
    for (int j : long_) take(j);
  }

 private:
  // About how many cells for_each_cell visits for s widened by `margin` (infinite for absurd coordinates).
  double cells_along(const Seg& s, double margin) const {
    const Eigen::Vector2d d = (s.b - s.a).cwiseAbs();
    const double major = std::max(d.x(), d.y()), minor = std::min(d.x(), d.y());
    const double columns = (major + 2 * margin) / cell_ + 2.0;
    const double rows_per_column = (major > 0 ? minor / major : 0.0) + 2 * margin / cell_ + 2.0;
    const double cells = columns * rows_per_column;
    return std::isfinite(cells) ? cells : 1e300;
  }

  // Calls fn(key) for every cell within `margin` of the segment: column by column along the major axis, the
  // span of minor-axis cells the segment (widened by the margin) covers in that column.
  template <typename Fn>
  void for_each_cell(const Seg& s, double margin, Fn fn) const {
    const Eigen::Vector2d d = s.b - s.a;
    const int major = std::abs(d.x()) >= std::abs(d.y()) ? 0 : 1, minor = 1 - major;
    const double lo = std::min(s.a[major], s.b[major]) - margin,
                 hi = std::max(s.a[major], s.b[major]) + margin;
    const std::int64_t c0 = cell_index(lo, cell_), c1 = cell_index(hi, cell_);
    for (std::int64_t c = c0; c <= c1; ++c) {
      // The segment's minor coordinate over this column's part of [lo, hi], clamped to the segment.
      const double s0 = std::max(lo, static_cast<double>(c) * cell_);
      const double s1 = std::min(hi, static_cast<double>(c + 1) * cell_);
      double m0, m1;
      if (d[major] != 0.0) {
        auto at = [&](double x) {
          const double t = std::clamp((x - s.a[major]) / d[major], 0.0, 1.0);
          return s.a[minor] + t * d[minor];
        };
        m0 = at(s0);
        m1 = at(s1);
      } else {
        m0 = s.a[minor];
        m1 = s.b[minor];
      }
      if (m0 > m1) std::swap(m0, m1);
      const std::int64_t r0 = cell_index(m0 - margin, cell_), r1 = cell_index(m1 + margin, cell_);
      for (std::int64_t r = r0; r <= r1; ++r) fn(major == 0 ? cell_key(c, r) : cell_key(r, c));
    }
  }

  const std::vector<Seg>& segs_;
  double margin_;
  double cell_ = 1.0;
  double long_cells_ = kMaxCellsPerSegment;  // a segment along more cells than this is "long"
  CellTable cells_{{}};
  std::vector<int> long_;
  std::vector<int> seen_;  // last query that took each segment
};

// The order in which segments become the base of a group: longest first (its line is the best defined),
// then by direction angle in (-pi/2, pi/2] and the line's signed offset from the origin.
struct BaseKey {
  double length, angle, offset;
  int index;
  bool operator<(const BaseKey& r) const {
    if (length != r.length) return length > r.length;
    if (angle != r.angle) return angle < r.angle;
    return offset != r.offset ? offset < r.offset : index < r.index;
  }
};

BaseKey base_key(const Seg& s, int index) {
  Eigen::Vector2d d = (s.b - s.a).normalized();
  if (d.x() < 0 || (d.x() == 0 && d.y() < 0)) d = -d;
  const Eigen::Vector2d n(-d.y(), d.x());
  return {(s.b - s.a).norm(), std::atan2(d.y(), d.x()), n.dot(s.a), index};
}

// Collinear groups become the union of their intervals on the group's line.
//
// Segments are taken longest first; each one not yet merged is the base of a group. The group
// grows through space: the unmerged segments near a member (grid query, within the tolerance) that lie on
// the base's line (both ends within the tolerance of it) join, and their neighbours are looked at in turn.
// So a curtain wall in 1 000 pieces is one group found piece by piece, and the work is near-linear. Whether
// a segment is on the line is decided by its ends alone, not by its direction: a short piece that a snapped
// end tilted by 1e-4 rad still merges (the bucketing by direction within 1e-6 rad that came before left
// such pieces overlapping).
std::vector<Seg> merge_collinear(const std::vector<Seg>& segs, double tolerance, CleanupCounts* counts) {
  const double tol = std::max(tolerance, 1e-9);
  const int n = static_cast<int>(segs.size());
  std::vector<BaseKey> keyed;
  keyed.reserve(n);
  for (int i = 0; i < n; ++i) keyed.push_back(base_key(segs[i], i));
  std::sort(keyed.begin(), keyed.end());
  SegmentCells grid(segs, tol);

  std::vector<char> used(n, 0);
  std::vector<Seg> out;
  std::vector<std::pair<double, double>> intervals, merged;
  std::vector<int> members, near;
  struct Endpoint {
    double t;
    int rank;  // 2 * member order + (0 for a, 1 for b): a later rank wins, as in a loop over the members
    Eigen::Vector2d p;
  };
  std::vector<Endpoint> endpoints;
  for (int k = 0; k < n; ++k) {
    const int i = keyed[k].index;
    if (used[i]) continue;
    used[i] = 1;
    const Seg& base = segs[i];
    const Eigen::Vector2d d = (base.b - base.a).normalized();
    const Eigen::Vector2d nrm(-d.y(), d.x());
    intervals.assign(1, {0.0, (base.b - base.a).norm()});
    members.assign(1, i);
    for (std::size_t next = 0; next < members.size(); ++next) {  // members doubles as the search queue
      grid.candidates(members[next], &near);
      for (int j : near) {
        if (used[j]) continue;
        const Seg& s = segs[j];
        if (std::abs(nrm.dot(s.a - base.a)) > tol || std::abs(nrm.dot(s.b - base.a)) > tol) continue;
        double t0 = d.dot(s.a - base.a), t1 = d.dot(s.b - base.a);
        if (t0 > t1) std::swap(t0, t1);
        intervals.push_back({t0, t1});
        members.push_back(j);
        used[j] = 1;
      }
    }
    if (members.size() == 1) {
      out.push_back(base);
      continue;
    }

    std::sort(intervals.begin(), intervals.end());
    // Union of overlapping intervals (gaps up to the tolerance close); pieces apart stay separate.
    merged.clear();
    for (const auto& iv : intervals) {
      if (!merged.empty() && iv.first <= merged.back().second + tol) {
        const bool identical = std::abs(iv.first - merged.back().first) <= tol &&
                               std::abs(iv.second - merged.back().second) <= tol;
        if (identical)
          ++counts->duplicates_dropped;
        else
          ++counts->collinear_merged;
        merged.back().second = std::max(merged.back().second, iv.second);
      } else {
        merged.push_back(iv);
      }
    }
    // A piece's ends are the members' own endpoints where one lies at the piece's end (within 1e-12), so
    // that untouched geometry keeps its coordinates exactly; found by binary search among the sorted ends.
    endpoints.clear();
    for (std::size_t j = 0; j < members.size(); ++j) {
      const Seg& s = segs[members[j]];
      endpoints.push_back({d.dot(s.a - base.a), static_cast<int>(2 * j), s.a});
      endpoints.push_back({d.dot(s.b - base.a), static_cast<int>(2 * j + 1), s.b});
    }
    std::sort(endpoints.begin(), endpoints.end(),
              [](const Endpoint& l, const Endpoint& r) { return l.t < r.t; });
    auto member_end_at = [&](double t, Eigen::Vector2d* p) {
      auto it = std::lower_bound(endpoints.begin(), endpoints.end(), t - 2e-12,
                                 [](const Endpoint& e, double v) { return e.t < v; });
      int best = -1;
      for (; it != endpoints.end() && it->t <= t + 2e-12; ++it)
        if (std::abs(it->t - t) <= 1e-12 && it->rank > best) {
          best = it->rank;
          *p = it->p;
        }
    };
    for (const auto& iv : merged) {
      Seg s{base.a + iv.first * d, base.a + iv.second * d};
      member_end_at(iv.first, &s.a);
      member_end_at(iv.second, &s.b);
      out.push_back(s);
    }
  }
  return out;
}

// Splits every segment where another crosses it or ends on it (within tolerance).
std::vector<Seg> split_at_intersections(const std::vector<Seg>& segs, double tolerance,
                                        CleanupCounts* counts) {
  const double tol = std::max(tolerance, 1e-9);
  SegmentCells grid(segs, tol);
  std::vector<Seg> out;
  out.reserve(segs.size());
  std::vector<int> near;
  std::vector<double> cuts;
  for (int i = 0; i < static_cast<int>(segs.size()); ++i) {
    const Seg& s = segs[i];
    const double len = (s.b - s.a).norm();
    cuts.clear();
    grid.candidates(i, &near);
    const Eigen::Vector2d lo = s.a.cwiseMin(s.b).array() - tol, hi = s.a.cwiseMax(s.b).array() + tol;
    for (int j : near) {
      const Seg& o = segs[j];
      // Boxes apart: neither a crossing nor an end within the tolerance (most grid neighbours end here).
      if ((o.a.cwiseMax(o.b).array() < lo.array()).any() || (o.a.cwiseMin(o.b).array() > hi.array()).any())
        continue;
      double t = 0.0, u = 0.0;
      if (intersect_segments(s.a, s.b, o.a, o.b, &t, &u)) cuts.push_back(t);
      // T-junction within tolerance: an endpoint of o close to the inside of s.
      for (const Eigen::Vector2d* p : {&o.a, &o.b}) {
        const double tt = (*p - s.a).dot(s.b - s.a) / (len * len);
        if (tt > 0.0 && tt < 1.0 && distance_point_segment(*p, s.a, s.b) <= tol) cuts.push_back(tt);
      }
    }
    std::sort(cuts.begin(), cuts.end());
    Eigen::Vector2d from = s.a;
    double last_t = 0.0;
    for (double t : cuts) {
      if (t * len <= tol || (1.0 - t) * len <= tol || (t - last_t) * len <= tol) continue;
      const Eigen::Vector2d at = s.a + t * (s.b - s.a);
      out.push_back({from, at});
      ++counts->intersections_split;
      from = at;
      last_t = t;
    }
    out.push_back({from, s.b});
  }
  return out;
}

// Segments drawn more than once with the very same ends (either way round) after snapping: the first is
// kept. The collinear merge would drop them too, but its neighbour search is quadratic in the segments that
// share a place: a block inserted as a dense array of copies (393 000 lines on 120 places, found by the
// fuzzer) took minutes there and takes milliseconds here.
void drop_exact_duplicates(std::vector<Seg>* segs, CleanupCounts* counts) {
  using Ends = std::array<double, 4>;
  std::vector<std::pair<Ends, int>> keyed;
  keyed.reserve(segs->size());
  for (int i = 0; i < static_cast<int>(segs->size()); ++i) {
    const Seg& s = (*segs)[static_cast<std::size_t>(i)];
    const bool ab = std::tie(s.a.x(), s.a.y()) <= std::tie(s.b.x(), s.b.y());
    const Eigen::Vector2d& p = ab ? s.a : s.b;
    const Eigen::Vector2d& q = ab ? s.b : s.a;
    keyed.push_back({{p.x(), p.y(), q.x(), q.y()}, i});
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<char> keep(segs->size(), 1);
  for (std::size_t k = 1; k < keyed.size(); ++k)
    if (keyed[k].first == keyed[k - 1].first) {
      keep[static_cast<std::size_t>(keyed[k].second)] = 0;
      ++counts->duplicates_dropped;
    }
  std::vector<Seg> out;
  out.reserve(segs->size());
  for (std::size_t i = 0; i < segs->size(); ++i)
    if (keep[i]) out.push_back((*segs)[i]);
  *segs = std::move(out);
}

}  // namespace

std::vector<PlanSegment> clean_segments(const std::vector<PlanSegment>& input, double tolerance,
                                        CleanupCounts* counts) {
  CleanupCounts local;
  if (!counts) counts = &local;
  std::map<std::string, std::vector<Seg>> by_layer;
  for (const auto& s : input) by_layer[s.layer].push_back({s.a, s.b});
  std::vector<PlanSegment> out;
  for (auto& [layer, segs] : by_layer) {
    snap(&segs, tolerance, counts);
    std::vector<Seg> kept;
    kept.reserve(segs.size());
    for (const auto& s : segs) {
      if ((s.b - s.a).norm() <= std::max(tolerance * 0.5, 0.0) || (s.a == s.b)) {
        ++counts->zero_length_dropped;
        continue;
      }
      kept.push_back(s);
    }
    drop_exact_duplicates(&kept, counts);
    kept = merge_collinear(kept, tolerance, counts);
    kept = split_at_intersections(kept, tolerance, counts);
    for (const auto& s : kept) {
      PlanSegment p;
      p.a = s.a;
      p.b = s.b;
      p.layer = layer;
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace plenopath
