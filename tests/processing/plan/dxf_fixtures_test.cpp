// The DXF fixtures written with python3-ezdxf (tests/data/dxf/make_fixtures_ezdxf.py: binary R12 and R2018,
// code pages 1252 and 936, MTEXT codes, hatch walls, unitless and contradicting units, far from the origin
// (millimetres in place, metres at projected coordinates re-centred) with a stray line, xref-bound layer
// names, walls on layer 0, MLINE walls, nested mirrored inserts), each imported with default options and
// checked against the NAME.expected.json the script wrote from what it drew: units, size in metres, extents
// in the DXF frame, layers that block sight, labels, counts, strays.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "processing/plan/dxf_import.h"

namespace plenopath {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kSuffix = ".expected.json";

fs::path fixture_dir() { return fs::path(PLENOPATH_TEST_DATA_DIR) / "dxf"; }

std::vector<std::string> fixture_names() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fixture_dir())) {
    const std::string file = entry.path().filename().string();
    if (file.size() > kSuffix.size() &&
        file.compare(file.size() - kSuffix.size(), kSuffix.size(), kSuffix) == 0)
      names.push_back(file.substr(0, file.size() - kSuffix.size()));
  }
  std::sort(names.begin(), names.end());
  return names;
}

json read_expectation(const std::string& name) {
  std::ifstream in(fixture_dir() / (name + kSuffix));
  return json::parse(in);
}

// Extents of one layer's segments and outlines (plan frame, metres); all layers when `layer` is empty.
PlanExtents layer_extents(const FloorPlan& plan, const std::string& layer) {
  PlanExtents e;
  auto add = [&e](const Eigen::Vector2d& p) {
    e.min = e.valid ? e.min.cwiseMin(p) : p;
    e.max = e.valid ? e.max.cwiseMax(p) : p;
    e.valid = true;
  };
  for (const auto& s : plan.segments)
    if (layer.empty() || s.layer == layer) {
      add(s.a);
      add(s.b);
    }
  for (const auto& o : plan.outlines)
    if (layer.empty() || o.layer == layer)
      for (const auto& p : o.points) add(p);
  return e;
}

// Expected extents {"min":[x,y],"max":[x,y]} in metres in the DXF frame against plan extents + dxf_origin_m.
void expect_extents(const json& expected, const PlanExtents& e, const Eigen::Vector2d& origin, double tol,
                    const std::string& what) {
  ASSERT_TRUE(e.valid) << what << ": no geometry";
  const Eigen::Vector2d min = e.min + origin, max = e.max + origin;
  EXPECT_NEAR(min.x(), expected["min"][0].get<double>(), tol) << what << " min x";
  EXPECT_NEAR(min.y(), expected["min"][1].get<double>(), tol) << what << " min y";
  EXPECT_NEAR(max.x(), expected["max"][0].get<double>(), tol) << what << " max x";
  EXPECT_NEAR(max.y(), expected["max"][1].get<double>(), tol) << what << " max y";
}

class DxfFixture : public ::testing::TestWithParam<std::string> {};

TEST(DxfFixtures, EachFixtureHasItsExpectation) {
  // make_fixtures_ezdxf.py writes ez_*.dxf with ez_*.expected.json beside it; a missing expectation file
  // would silently drop a case.
  std::size_t dxf_files = 0;
  for (const auto& entry : fs::directory_iterator(fixture_dir())) {
    const std::string file = entry.path().filename().string();
    if (file.rfind("ez_", 0) != 0 || entry.path().extension() != ".dxf") continue;
    ++dxf_files;
    EXPECT_TRUE(fs::exists(fixture_dir() / (entry.path().stem().string() + kSuffix))) << file;
  }
  EXPECT_EQ(fixture_names().size(), dxf_files);
  EXPECT_GE(dxf_files, 13u);
}

TEST_P(DxfFixture, ImportsAsDrawn) {
  const std::string name = GetParam();
  const json x = read_expectation(name);
  const std::string file = (fixture_dir() / x["file"].get<std::string>()).string();
  DxfImportReport report;
  FloorPlan plan;
  ASSERT_NO_THROW(plan = import_dxf(file, {}, &report)) << file;

  // What the file is.
  EXPECT_EQ(report.version, x["version"].get<std::string>());
  EXPECT_EQ(report.binary, x["binary"].get<bool>());
  if (x.contains("codepage")) {
    EXPECT_EQ(report.codepage, x["codepage"].get<std::string>());
  }

  // Units and how they were found.
  EXPECT_EQ(plan.units, x["units"].get<std::string>()) << report.units_reason;
  EXPECT_DOUBLE_EQ(plan.metres_per_unit, metres_per_unit(x["units"].get<std::string>()));
  const auto sources = x["units_source_any_of"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(sources.begin(), sources.end(), report.units_source), sources.end())
      << "units source " << report.units_source << ": " << report.units_reason;

  // Size and place of the building (strays left out), re-centring.
  const double tol = x["size_tolerance_m"].get<double>();
  const PlanExtents e = plan.extents();
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.size().x(), x["size_m"][0].get<double>(), tol);
  EXPECT_NEAR(e.size().y(), x["size_m"][1].get<double>(), tol);
  expect_extents(x["extents_dxf_m"], e, plan.dxf_origin_m, tol, "building");
  if (x["recentred"].get<bool>()) {
    EXPECT_GT(plan.dxf_origin_m.norm(), 0.0);
    EXPECT_LT(std::max(e.min.cwiseAbs().maxCoeff(), e.max.cwiseAbs().maxCoeff()),
              DxfImportOptions{}.recentre_beyond_m);
  } else {
    EXPECT_EQ(plan.dxf_origin_m, Eigen::Vector2d::Zero());
  }
  EXPECT_EQ(report.origin_m, plan.dxf_origin_m);
  EXPECT_EQ(report.stray_entities, x["stray_entities"].get<int>());
  if (x.contains("layer_extents_dxf_m"))
    for (const auto& [layer, box] : x["layer_extents_dxf_m"].items())
      expect_extents(box, layer_extents(plan, layer), plan.dxf_origin_m, tol, "layer " + layer);

  // Layers (UTF-8 names) and which of them block sight.
  for (const auto& layer : x["layers"])
    EXPECT_NE(plan.find_layer(layer.get<std::string>()), nullptr) << layer;
  for (const auto& layer : x["occluder_layers"]) {
    const PlanLayer* l = plan.find_layer(layer.get<std::string>());
    ASSERT_NE(l, nullptr) << layer;
    EXPECT_TRUE(l->occluder) << layer << " should block sight";
    const auto occluding = plan.occluder_segments();
    EXPECT_TRUE(std::any_of(occluding.begin(), occluding.end(),
                            [&](const PlanSegment& s) { return s.layer == l->name; }))
        << layer << " has no occluding segments";
  }
  for (const auto& layer : x["not_occluder_layers"]) {
    const PlanLayer* l = plan.find_layer(layer.get<std::string>());
    ASSERT_NE(l, nullptr) << layer;
    EXPECT_FALSE(l->occluder) << layer << " should not block sight"
                              << (report.occluder_reasons.count(l->name)
                                      ? ": " + report.occluder_reasons.at(l->name)
                                      : "");
  }

  // Labels in UTF-8; an array lists the spellings accepted for one label (%%c: U+2300 or U+00D8).
  for (const auto& label : x["labels"]) {
    const std::vector<std::string> any_of = label.is_array()
                                                ? label.get<std::vector<std::string>>()
                                                : std::vector<std::string>{label.get<std::string>()};
    const bool found = std::any_of(plan.labels.begin(), plan.labels.end(), [&](const PlanLabel& l) {
      return std::find(any_of.begin(), any_of.end(), l.text) != any_of.end();
    });
    std::string have;
    for (const auto& l : plan.labels) have += " [" + l.text + "]";
    EXPECT_TRUE(found) << "label " << label.dump() << " not among" << have;
  }

  // Model-space entities read, per layer and kind.
  const auto counts = x["entities_by_layer"].get<std::map<std::string, std::map<std::string, int>>>();
  EXPECT_EQ(report.entities_by_layer, counts);
}

INSTANTIATE_TEST_SUITE_P(Ezdxf, DxfFixture, ::testing::ValuesIn(fixture_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace plenopath
