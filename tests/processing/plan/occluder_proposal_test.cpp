// Which layers block sight, on plans built by hand in metres: names first, geometry when no name says so.
#include "processing/plan/occluder_proposal.h"

#include <gtest/gtest.h>

#include <chrono>
#include <iostream>

namespace plenopath {
namespace {

struct PlanBuilder {
  FloorPlan plan;
  void layer(const std::string& name) {
    if (!plan.find_layer(name)) plan.layers.push_back({name});
  }
  void line(const std::string& l, double x0, double y0, double x1, double y1) {
    layer(l);
    plan.segments.push_back({{x0, y0}, {x1, y1}, l, false});
  }
  // A closed outline and its edges, as the importer delivers them.
  void closed(const std::string& l, const std::vector<Eigen::Vector2d>& pts) {
    layer(l);
    plan.outlines.push_back({pts, l, true});
    for (std::size_t i = 0; i < pts.size(); ++i)
      plan.segments.push_back({pts[i], pts[(i + 1) % pts.size()], l, false});
  }
  void rect(const std::string& l, double x, double y, double w, double h) {
    closed(l, {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}});
  }
  void label(const std::string& l, double x, double y, const std::string& text) {
    layer(l);
    plan.labels.push_back({{x, y}, text, 0.25, l});
  }
  // A 12 x 8 m office, walls 0.2 m thick drawn as two lines, a partition at x = 6 with a 0.9 m opening.
  void office_walls(const std::string& l) {
    line(l, 0, 0, 12, 0);
    line(l, 12, 0, 12, 8);
    line(l, 12, 8, 0, 8);
    line(l, 0, 8, 0, 0);
    line(l, 0.2, 0.2, 11.8, 0.2);
    line(l, 11.8, 0.2, 11.8, 7.8);
    line(l, 11.8, 7.8, 0.2, 7.8);
    line(l, 0.2, 7.8, 0.2, 0.2);
    line(l, 5.9, 0.2, 5.9, 3);
    line(l, 6.1, 0.2, 6.1, 3);
    line(l, 5.9, 3.9, 5.9, 7.8);
    line(l, 6.1, 3.9, 6.1, 7.8);
    line(l, 5.9, 3, 6.1, 3);
    line(l, 5.9, 3.9, 6.1, 3.9);
  }
  // Desks, chairs, cabinets and a sofa of varied sizes, 0.5-2 m.
  void furniture(const std::string& l) {
    const double sizes[][2] = {{1.6, 0.8}, {0.5, 0.5}, {0.55, 0.5}, {2.0, 0.9}, {1.2, 0.6},
                               {0.8, 0.4}, {1.8, 0.8}, {0.6, 0.6},  {1.0, 0.5}, {1.4, 0.7}};
    for (int i = 0; i < 10; ++i) rect(l, 1 + (i % 5) * 2.0, 1 + (i / 5) * 3.0, sizes[i][0], sizes[i][1]);
  }
};

const OccluderProposal& proposal(const std::vector<OccluderProposal>& all, const std::string& layer) {
  for (const auto& p : all)
    if (p.layer == layer) return p;
  static OccluderProposal none;
  ADD_FAILURE() << "no proposal for " << layer;
  return none;
}

void print(const std::vector<OccluderProposal>& all) {
  for (const auto& p : all)
    std::cout << "  " << p.layer << ": " << (p.occluder ? "yes" : "no") << " -- " << p.reason << "\n";
}

TEST(OccluderProposal, WallsOnLayerZeroNextToTextAndFurniture) {
  PlanBuilder b;
  b.office_walls("0");
  b.label("TEXT", 3, 4, "Office 1");
  b.label("TEXT", 9, 4, "Office 2");
  b.line("TEXT", 2.5, 3.8, 3.5, 3.8);  // an underline
  b.furniture("FURNITURE");
  b.furniture("L2");  // the same furniture on a layer whose name says nothing
  const auto all = propose_occluder_layers(b.plan, {});
  print(all);
  ASSERT_EQ(all.size(), 4u);
  const auto& zero = proposal(all, "0");
  EXPECT_TRUE(zero.occluder);
  // Pairs: 4 outer walls and 2 partition pieces, all 0.2 m apart.
  EXPECT_NE(zero.reason.find("6 parallel line pairs 0.20 m apart"), std::string::npos) << zero.reason;
  EXPECT_FALSE(proposal(all, "TEXT").occluder);
  EXPECT_FALSE(proposal(all, "FURNITURE").occluder);
  EXPECT_NE(proposal(all, "FURNITURE").reason.find("furniture"), std::string::npos);
  EXPECT_FALSE(proposal(all, "L2").occluder) << proposal(all, "L2").reason;
}

TEST(OccluderProposal, SolidHatchedWalls) {
  // Walls only as solid-filled outlines (the lines around them are the hatch boundaries): an L-shaped
  // corner, two straight walls and a short stub, 0.25 m thick, on a layer named "Layer 5". Room fills (big
  // coloured polygons, also solid) on "Z1" are not walls.
  PlanBuilder b;
  b.closed("Layer 5", {{0, 0}, {10, 0}, {10, 0.25}, {0.25, 0.25}, {0.25, 6}, {0, 6}});
  b.rect("Layer 5", 9.75, 0.25, 0.25, 5.75);
  b.rect("Layer 5", 0, 6, 10, 0.25);
  b.rect("Layer 5", 5, 0.25, 0.25, 1.5);
  b.rect("Z1", 0.25, 0.25, 4.75, 5.75);
  b.rect("Z1", 5.25, 0.25, 4.5, 5.75);
  const auto all = propose_occluder_layers(b.plan, {{"Layer 5", 4}, {"Z1", 2}});
  print(all);
  const auto& walls = proposal(all, "Layer 5");
  EXPECT_TRUE(walls.occluder);
  EXPECT_NE(walls.reason.find("4 solid-filled outlines: 4 wall-like"), std::string::npos) << walls.reason;
  EXPECT_FALSE(proposal(all, "Z1").occluder) << proposal(all, "Z1").reason;
  // Without the solid-fill counts, the outline edges still pair up as two-line walls.
  EXPECT_TRUE(proposal(propose_occluder_layers(b.plan, {}), "Layer 5").occluder);
}

TEST(OccluderProposal, SolidFillsOnAWallPatternLayerAreTheWalls) {
  // Walls drawn only as poche on "A-WALL-PATT" (votes no by name: a pattern), columns on "S-COLS", room
  // fills on "A-AREA-PATT" (not walls in name or shape), and big solid fills on a second wall pattern
  // layer that are not wall-shaped (4 x 4 m squares).
  PlanBuilder b;
  b.closed("A-WALL-PATT", {{0, 0}, {10, 0}, {10, 0.25}, {0.25, 0.25}, {0.25, 6}, {0, 6}});
  b.rect("A-WALL-PATT", 9.75, 0.25, 0.25, 5.75);
  b.rect("S-COLS", 5, 3, 0.4, 0.4);
  b.rect("A-AREA-PATT", 0.25, 0.25, 9.5, 5.75);
  b.rect("Wandschraffur", 20, 0, 4, 4);
  b.rect("Wandschraffur", 30, 0, 4, 4);
  const auto all =
      propose_occluder_layers(b.plan, {{"A-WALL-PATT", 2}, {"A-AREA-PATT", 1}, {"Wandschraffur", 2}});
  print(all);
  EXPECT_TRUE(proposal(all, "S-COLS").occluder);
  const auto& poche = proposal(all, "A-WALL-PATT");
  EXPECT_TRUE(poche.occluder);
  EXPECT_EQ(poche.reason,
            "2 solid-filled outlines: 2 wall-like 0.24-0.25 m thick on a wall pattern layer (AIA 'PATT' "
            "(hatch patterns))");
  EXPECT_FALSE(proposal(all, "A-AREA-PATT").occluder);
  EXPECT_FALSE(proposal(all, "Wandschraffur").occluder);
  // Without fills the pattern layer stays out: its name says no.
  EXPECT_FALSE(proposal(propose_occluder_layers(b.plan, {}), "A-WALL-PATT").occluder);
}

TEST(OccluderProposal, SolidFilledWallPiecesAlone) {
  // A wall hatched bay by bay: six solid pieces of 1.5 x 0.2 m (each too small to pair as two-line walls,
  // too thin to be a column), on "Layer 6"; long single lines elsewhere on "Layer 7".
  PlanBuilder b;
  for (int k = 0; k < 6; ++k) b.rect("Layer 6", k * 1.6, 0, 1.5, 0.2);
  for (int k = 0; k < 4; ++k) b.line("Layer 7", 0, 2 + k * 3.0, 30, 2 + k * 3.0);
  const auto all = propose_occluder_layers(b.plan, {{"Layer 6", 6}});
  print(all);
  const auto& fills = proposal(all, "Layer 6");
  EXPECT_TRUE(fills.occluder);
  EXPECT_EQ(fills.reason, "6 solid-filled outlines: 6 wall-like 0.18 m thick") << fills.reason;
  EXPECT_FALSE(proposal(all, "Layer 7").occluder);
  // The same pieces without fills say nothing; then the single-line fallback takes the layer with most lines.
  const auto plain = propose_occluder_layers(b.plan, {});
  EXPECT_FALSE(proposal(plain, "Layer 6").occluder);
  EXPECT_TRUE(proposal(plain, "Layer 7").occluder);
}

TEST(OccluderProposal, HundredThousandSegments) {
  // 79 x 79 rooms of 4 m with 0.2 m walls as two lines cut into 1 m pieces (101 120 segments) on "0", a
  // 0.4 m column at every crossing on "C" (6 400), labels on "TEXT".
  PlanBuilder b;
  const int rooms = 79;
  const double span = rooms * 4.0;
  b.layer("0");
  for (int w = 0; w <= rooms; ++w)
    for (double face : {w * 4.0 - 0.1, w * 4.0 + 0.1})
      for (double t = 0; t < span; t += 1.0) {
        b.plan.segments.push_back({{face, t}, {face, t + 1}, "0", false});
        b.plan.segments.push_back({{t, face}, {t + 1, face}, "0", false});
      }
  for (int i = 0; i <= rooms; ++i)
    for (int j = 0; j <= rooms; ++j) b.rect("C", i * 4.0 - 0.2, j * 4.0 - 0.2, 0.4, 0.4);
  b.label("TEXT", 1, 1, "Room");
  const auto start = std::chrono::steady_clock::now();
  const auto all = propose_occluder_layers(b.plan, {});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << b.plan.segments.size() << " segments: " << seconds << " s\n";
  print(all);
  EXPECT_TRUE(proposal(all, "0").occluder);
  EXPECT_TRUE(proposal(all, "C").occluder);
  EXPECT_FALSE(proposal(all, "TEXT").occluder);
}

TEST(OccluderProposal, ColumnsOnly) {
  // A 4 x 3 grid of 0.4 m square columns every 6 m, and two round ones (16-gons of 0.5 m), on "Layer 3";
  // furniture of varied sizes on "Layer 4"; text on "TEXT".
  PlanBuilder b;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) b.rect("Layer 3", i * 6.0, j * 6.0, 0.4, 0.4);
  for (int k = 0; k < 2; ++k) {
    std::vector<Eigen::Vector2d> disc;
    for (int a = 0; a < 16; ++a)
      disc.push_back({3 + 6 * k + 0.25 * std::cos(a * M_PI / 8), 3 + 0.25 * std::sin(a * M_PI / 8)});
    b.closed("Layer 3", disc);
  }
  b.furniture("Layer 4");
  b.label("TEXT", 1, 1, "Hall");
  const auto all = propose_occluder_layers(b.plan, {});
  print(all);
  const auto& columns = proposal(all, "Layer 3");
  EXPECT_TRUE(columns.occluder);
  EXPECT_NE(columns.reason.find("14 small closed outlines 0.40-0.50 m across (columns)"), std::string::npos)
      << columns.reason;
  EXPECT_FALSE(proposal(all, "Layer 4").occluder) << proposal(all, "Layer 4").reason;
  EXPECT_FALSE(proposal(all, "TEXT").occluder);
  EXPECT_EQ(proposal(all, "TEXT").reason.substr(0, 7), "English");
}

TEST(OccluderProposal, NamesDecideWhenOneSaysWall) {
  PlanBuilder b;
  b.office_walls("A-WALL");
  b.office_walls("0");  // wall-like geometry, but a name already says where the walls are
  b.rect("S-COLS", 3, 3, 0.4, 0.4);
  b.line("A-DOOR", 2, 0.2, 2, 1.1);
  b.line("Wand (neu)", 20, 0, 25, 0);
  const auto all = propose_occluder_layers(b.plan, {});
  print(all);
  EXPECT_TRUE(proposal(all, "A-WALL").occluder);
  EXPECT_EQ(proposal(all, "A-WALL").reason, "English 'wall'");
  EXPECT_TRUE(proposal(all, "S-COLS").occluder);
  EXPECT_TRUE(proposal(all, "Wand (neu)").occluder);
  EXPECT_FALSE(proposal(all, "A-DOOR").occluder);
  EXPECT_FALSE(proposal(all, "0").occluder);
  EXPECT_NE(proposal(all, "0").reason.find("name the walls"), std::string::npos);
}

TEST(OccluderProposal, HatchPatternsAndTextAreNeverWalls) {
  // An exploded hatch: 30 parallel lines 0.3 m apart, 6 m long, on "L9"; text on "L8"; walls drawn with
  // single lines on "0" (no pairs): the fallback takes "0", the layer holding most lines that is not a
  // pattern or text.
  PlanBuilder b;
  for (int k = 0; k < 30; ++k) b.line("L9", 0, k * 0.3, 6, k * 0.3);
  for (int k = 0; k < 8; ++k) b.label("L8", k, 0, "T" + std::to_string(k));
  for (int k = 0; k <= 5; ++k) {
    b.line("0", k * 5.0, 0, k * 5.0, 25);
    b.line("0", 0, k * 5.0, 25, k * 5.0);
  }
  const auto all = propose_occluder_layers(b.plan, {});
  print(all);
  EXPECT_FALSE(proposal(all, "L9").occluder);
  EXPECT_NE(proposal(all, "L9").reason.find("hatch pattern"), std::string::npos)
      << proposal(all, "L9").reason;
  EXPECT_FALSE(proposal(all, "L8").occluder);
  EXPECT_EQ(proposal(all, "L8").reason, "text only");
  EXPECT_TRUE(proposal(all, "0").occluder);
  EXPECT_NE(proposal(all, "0").reason.find("single lines"), std::string::npos);
  // With only the pattern and the text, nothing is proposed.
  PlanBuilder c;
  for (int k = 0; k < 30; ++k) c.line("L9", 0, k * 0.3, 6, k * 0.3);
  c.label("L8", 0, 0, "x");
  for (const auto& p : propose_occluder_layers(c.plan, {})) EXPECT_FALSE(p.occluder) << p.layer;
}

}  // namespace
}  // namespace plenopath
