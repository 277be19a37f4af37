// clean_segments against hand-computed cases and, on random small plans, against brute-force checks written
// here (every pair of segments looked at; no grid, no buckets): the same union of covered points per layer
// within the tolerance, no two segments crossing except at endpoints, no end on another's inside, no
// collinear overlaps left.
#include "processing/plan/dxf_cleanup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace plenopath {
namespace {

using V = Eigen::Vector2d;
constexpr double kTol = 0.001;  // 1 mm, the importer's default snap tolerance

PlanSegment seg(V a, V b, const std::string& layer = "WALLS") {
  PlanSegment s;
  s.a = a;
  s.b = b;
  s.layer = layer;
  return s;
}

double cross(const V& u, const V& v) { return u.x() * v.y() - u.y() * v.x(); }

double point_segment_distance(const V& p, const V& a, const V& b) {
  const V ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// The crossing point of two non-parallel segments, if they cross.
bool crossing(const PlanSegment& s, const PlanSegment& o, V* at) {
  const V r = s.b - s.a, q = o.b - o.a;
  const double den = cross(r, q);
  if (std::abs(den) < 1e-12 * r.norm() * q.norm()) return false;
  const double t = cross(o.a - s.a, q) / den, u = cross(o.a - s.a, r) / den;
  if (t < 0 || t > 1 || u < 0 || u > 1) return false;
  *at = s.a + t * r;
  return true;
}

double nearest_end(const V& p, const PlanSegment& s) { return std::min((p - s.a).norm(), (p - s.b).norm()); }

double total_length(const std::vector<PlanSegment>& segs) {
  double sum = 0;
  for (const auto& s : segs) sum += s.length();
  return sum;
}

TEST(DxfCleanup, CurtainWallInPiecesBecomesOneSegment) {
  std::vector<PlanSegment> in;
  for (int k = 0; k < 1000; ++k) in.push_back(seg({0.3 * k, 5.0}, {0.3 * (k + 1), 5.0}));
  CleanupCounts counts;
  const auto out = clean_segments(in, kTol, &counts);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(std::min(out[0].a.x(), out[0].b.x()), 0.0, 1e-9);
  EXPECT_NEAR(std::max(out[0].a.x(), out[0].b.x()), 300.0, 1e-9);
  EXPECT_NEAR(out[0].a.y(), 5.0, 1e-12);
  EXPECT_EQ(counts.collinear_merged, 999);
  EXPECT_EQ(counts.duplicates_dropped, 0);
}

TEST(DxfCleanup, DashesApartStayApartWithTheirOwnEnds) {
  // 500 dashes of 0.2 m, 0.1 m apart, on a 30 degree line: nothing merges, every end is kept bit for bit.
  const V d(std::cos(M_PI / 6), std::sin(M_PI / 6));
  std::vector<PlanSegment> in;
  for (int k = 0; k < 500; ++k) in.push_back(seg(V(1, 2) + d * (0.3 * k), V(1, 2) + d * (0.3 * k + 0.2)));
  CleanupCounts counts;
  auto out = clean_segments(in, kTol, &counts);
  ASSERT_EQ(out.size(), in.size());
  EXPECT_EQ(counts.collinear_merged + counts.duplicates_dropped + counts.intersections_split, 0);
  auto key = [](const PlanSegment& s) { return std::make_pair(s.a.x(), s.a.y()); };
  auto by_start = [&](const PlanSegment& l, const PlanSegment& r) { return key(l) < key(r); };
  std::sort(in.begin(), in.end(), by_start);
  std::sort(out.begin(), out.end(), by_start);
  for (std::size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ(out[i].a, in[i].a);
    EXPECT_EQ(out[i].b, in[i].b);
  }
}

TEST(DxfCleanup, DuplicateZeroLengthAndOverlap) {
  CleanupCounts counts;
  const auto out = clean_segments({seg({0, 0}, {10, 0}), seg({10, 0}, {0, 0}),  // the same wall twice
                                   seg({4, 4}, {4, 4.0003}),                    // shorter than tol / 2
                                   seg({0, 3}, {6, 3}), seg({4, 3.0004}, {9, 3.0004})},  // overlapping
                                  kTol, &counts);
  EXPECT_EQ(counts.duplicates_dropped, 1);
  EXPECT_EQ(counts.zero_length_dropped, 1);
  EXPECT_EQ(counts.collinear_merged, 1);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(total_length(out), 10.0 + 9.0, 1e-6);  // the merged piece ends at (9, 3.0004)
}

TEST(DxfCleanup, ThousandsOfCopiesInOnePlaceAreDuplicates) {
  // A block inserted as a dense array of copies: 2000 of each of three walls, drawn either way round.
  std::vector<PlanSegment> in;
  for (int k = 0; k < 2000; ++k) {
    in.push_back(k % 2 ? seg({0, 0}, {5, 0}) : seg({5, 0}, {0, 0}));
    in.push_back(seg({5, 0}, {5, 4}));
    in.push_back(seg({0, 4}, {5, 4}));
  }
  CleanupCounts counts;
  const auto out = clean_segments(in, kTol, &counts);
  EXPECT_EQ(counts.duplicates_dropped, 3 * 2000 - 3);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_NEAR(total_length(out), 5.0 + 4.0 + 5.0, 1e-9);
}

TEST(DxfCleanup, CrossingsAndTJunctionsSplitPerLayer) {
  CleanupCounts counts;
  // A cross on WALLS; a T whose stem stops 0.4 mm short of the bar on DOORS; a crossing of two layers.
  const auto out = clean_segments(
      {seg({0, 0}, {2, 2}), seg({0, 2}, {2, 0}), seg({10, 0}, {14, 0}, "DOORS"),
       seg({11, 0.0004}, {11, 3}, "DOORS"), seg({20, 0}, {22, 0}, "A"), seg({21, -1}, {21, 1}, "B")},
      kTol, &counts);
  EXPECT_EQ(counts.intersections_split, 2 + 1);
  int walls = 0, doors = 0;
  for (const auto& s : out) {
    if (s.layer == "WALLS") {
      ++walls;
      EXPECT_NEAR(s.length(), std::sqrt(2.0), 1e-9);
      EXPECT_LT(nearest_end({1, 1}, s), 1e-12);
    }
    if (s.layer == "DOORS") ++doors;
  }
  EXPECT_EQ(walls, 4);
  EXPECT_EQ(doors, 3);
  EXPECT_EQ(out.size(), 4u + 3u + 2u);  // A and B do not meet: different layers
}

TEST(DxfCleanup, NearlyVerticalPiecesMergeAcrossTheWrap) {
  // Pieces of the line x = 0 whose directions lean by 1e-10 rad to either side of vertical (as rotated
  // blocks leave them): one leans just past +90 degrees, the other just short of it.
  CleanupCounts counts;
  const auto out = clean_segments({seg({0, 0}, {1e-9, 10}), seg({0, 5}, {-1e-9, 15})}, kTol, &counts);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(counts.collinear_merged, 1);
  EXPECT_NEAR(std::min(out[0].a.y(), out[0].b.y()), 0.0, 1e-9);
  EXPECT_NEAR(std::max(out[0].a.y(), out[0].b.y()), 15.0, 1e-9);
}

TEST(DxfCleanup, StrayEntityFarAwayAndAbsurdCoordinates) {
  // A grid of 40 x 40 walls, one stray line 1e7 m away and one at 1e20: the grid is split as without them.
  std::vector<PlanSegment> in;
  for (int k = 0; k <= 40; ++k) {
    in.push_back(seg({0.0, k * 1.0}, {40.0, k * 1.0}));
    in.push_back(seg({k * 1.0, 0.0}, {k * 1.0, 40.0}));
  }
  CleanupCounts plain_counts, counts;
  const auto plain = clean_segments(in, kTol, &plain_counts);
  in.push_back(seg({1e7, 1e7}, {1e7 + 3, 1e7}));
  in.push_back(seg({1e20, 0}, {1e20, 1e20}));
  // No time limit here (CI machines are shared): a grid that tried to span 1e20 m would not finish, and
  // ctest's timeout reports that.
  const auto out = clean_segments(in, kTol, &counts);
  EXPECT_EQ(plain.size(), 41u * 40u * 2u);
  EXPECT_EQ(out.size(), plain.size() + 2);
  EXPECT_EQ(counts.intersections_split, plain_counts.intersections_split);
}

// ---------------------------------------------------------------------------------------------------------
// Random small plans. Directions on 45 degree steps (so crossings are never shallower than 45 degrees and
// the tolerance zones stay small), coordinates on a 1 cm lattice, then the mess CAD files have: pieces
// overlapping on one line, copies shifted across by less than the tolerance, ends jittered within half the
// tolerance, T-junctions ending on another line or just short of it, zero-length lines, two layers.
std::vector<PlanSegment> random_plan(std::mt19937* rng) {
  std::uniform_int_distribution<int> lattice(0, 400), length(5, 200), direction(0, 3), kind(0, 9);
  std::uniform_real_distribution<double> unit(0.0, 1.0), jitter(-0.4 * kTol, 0.4 * kTol);
  const V dirs[4] = {V(1, 0), V(1, 1), V(0, 1), V(-1, 1)};
  std::vector<PlanSegment> out;
  const char* layers[2] = {"WALLS", "GLASS"};
  std::vector<std::size_t> fresh;
  for (int i = 0; i < 250; ++i) {
    const std::string layer = layers[unit(*rng) < 0.7 ? 0 : 1];
    const int k = kind(*rng);
    if (k <= 4 || out.empty()) {  // a fresh line
      fresh.push_back(out.size());
      const V a = V(lattice(*rng), lattice(*rng)) * 0.01;
      out.push_back(seg(a, a + dirs[direction(*rng)] * (length(*rng) * 0.01), layer));
      continue;
    }
    // Pieces and copies come from fresh lines only: copies of copies, each moved across by up to half the
    // tolerance, would drift off their line by more than it (no clean-up can merge such a chain at once).
    auto any_of = [&](std::size_t count) {
      return std::uniform_int_distribution<std::size_t>(0, count - 1)(*rng);
    };
    const PlanSegment base = k == 5 || k == 6 ? out[fresh[any_of(fresh.size())]] : out[any_of(out.size())];
    const V d = base.b - base.a, across = V(-d.y(), d.x()).normalized();
    if (k == 5) {  // an overlapping piece on the same line
      const double t0 = unit(*rng) * 1.2 - 0.1, t1 = t0 + 0.1 + unit(*rng) * 0.8;
      out.push_back(seg(base.a + t0 * d, base.a + t1 * d, base.layer));
    } else if (k == 6) {  // a copy moved across by under half the tolerance, along by 1 % to 31 %
      const V shift = across * (0.45 * kTol * (2 * unit(*rng) - 1)) + d * (0.01 + 0.3 * unit(*rng));
      out.push_back(seg(base.b + shift, base.a + shift, base.layer));
    } else if (k == 7) {  // a T-junction: a stem from the inside of base, ending on it or up to 0.4 tol short
      const V foot = base.a + (0.15 + 0.7 * unit(*rng)) * d + across * (0.4 * kTol * unit(*rng));
      V stem = dirs[direction(*rng)];
      if (std::abs(cross(stem.normalized(), d.normalized())) < 0.5) stem = across;
      out.push_back(seg(foot, foot + stem.normalized() * (0.05 + unit(*rng)), base.layer));
    } else if (k == 8) {  // a line continuing from an end of base, its start within half the tolerance
      const V from = base.b + V(jitter(*rng), jitter(*rng));
      out.push_back(seg(from, from + dirs[direction(*rng)] * (length(*rng) * 0.01), base.layer));
    } else {  // a point drawn as a line
      const V p = V(lattice(*rng), lattice(*rng)) * 0.01;
      out.push_back(seg(p, p + V(jitter(*rng), 0.0), layer));
    }
  }
  return out;
}

// Points every 2 cm along a segment, both ends included.
std::vector<V> samples(const PlanSegment& s) {
  const int n = std::max(1, static_cast<int>(std::ceil(s.length() / 0.02)));
  std::vector<V> out;
  for (int k = 0; k <= n; ++k) out.push_back(s.a + (s.b - s.a) * (static_cast<double>(k) / n));
  return out;
}

double distance_to_layer(const V& p, const std::vector<PlanSegment>& segs, const std::string& layer) {
  double best = INFINITY;
  for (const auto& s : segs)
    if (s.layer == layer) best = std::min(best, point_segment_distance(p, s.a, s.b));
  return best;
}

TEST(DxfCleanup, RandomPlansAgainstBruteForce) {
  std::mt19937 rng(20240616);
  // Snapping moves an end by up to the tolerance and merging lays a piece onto its group's line (within the
  // tolerance again): covered points move by at most 2 tol.
  const double cover = 2.0 * kTol + 1e-9;
  for (int plan = 0; plan < 25; ++plan) {
    SCOPED_TRACE("plan " + std::to_string(plan));
    const std::vector<PlanSegment> in = random_plan(&rng);
    CleanupCounts counts;
    const std::vector<PlanSegment> out = clean_segments(in, kTol, &counts);
    EXPECT_GT(counts.collinear_merged + counts.duplicates_dropped, 0);
    EXPECT_GT(counts.intersections_split, 0);

    // 1. The same covered points per layer: input within reach of the output and back. Lines no longer
    //    than the tolerance are points and may vanish.
    for (const auto& s : in) {
      if (s.length() <= kTol) continue;
      for (const V& p : samples(s)) ASSERT_LE(distance_to_layer(p, out, s.layer), cover) << s.layer;
    }
    for (const auto& s : out) {
      ASSERT_GT(s.length(), 0.0);
      for (const V& p : samples(s)) ASSERT_LE(distance_to_layer(p, in, s.layer), cover) << s.layer;
    }

    for (std::size_t i = 0; i < out.size(); ++i)
      for (std::size_t j = 0; j < out.size(); ++j) {
        const PlanSegment &s = out[i], &o = out[j];
        if (i == j || s.layer != o.layer) continue;
        const V ds = (s.b - s.a).normalized(), dor = (o.b - o.a).normalized();
        const bool parallel = std::abs(cross(ds, dor)) < 1e-3;
        // 2. Segments meet only at their ends (within the tolerance a split keeps from its last cut).
        V at;
        if (!parallel && i < j && crossing(s, o, &at)) {
          ASSERT_LE(nearest_end(at, s), 1.5 * kTol) << "crossing at " << at.transpose();
          ASSERT_LE(nearest_end(at, o), 1.5 * kTol) << "crossing at " << at.transpose();
        }
        // 3. No end of o on the inside of s: it was split there (the cut lies at the end's foot on s).
        if (!parallel) {
          for (const V& p : {o.a, o.b}) {
            if (point_segment_distance(p, s.a, s.b) <= 0.5 * kTol) {
              ASSERT_LE(nearest_end(p, s), 2.0 * kTol) << "T-junction left at " << p.transpose();
            }
          }
        }
        // 4. No collinear overlap: o on s's line within the tolerance shares at most the tolerance with s.
        if (parallel && i < j) {
          const V n(-ds.y(), ds.x());
          if (std::abs(n.dot(o.a - s.a)) <= kTol && std::abs(n.dot(o.b - s.a)) <= kTol) {
            const double s1 = s.length();
            double t0 = ds.dot(o.a - s.a), t1 = ds.dot(o.b - s.a);
            if (t0 > t1) std::swap(t0, t1);
            const double overlap = std::min(s1, t1) - std::max(0.0, t0);
            ASSERT_LE(overlap, kTol) << "collinear overlap of " << s.a.transpose() << " - " << s.b.transpose()
                                     << " and " << o.a.transpose() << " - " << o.b.transpose();
          }
        }
      }
  }
}

}  // namespace
}  // namespace plenopath
