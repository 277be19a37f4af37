// Units inference on drawings built by hand: the same 12 x 8 m office (0.9 m doors, 0.2 m walls) drawn in
// each unit, a plan without doors, one with nothing to go by, a header that contradicts the drawing, and a
// 100 000-segment plan.
#include "processing/plan/units_inference.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>

namespace plenopath {
namespace {

struct Drawing {
  std::vector<DrawingSegment> segments;
  std::vector<DrawingArc> arcs;
};

// The office in metres: outer walls 12 x 8 m, 0.2 m thick, a partition at x = 6 and one at y = 4 on the
// right, three doors of 0.9 m (entrance in the bottom wall, one in each partition), each drawn as a quarter
// arc with its leaf open at right angles to the wall. Then every coordinate is divided by `metres_per_unit`.
Drawing office(double metres_per_unit, bool with_doors = true) {
  Drawing d;
  auto line = [&d](double x0, double y0, double x1, double y1) {
    d.segments.push_back({{x0, y0}, {x1, y1}});
  };
  // Outer faces and inner faces; the bottom wall has the entrance at x = 2 .. 2.9.
  line(0, 0, 2, 0);
  line(2.9, 0, 12, 0);
  line(12, 0, 12, 8);
  line(12, 8, 0, 8);
  line(0, 8, 0, 0);
  line(0.2, 0.2, 2, 0.2);
  line(2.9, 0.2, 11.8, 0.2);
  line(11.8, 0.2, 11.8, 7.8);
  line(11.8, 7.8, 0.2, 7.8);
  line(0.2, 7.8, 0.2, 0.2);
  line(2, 0, 2, 0.2);  // jambs
  line(2.9, 0, 2.9, 0.2);
  // Partition x = 5.9 .. 6.1 with a door at y = 3 .. 3.9.
  line(5.9, 0.2, 5.9, 3);
  line(5.9, 3.9, 5.9, 7.8);
  line(6.1, 0.2, 6.1, 3);
  line(6.1, 4.1, 6.1, 7.8);
  line(5.9, 3, 6.1, 3);
  line(5.9, 3.9, 6.1, 3.9);
  // Partition y = 3.9 .. 4.1 from x = 6.1 to 11.8 with a door at x = 8 .. 8.9.
  line(6.1, 3.9, 8, 3.9);
  line(8.9, 3.9, 11.8, 3.9);
  line(6.1, 4.1, 8, 4.1);
  line(8.9, 4.1, 11.8, 4.1);
  line(8, 3.9, 8, 4.1);
  line(8.9, 3.9, 8.9, 4.1);
  if (with_doors) {
    // Entrance: hinge (2, 0.2), arc from (2.9, 0.2) to (2, 1.1), leaf open along +y.
    d.arcs.push_back({{2, 0.2}, 0.9, M_PI / 2, 0.0});
    line(2, 0.2, 2, 1.1);
    // Partition door: hinge (6.1, 3), arc from (7, 3) to (6.1, 3.9), leaf open along +x.
    d.arcs.push_back({{6.1, 3.0}, 0.9, M_PI / 2, 0.0});
    line(6.1, 3, 7, 3);
    // Second partition door: hinge (8, 4.1), arc from (8.9, 4.1) to (8, 5), leaf along +y.
    d.arcs.push_back({{8, 4.1}, 0.9, M_PI / 2, 0.0});
    line(8, 4.1, 8, 5);
  }
  for (auto& s : d.segments) {
    s.a /= metres_per_unit;
    s.b /= metres_per_unit;
  }
  for (auto& a : d.arcs) {
    a.centre /= metres_per_unit;
    a.radius /= metres_per_unit;
  }
  return d;
}

struct Unit {
  const char* name;
  double metres;
};
const Unit kUnits[] = {{"mm", 0.001}, {"cm", 0.01}, {"m", 1.0}, {"in", 0.0254}, {"ft", 0.3048}};

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

TEST(UnitsInference, EvidenceOfTheOfficeInEachUnit) {
  for (const Unit& u : kUnits) {
    SCOPED_TRACE(u.name);
    const Drawing d = office(u.metres);
    const UnitsEvidence e = collect_units_evidence(d.segments, d.arcs);
    ASSERT_EQ(e.door_swing_radii.size(), 3u);
    EXPECT_EQ(e.door_leaves, 3);
    for (double r : e.door_swing_radii) EXPECT_NEAR(r * u.metres, 0.9, 1e-9);
    // Wall faces pair up 0.2 m apart: bottom (2 pieces), top, left, right, partition x (3 on the left face
    // side), partition y (2); every gap is 0.2 m by construction.
    ASSERT_GE(e.wall_gaps.size(), 8u);
    EXPECT_NEAR(median_of(e.wall_gaps) * u.metres, 0.2, 1e-9);
    for (double g : e.wall_gaps) EXPECT_NEAR(g * u.metres, 0.2, 1e-9);
    // The endpoints span 0..12 m in x (many at 0 and 12), so the 2nd-98th percentile is the full width.
    EXPECT_NEAR(e.drawing_size * u.metres, 12.0, 1e-9);
  }
}

TEST(UnitsInference, TheOfficeComesOutInItsOwnUnits) {
  for (const Unit& u : kUnits) {
    SCOPED_TRACE(u.name);
    const Drawing d = office(u.metres);
    const UnitsInference r = infer_units(collect_units_evidence(d.segments, d.arcs));
    EXPECT_EQ(r.units, u.name) << r.reason;
    EXPECT_GT(r.confidence, 0.5) << r.reason;
    EXPECT_NE(r.reason.find("3 door swings (3 with a leaf)"), std::string::npos) << r.reason;
    EXPECT_NE(r.reason.find("doors 0.90 m"), std::string::npos) << r.reason;
    EXPECT_NE(r.reason.find("walls 0.20 m"), std::string::npos) << r.reason;
    std::cout << u.name << ": " << r.reason << "\n";
  }
}

TEST(UnitsInference, WithoutDoorsWallsAndSizeDecide) {
  for (const Unit& u : kUnits) {
    SCOPED_TRACE(u.name);
    const Drawing d = office(u.metres, false);
    const UnitsEvidence e = collect_units_evidence(d.segments, d.arcs);
    EXPECT_TRUE(e.door_swing_radii.empty());
    const UnitsInference r = infer_units(e);
    EXPECT_EQ(r.units, u.name) << r.reason;
    EXPECT_GT(r.confidence, 0.0) << r.reason;
    EXPECT_EQ(r.reason.find("door"), std::string::npos) << r.reason;
    std::cout << u.name << " without doors: confidence " << r.confidence << ": " << r.reason << "\n";
  }
  // Millimetres against their neighbours is clear-cut without doors: 200 units is 2 m in cm, 5 m in inches.
  const Drawing d = office(0.001, false);
  EXPECT_GT(infer_units(collect_units_evidence(d.segments, d.arcs)).confidence, 0.5);
}

TEST(UnitsInference, NothingToGoBy) {
  const UnitsInference none = infer_units(collect_units_evidence({}, {}));
  EXPECT_EQ(none.units, "");
  EXPECT_EQ(none.confidence, 0.0);
  EXPECT_NE(none.reason.find("no door swings"), std::string::npos) << none.reason;
  // All geometry at one point: no extent, no pairs, no quarter arcs.
  const std::vector<DrawingSegment> dot = {{{5, 5}, {5, 5}}, {{5, 5}, {5, 5}}};
  const UnitsInference r = infer_units(collect_units_evidence(dot, {{{5, 5}, 1.0, 2 * M_PI}}));
  EXPECT_EQ(r.units, "");
  EXPECT_FALSE(r.reason.empty());
  std::string why;
  EXPECT_TRUE(units_plausible("m", UnitsEvidence{}, &why));
  EXPECT_NE(why.find("nothing"), std::string::npos) << why;
}

TEST(UnitsInference, InchesHeaderOnAMillimetreDrawingIsImplausible) {
  const Drawing d = office(0.001);
  const UnitsEvidence e = collect_units_evidence(d.segments, d.arcs);
  std::string why;
  EXPECT_FALSE(units_plausible("in", e, &why));
  // 900 units as inches: 22.86 m doors.
  EXPECT_NE(why.find("3 door swings of median radius 900 in would be 23 m in inches"), std::string::npos)
      << why;
  EXPECT_TRUE(units_plausible("mm", e, &why)) << why;
  EXPECT_NE(why.find("0.90 m: ok"), std::string::npos) << why;
  EXPECT_FALSE(units_plausible("cm", e, &why));  // 9 m doors
  EXPECT_FALSE(units_plausible("furlongs", e, &why));
  EXPECT_NE(why.find("unknown units"), std::string::npos) << why;
  // Without doors the walls speak: 200 units as inches would be 5.08 m thick.
  const Drawing bare = office(0.001, false);
  EXPECT_FALSE(units_plausible("in", collect_units_evidence(bare.segments, bare.arcs), &why));
  EXPECT_NE(why.find("wall line pairs of median gap 200 in would be 5.08 m in inches"), std::string::npos)
      << why;
  // Quarter arcs of 5 m and lines 3 m apart fit no unit: a drawing that is no floor plan keeps its header.
  const std::vector<DrawingSegment> odd = {{{0, 0}, {40, 0}}, {{0, 3}, {40, 3}},   {{0, 6}, {40, 6}},
                                           {{0, 9}, {40, 9}}, {{0, 12}, {40, 12}}, {{0, 15}, {40, 15}}};
  const std::vector<DrawingArc> big_arcs = {{{5, 20}, 5.0, M_PI / 2}, {{20, 20}, 5.0, M_PI / 2}};
  EXPECT_TRUE(units_plausible("m", collect_units_evidence(odd, big_arcs), &why)) << why;
  EXPECT_NE(why.find("would be 5.00 m in metres (doors are 0.6-1.1 m), but no other unit fits"),
            std::string::npos)
      << why;
  // A metre drawing declared in feet and without doors cannot be told apart (0.2 ft walls, 3.7 m across):
  // the header is kept.
  const Drawing metres = office(1.0, false);
  EXPECT_TRUE(units_plausible("ft", collect_units_evidence(metres.segments, metres.arcs), &why)) << why;
}

TEST(UnitsInference, QuarterArcsThatAreNotDoorsDoNotOutvoteLeaves) {
  // The millimetre office plus 20 quarter-circle chair backs of 300 mm without leaves: the confirmed doors
  // win.
  Drawing d = office(0.001);
  for (int i = 0; i < 20; ++i) d.arcs.push_back({{1000.0 + 400 * i, 6000}, 300.0, M_PI / 2, 0.0});
  const UnitsEvidence e = collect_units_evidence(d.segments, d.arcs);
  EXPECT_EQ(e.door_leaves, 3);
  ASSERT_EQ(e.door_swing_radii.size(), 3u);
  EXPECT_EQ(infer_units(e).units, "mm");
}

TEST(UnitsInference, HundredThousandSegmentsWithAGrid) {
  // 79 x 79 rooms of 4 m, walls 0.2 m thick drawn as two lines cut into 1 m pieces, in millimetres; one
  // door arc per room (no leaves, start unknown). 16 * 79 * 80 = 101 120 segments.
  const int rooms = 79;
  const double room = 4000.0, half = 100.0, piece = 1000.0, span = rooms * room;
  Drawing d;
  for (int w = 0; w <= rooms; ++w) {
    const double c = w * room;
    for (double face : {c - half, c + half})
      for (double t = 0; t < span; t += piece) {
        d.segments.push_back({{face, t}, {face, t + piece}});
        d.segments.push_back({{t, face}, {t + piece, face}});
      }
  }
  for (int i = 0; i < rooms; ++i)
    for (int j = 0; j < rooms; ++j) d.arcs.push_back({{i * room + half, j * room + half}, 900.0, M_PI / 2});
  ASSERT_EQ(d.segments.size(), 101120u);
  const auto start = std::chrono::steady_clock::now();
  const UnitsEvidence e = collect_units_evidence(d.segments, d.arcs);
  const UnitsInference r = infer_units(e);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << d.segments.size() << " segments, " << d.arcs.size() << " arcs: " << seconds << " s; "
            << r.reason << "\n";
  EXPECT_EQ(r.units, "mm");
  EXPECT_EQ(e.door_swing_radii.size(), d.arcs.size());
  EXPECT_NEAR(median_of(e.wall_gaps), 200.0, 1e-6);
  // Endpoints are spread about evenly over the span: the 2nd-98th percentile covers about 96 % of it.
  EXPECT_GT(e.drawing_size, 0.9 * span);
  EXPECT_LT(e.drawing_size, span);
}

}  // namespace
}  // namespace plenopath
