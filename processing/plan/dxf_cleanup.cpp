#include "processing/plan/dxf_cleanup.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "processing/segment_grid.h"

namespace plenopath {
namespace {

struct Seg {
  Eigen::Vector2d a, b;
};

// Endpoints within `tolerance` of an earlier endpoint move onto it.
void snap(std::vector<Seg>* segs, double tolerance, CleanupCounts* counts) {
  if (tolerance <= 0.0) return;
  std::unordered_map<long long, std::vector<Eigen::Vector2d>> cells;
  auto key = [](long long x, long long y) { return x * 73856093LL ^ y * 19349663LL; };
  auto snap_point = [&](Eigen::Vector2d* p) {
    const long long cx = static_cast<long long>(std::floor(p->x() / tolerance));
    const long long cy = static_cast<long long>(std::floor(p->y() / tolerance));
    for (long long dy = -1; dy <= 1; ++dy)
      for (long long dx = -1; dx <= 1; ++dx) {
        auto it = cells.find(key(cx + dx, cy + dy));
        if (it == cells.end()) continue;
        for (const auto& q : it->second)
          if ((q - *p).norm() <= tolerance) {
            if (q != *p) ++counts->snapped_endpoints;
            *p = q;
            return;
          }
      }
    cells[key(cx, cy)].push_back(*p);
  };
  for (auto& s : *segs) {
    snap_point(&s.a);
    snap_point(&s.b);
  }
}

// Collinear groups (same line within tolerance) become the union of their intervals.
std::vector<Seg> merge_collinear(std::vector<Seg> segs, double tolerance, CleanupCounts* counts) {
  const double tol = std::max(tolerance, 1e-9);
  struct Keyed {
    double angle, offset;
    int index;
  };
  std::vector<Keyed> keyed;
  for (int i = 0; i < static_cast<int>(segs.size()); ++i) {
    Eigen::Vector2d d = (segs[i].b - segs[i].a).normalized();
    if (d.x() < 0 || (d.x() == 0 && d.y() < 0)) d = -d;
    double angle = std::atan2(d.y(), d.x());  // (-pi/2, pi/2]
    const Eigen::Vector2d n(-d.y(), d.x());
    keyed.push_back({angle, n.dot(segs[i].a), i});
  }
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& l, const Keyed& r) {
    return l.angle != r.angle ? l.angle < r.angle : l.offset < r.offset;
  });
  std::vector<bool> used(segs.size(), false);
  std::vector<Seg> out;
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    const int i = keyed[k].index;
    if (used[i]) continue;
    used[i] = true;
    const Seg& base = segs[i];
    const Eigen::Vector2d d = (base.b - base.a).normalized();
    std::vector<std::pair<double, double>> intervals = {{0.0, (base.b - base.a).norm()}};
    std::vector<int> members = {i};
    // Candidates: following entries with nearly the same angle and offset.
    for (std::size_t m = k + 1; m < keyed.size() && keyed[m].angle - keyed[k].angle < 1e-6; ++m) {
      const int j = keyed[m].index;
      if (used[j] || std::abs(keyed[m].offset - keyed[k].offset) > tol) continue;
      const Seg& s = segs[j];
      const Eigen::Vector2d n(-d.y(), d.x());
      if (std::abs(n.dot(s.a - base.a)) > tol || std::abs(n.dot(s.b - base.a)) > tol) continue;
      double t0 = d.dot(s.a - base.a), t1 = d.dot(s.b - base.a);
      if (t0 > t1) std::swap(t0, t1);
      intervals.push_back({t0, t1});
      members.push_back(j);
    }
    std::sort(intervals.begin(), intervals.end());
    // Union of overlapping intervals; `members` not overlapping stay separate pieces.
    std::vector<std::pair<double, double>> merged;
    std::vector<int> pieces_per_merged;
    for (const auto& iv : intervals) {
      if (!merged.empty() && iv.first <= merged.back().second + tol) {
        const bool identical = std::abs(iv.first - merged.back().first) <= tol &&
                               std::abs(iv.second - merged.back().second) <= tol;
        if (identical) ++counts->duplicates_dropped;
        else ++counts->collinear_merged;
        merged.back().second = std::max(merged.back().second, iv.second);
      } else {
        merged.push_back(iv);
      }
    }
    for (const auto& iv : merged) {
      // Keep original endpoints exactly when an interval is one member's own.
      Seg s{base.a + iv.first * d, base.a + iv.second * d};
      for (int j : members) {
        for (const Eigen::Vector2d* p : {&segs[j].a, &segs[j].b}) {
          if (std::abs(d.dot(*p - base.a) - iv.first) <= 1e-12) s.a = *p;
          if (std::abs(d.dot(*p - base.a) - iv.second) <= 1e-12) s.b = *p;
        }
      }
      out.push_back(s);
    }
    for (int j : members) used[j] = true;
  }
  return out;
}

// Splits every segment where another crosses it or ends on it (within tolerance).
std::vector<Seg> split_at_intersections(const std::vector<Seg>& segs, double tolerance, CleanupCounts* counts) {
  std::vector<Segment2> plain;
  for (const auto& s : segs) plain.push_back({s.a, s.b});
  const SegmentGrid grid(plain);
  const double tol = std::max(tolerance, 1e-9);
  std::vector<Seg> out;
  for (int i = 0; i < static_cast<int>(segs.size()); ++i) {
    const Seg& s = segs[i];
    const double len = (s.b - s.a).norm();
    std::vector<double> cuts;
    for (int j : grid.along(s.a, s.b)) {
      if (j == i) continue;
      const Seg& o = segs[j];
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
    for (const auto& s : segs) {
      if ((s.b - s.a).norm() <= std::max(tolerance * 0.5, 0.0) || (s.a == s.b)) {
        ++counts->zero_length_dropped;
        continue;
      }
      kept.push_back(s);
    }
    kept = merge_collinear(std::move(kept), tolerance, counts);
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
