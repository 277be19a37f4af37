// DXF import against hand-computed geometry (files written by tests/data/dxf/make_dxf.py).
#include "processing/plan/dxf_import.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "model/error.h"

namespace plenopath {
namespace {

std::string data(const std::string& name) { return std::string(PLENOPATH_TEST_DATA_DIR) + "/dxf/" + name; }

// True if the plan has a segment from a to b (either direction) within tol.
bool has_segment(const FloorPlan& plan, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                 double tol = 1e-9) {
  for (const auto& s : plan.segments)
    if (((s.a - a).norm() < tol && (s.b - b).norm() < tol) ||
        ((s.a - b).norm() < tol && (s.b - a).norm() < tol))
      return true;
  return false;
}

double total_length(const FloorPlan& plan, const std::string& layer) {
  double sum = 0.0;
  for (const auto& s : plan.segments)
    if (s.layer == layer) sum += s.length();
  return sum;
}

TEST(DxfImport, LinesInMillimetresWithCleanup) {
  DxfImportReport report;
  const FloorPlan plan = import_dxf(data("lines_mm.dxf"), {}, &report);
  EXPECT_EQ(plan.units, "mm");
  EXPECT_TRUE(report.units_from_header);
  EXPECT_DOUBLE_EQ(plan.metres_per_unit, 0.001);
  EXPECT_TRUE(has_segment(plan, {0, 0}, {10, 0}));
  EXPECT_TRUE(has_segment(plan, {10, 0}, {10, 10}));
  EXPECT_TRUE(has_segment(plan, {0, 10}, {0, 0}));
  EXPECT_NEAR(total_length(plan, "WALLS"), 40.0, 1e-9);  // the duplicate and the zero-length line are gone
  EXPECT_EQ(report.duplicates_dropped, 1);
  EXPECT_EQ(report.zero_length_dropped, 1);
  EXPECT_TRUE(has_segment(plan, {2, 2}, {3, 2}));
  ASSERT_NE(plan.find_layer("WALLS"), nullptr);
  EXPECT_TRUE(plan.find_layer("WALLS")->occluder);
  EXPECT_FALSE(plan.find_layer("FURNITURE")->occluder);
  EXPECT_EQ(plan.find_layer("WALLS")->entity_count, 6);
  ASSERT_NE(plan.find_layer("HIDDEN"), nullptr);
  EXPECT_FALSE(plan.find_layer("HIDDEN")->visible);  // negative colour = off
  EXPECT_EQ(plan.occluder_segments().size(), 4u);
  const PlanExtents e = plan.extents();
  EXPECT_NEAR(e.max.x(), 10.0, 1e-12);
  EXPECT_NEAR(e.min.y(), 0.0, 1e-12);
}

TEST(DxfImport, OptionsOverrideUnitsLayersAndOccluders) {
  DxfImportOptions options;
  options.units_override = "cm";
  options.layers = {"FURNITURE"};
  options.occluder_layers = {"FURNITURE"};
  const FloorPlan plan = import_dxf(data("lines_mm.dxf"), options);
  EXPECT_EQ(plan.units, "cm");
  ASSERT_EQ(plan.segments.size(), 1u);
  EXPECT_TRUE(has_segment(plan, {20, 20}, {30, 20}));
  EXPECT_TRUE(plan.segments[0].occluder);
  EXPECT_EQ(plan.find_layer("WALLS"), nullptr);

  DxfImportOptions bad;
  bad.units_override = "furlong";
  EXPECT_THROW(bad.check(), Error);
  bad = {};
  bad.chord_tolerance_m = 0.0;
  EXPECT_THROW(bad.check(), Error);
}

TEST(DxfImport, LwpolylineBulgeIsAHalfCircle) {
  const FloorPlan plan = import_dxf(data("lwpolyline_bulge.dxf"));
  ASSERT_EQ(plan.outlines.size(), 1u);
  const auto& pts = plan.outlines[0].points;
  EXPECT_TRUE(plan.outlines[0].closed);
  double max_x = 0.0, area2 = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto& p = pts[i];
    const auto& q = pts[(i + 1) % pts.size()];
    area2 += p.x() * q.y() - p.y() * q.x();
    max_x = std::max(max_x, p.x());
    if (p.x() > 4.0 + 1e-12) {
      EXPECT_NEAR((p - Eigen::Vector2d(4, 1)).norm(), 1.0, 1e-9);  // on the arc
    }
  }
  EXPECT_NEAR(max_x, 5.0, 0.005);  // the bulge goes right, to x = 5
  // Rectangle plus half disc; the inscribed chords (sagitta <= 5 mm) lose at most ~ (2/3) 5 mm x pi m.
  EXPECT_NEAR(0.5 * area2, 8.0 + M_PI / 2.0, 0.012);
  EXPECT_LE(0.5 * area2, 8.0 + M_PI / 2.0);
  EXPECT_GT(pts.size(), 8u);
}

TEST(DxfImport, OldStylePolylineInCentimetres) {
  const FloorPlan plan = import_dxf(data("old_polyline_cm.dxf"));
  EXPECT_EQ(plan.segments.size(), 4u);
  EXPECT_TRUE(has_segment(plan, {0, 0}, {1, 0}));
  EXPECT_TRUE(has_segment(plan, {1, 0}, {1, 0.5}));
  EXPECT_TRUE(has_segment(plan, {0, 0.5}, {0, 0}));  // closed
}

TEST(DxfImport, ArcCircleEllipseAndMirroredExtrusion) {
  const FloorPlan plan = import_dxf(data("curves.dxf"));
  int arc = 0, circle = 0, ellipse = 0, mirrored = 0;
  for (const auto& s : plan.segments) {
    for (const Eigen::Vector2d& p : {s.a, s.b}) {
      if (s.layer == "COLUMNS") {
        EXPECT_NEAR((p - Eigen::Vector2d(10, 0)).norm(), 1.0, 1e-9);
        ++circle;
      } else if (s.layer == "MIRRORED") {
        EXPECT_NEAR((p - Eigen::Vector2d(-5, 5)).norm(), 1.0, 1e-9);
        EXPECT_LE(p.x(), -5.0 + 1e-9);  // OCS quadrant x>=5 mirrors to x <= -5
        EXPECT_GE(p.y(), 5.0 - 1e-9);
        ++mirrored;
      } else if (p.x() < 5) {
        EXPECT_NEAR(p.norm(), 2.0, 1e-9);
        EXPECT_GE(p.x(), -1e-9);
        EXPECT_GE(p.y(), -1e-9);
        ++arc;
      } else {
        const double x = p.x() - 20, y = p.y();
        EXPECT_NEAR(x * x / 9.0 + y * y / 2.25, 1.0, 1e-9);
        ++ellipse;
      }
    }
    // Chords stay within the chord tolerance (5 mm) of the curve: check the circle's.
    if (s.layer == "COLUMNS") {
      EXPECT_LT(1.0 - (0.5 * (s.a + s.b) - Eigen::Vector2d(10, 0)).norm(), 0.0051);
    }
  }
  EXPECT_GT(arc, 4);
  EXPECT_GT(circle, 16);
  EXPECT_GT(ellipse, 16);
  EXPECT_GT(mirrored, 4);
  EXPECT_TRUE([&] {
    for (const auto& s : plan.segments)
      if (s.layer == "MIRRORED" &&
          ((s.a - Eigen::Vector2d(-6, 5)).norm() < 1e-9 || (s.b - Eigen::Vector2d(-6, 5)).norm() < 1e-9))
        return true;
    return false;
  }());
}

TEST(DxfImport, QuadraticSplineIsItsBezier) {
  const FloorPlan plan = import_dxf(data("spline.dxf"));
  ASSERT_FALSE(plan.segments.empty());
  double max_y = 0.0;
  bool starts = false, ends = false;
  for (const auto& s : plan.segments)
    for (const Eigen::Vector2d& p : {s.a, s.b}) {
      // Bezier (0,0) (1,2) (2,0): x = 2t, y = 4t(1-t) -> y = 2x - x^2.
      EXPECT_NEAR(p.y(), 2 * p.x() - p.x() * p.x(), 1e-6);
      max_y = std::max(max_y, p.y());
      starts |= p.norm() < 1e-9;
      ends |= (p - Eigen::Vector2d(2, 0)).norm() < 1e-6;
    }
  EXPECT_NEAR(max_y, 1.0, 0.005);
  EXPECT_TRUE(starts);
  EXPECT_TRUE(ends);
}

TEST(DxfImport, NestedMirroredRotatedArrayedBlocksInInches) {
  DxfImportReport report;
  const FloorPlan plan = import_dxf(data("blocks_in.dxf"), {}, &report);
  EXPECT_EQ(plan.units, "in");
  const double in = 0.0254;
  // p -> (10,0) + R90 (S p + (5c, 4r)), S = diag(-2, 1), R90 (x, y) = (-y, x).
  auto place = [&](Eigen::Vector2d p, int c, int r) -> Eigen::Vector2d {
    const Eigen::Vector2d q(-2 * p.x() + 5 * c, p.y() + 4 * r);
    return Eigen::Vector2d(10 - q.y(), q.x()) * in;
  };
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 2; ++r) {
      EXPECT_TRUE(has_segment(plan, place({0, 0}, c, r), place({1, 0}, c, r), 1e-9)) << c << "," << r;
      // The nested TICK: (1,0)-(1,1) in COL's frame.
      EXPECT_TRUE(has_segment(plan, place({1, 0}, c, r), place({1, 1}, c, r), 1e-9)) << c << "," << r;
    }
  EXPECT_EQ(plan.segments.size(), 12u);
  for (const auto& s : plan.segments) EXPECT_EQ(s.layer, "COLUMNS");  // layer 0 inherits the INSERT's layer
  EXPECT_TRUE(plan.segments[0].occluder);                             // COL... guessed as a column layer
  EXPECT_EQ(report.blocks_expanded, 12);
}

TEST(DxfImport, FeetAndBlockBasePoint) {
  const FloorPlan plan = import_dxf(data("feet.dxf"));
  EXPECT_TRUE(has_segment(plan, {0, 0}, {3.048, 0}, 1e-12));
  EXPECT_TRUE(has_segment(plan, {0, 5 * 0.3048}, {0.3048, 5 * 0.3048}, 1e-12));
}

TEST(DxfImport, TextAndMTextBecomeLabels) {
  const FloorPlan plan = import_dxf(data("text.dxf"));
  ASSERT_EQ(plan.labels.size(), 2u);
  EXPECT_EQ(plan.labels[0].text, "Kitchen");
  EXPECT_NEAR((plan.labels[0].position - Eigen::Vector2d(1, 2)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(plan.labels[0].height, 0.25, 1e-12);
  EXPECT_EQ(plan.labels[1].text, "Hall");
  EXPECT_NEAR((plan.labels[1].position - Eigen::Vector2d(3, 4)).norm(), 0.0, 1e-12);
  EXPECT_FALSE(plan.find_layer("ANNOTATION")->occluder);
}

void expect_error(const std::string& file, const std::string& fragment) {
  try {
    import_dxf(data(file));
    FAIL() << file << " was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(DxfImport, BadFilesGiveClearErrors) {
  expect_error("binary.dxf", "binary");  // the sentinel, then noise
  expect_error("no_geometry.dxf", "no 2-D plan geometry");
  expect_error("absurd.dxf", "out of range");  // its only line reaches 1e13 units: skipped, nothing left
  expect_error("absent.dxf", "cannot open");
  EXPECT_THROW(import_dxf_from_memory("", "empty.dxf"), Error);
  EXPECT_THROW(import_dxf_from_memory("0\nSECTION\n2\nENTITIES\n0\nLINE\n8\n0\n10\n1e308\n", "x.dxf"), Error);
}

// Integer group codes beyond int (found by the fuzzer under UBSan: block flags 4.6e11, $INSUNITS 2.7e10):
// read as absent, never converted out of range.
TEST(DxfImport, IntegerCodesBeyondIntAreIgnoredNotOverflowed) {
  const std::string dxf =
      "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n26624838613\n0\nENDSEC\n"
      "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n"
      "0\nLAYER\n2\nWALLS\n62\n-2147483648\n70\n1e20\n"  // colour INT_MIN: off (negative), 256 at most
      "0\nENDTAB\n0\nENDSEC\n"
      "0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nB\n70\n461632000000\n10\n0\n20\n0\n"
      "0\nLINE\n8\nWALLS\n10\n0\n20\n0\n11\n2\n21\n0\n0\nENDBLK\n0\nENDSEC\n"
      "0\nSECTION\n2\nENTITIES\n0\nINSERT\n8\nWALLS\n2\nB\n10\n1\n20\n1\n"
      "0\nLINE\n8\nWALLS\n10\n0\n20\n0\n11\n4\n21\n0\n0\nENDSEC\n0\nEOF\n";
  DxfImportReport report;
  const FloorPlan plan = import_dxf_from_memory(dxf, "flags.dxf", {}, &report);
  EXPECT_NE(report.units_reason.find("no $INSUNITS"), std::string::npos) << report.units_reason;
  ASSERT_FALSE(plan.layers.empty());
  EXPECT_EQ(plan.layers[0].name, "WALLS");
  EXPECT_EQ(plan.layers[0].color, 256);
  EXPECT_FALSE(plan.layers[0].visible);
  // The block's flags are unreadable, so it is not external: its line is inserted next to the plain one.
  double length = 0.0;
  for (const PlanSegment& seg : plan.segments) length += seg.length();
  EXPECT_NEAR(length, 4.0 + 2.0, 1e-9);
}

// Broken files import what is readable and say what was not (the whole-file guards are gone).
TEST(DxfImport, BrokenFilesImportWhatIsReadable) {
  DxfImportReport report;
  const FloorPlan truncated = import_dxf(data("truncated.dxf"), {}, &report);  // cut in half
  EXPECT_FALSE(truncated.segments.empty());
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings.front().find("cut short"), std::string::npos) << report.warnings.front();

  // A group code line reading "xx" in the first LINE: that line is lost, the other five are read.
  const FloorPlan garbled = import_dxf(data("bad_group_code.dxf"), {}, &report);
  EXPECT_EQ(report.entities_by_layer["WALLS"]["LINE"], 5);
  EXPECT_EQ(report.entities_skipped, 1);

  // "1O000" (a letter O) in the second LINE: that entity is skipped with its line and why.
  const FloorPlan bad_number = import_dxf(data("bad_number.dxf"), {}, &report);
  EXPECT_EQ(report.entities_by_layer["WALLS"]["LINE"], 5);
  ASSERT_EQ(report.skipped.size(), 1u);
  EXPECT_EQ(report.skipped[0].kind, "LINE");
  EXPECT_EQ(report.skipped[0].layer, "WALLS");
  EXPECT_GT(report.skipped[0].line, 0u);
  EXPECT_NE(report.skipped[0].why.find("not a number"), std::string::npos) << report.skipped[0].why;
}

TEST(DxfImport, UnitTable) {
  EXPECT_DOUBLE_EQ(metres_per_unit("in"), 0.0254);
  EXPECT_DOUBLE_EQ(metres_per_unit("ft"), 0.3048);
  EXPECT_EQ(units_of_insunits(4), "mm");
  EXPECT_EQ(units_of_insunits(5), "cm");
  EXPECT_EQ(units_of_insunits(0), "");
}

}  // namespace
}  // namespace plenopath
