// The DXF writer against the DXF importer: the office sample written in millimetres reads back as the same
// plan (in metres) that flatten_drawing builds in code.
#include "processing/plan/dxf_export.h"

#include <gtest/gtest.h>

#include <map>

#include "model/error.h"
#include "processing/plan/dxf_import.h"
#include "rig/plan_drawing.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

std::map<std::string, double> length_per_layer(const FloorPlan& plan) {
  std::map<std::string, double> out;
  for (const auto& s : plan.segments) out[s.layer] += s.length();
  return out;
}

TEST(DxfExport, OfficeSampleReadsBackInMetres) {
  const std::string file = testing::TempDir() + "/office_export.dxf";
  write_dxf(make_office_sample_drawing(), file);
  DxfImportReport report;
  const FloorPlan imported = import_dxf(file, {}, &report);
  EXPECT_EQ(report.units, "mm");
  EXPECT_TRUE(report.units_from_header);
  EXPECT_GE(report.blocks_expanded, 15);  // the furniture inserts

  const FloorPlan built = make_office_sample_plan();
  const PlanExtents a = imported.extents(), b = built.extents();
  EXPECT_NEAR((a.min - b.min).norm(), 0.0, 1e-6);
  EXPECT_NEAR((a.max - b.max).norm(), 0.0, 1e-6);
  // Straight geometry keeps its length exactly; circles and arcs are tessellated differently, so the
  // layers holding them (COLUMNS, DOORS) agree only to the chord error.
  const auto la = length_per_layer(imported), lb = length_per_layer(built);
  EXPECT_NEAR(la.at("WALLS"), lb.at("WALLS"), 1e-6);
  EXPECT_NEAR(la.at("FURNITURE"), lb.at("FURNITURE"), 1e-6);
  EXPECT_NEAR(la.at("COLUMNS"), lb.at("COLUMNS"), 0.02);
  EXPECT_NEAR(la.at("DOORS"), lb.at("DOORS"), 0.05);
  ASSERT_EQ(imported.labels.size(), built.labels.size());
  for (const auto& l : built.labels) {
    bool found = false;
    for (const auto& m : imported.labels)
      found = found || (m.text == l.text && (m.position - l.position).norm() < 1e-6 &&
                        std::abs(m.height - l.height) < 1e-6);
    EXPECT_TRUE(found) << l.text;
  }
  const PlanLayer* walls = imported.find_layer("WALLS");
  ASSERT_NE(walls, nullptr);
  EXPECT_TRUE(walls->occluder);
  EXPECT_FALSE(imported.find_layer("DOORS")->occluder);
}

TEST(DxfExport, RendersTheSameWallsAsTheBuiltInPlan) {
  const std::string file = testing::TempDir() + "/office_export2.dxf";
  write_dxf(make_office_sample_drawing(), file, {"m"});
  const SyntheticScene from_dxf = build_synthetic_scene(import_dxf(file));
  const SyntheticScene built = build_synthetic_scene(make_office_sample_plan());
  EXPECT_EQ(from_dxf.footprints.size(),
            built.footprints.size());  // furniture inserts arrive as closed outlines
  RenderOptions options;
  options.width = 128;
  options.height = 64;
  const PathFrame pose{0, "", 4.0, 7.5, 0.0, 1.0, kFrameOk, ""};  // the corridor: walls and doorways only
  const cv::Mat a = render_panorama(from_dxf, pose, options).depth,
                b = render_panorama(built, pose, options).depth;
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  EXPECT_LT(cv::countNonZero(diff > 1e-4), 10);  // the importer may split segments; surfaces stay put
}

TEST(DxfExport, ErrorsNameTheFile) {
  PlanDrawing d = make_office_sample_drawing();
  d.inserts.push_back({"NO_SUCH_BLOCK", {0, 0}, 0.0, "FURNITURE"});
  try {
    write_dxf(d, testing::TempDir() + "/bad.dxf");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("NO_SUCH_BLOCK"), std::string::npos);
  }
  EXPECT_THROW(write_dxf(make_office_sample_drawing(), "/nonexistent-folder/x.dxf"), Error);
  EXPECT_THROW(write_dxf(make_office_sample_drawing(), testing::TempDir() + "/u.dxf", {"furlong"}), Error);
}

TEST(DxfExport, PlanToDrawingKeepsOutlinesWhole) {
  const FloorPlan plan = make_office_sample_plan();
  const PlanDrawing d = drawing_from_plan(plan);
  EXPECT_EQ(d.polylines.size(), plan.outlines.size());
  EXPECT_EQ(d.texts.size(), plan.labels.size());
  const std::string file = testing::TempDir() + "/plan_export.dxf";
  write_dxf(d, file);
  const FloorPlan back = import_dxf(file);
  EXPECT_NEAR(length_per_layer(back).at("WALLS"), length_per_layer(plan).at("WALLS"), 1e-6);
}

}  // namespace
}  // namespace plenopath
