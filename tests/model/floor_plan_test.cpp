#include "model/floor_plan.h"

#include <gtest/gtest.h>

#include "model/geo_anchor.h"
#include "model/keyframes.h"

namespace plenopath {
namespace {

TEST(FloorPlan, ExtentsCoverSegmentsAndOutlines) {
  FloorPlan plan;
  EXPECT_FALSE(plan.extents().valid);
  plan.segments = {{{1, 2}, {4, -1}, "WALLS", true}};
  plan.outlines = {{{{-3, 0}, {0, 9}}, "COLUMNS", true}};
  const PlanExtents e = plan.extents();
  ASSERT_TRUE(e.valid);
  EXPECT_EQ(e.min, Eigen::Vector2d(-3, -1));
  EXPECT_EQ(e.max, Eigen::Vector2d(4, 9));
}

TEST(FloorPlan, LayerOccluderFlagReachesSegments) {
  FloorPlan plan;
  plan.layers = {{"A-WALL"}, {"FURN"}};
  plan.segments = {{{0, 0}, {1, 0}, "A-WALL", false}, {{0, 0}, {0, 1}, "FURN", false}};
  plan.set_layer_occluder("A-WALL", true);
  EXPECT_TRUE(plan.find_layer("A-WALL")->occluder);
  ASSERT_EQ(plan.occluder_segments().size(), 1u);
  EXPECT_EQ(plan.occluder_segments()[0].layer, "A-WALL");
}

TEST(FloorPlan, GuessesOccluderLayersByName) {
  for (const char* yes : {"WALLS", "A-WALL-FULL", "Columns", "struct", "S-COL"})
    EXPECT_TRUE(guess_layer_is_occluder(yes)) << yes;
  for (const char* no : {"FURNITURE", "DOORS", "TEXT", "A-ANNO-DIMS", "0", "Wall-Text", "Defpoints"})
    EXPECT_FALSE(guess_layer_is_occluder(no)) << no;
}

TEST(GeoAnchor, EnuAndPlanAreInverse) {
  GeoAnchor g;
  g.plan_rotation = 0.4;
  g.scale = 1.25;
  g.plan_origin = {3, -2};
  const Eigen::Vector2d p(7.5, 11.25);
  EXPECT_LT((g.plan_from_enu(g.enu_from_plan(p)) - p).norm(), 1e-12);
  // Plan +X rotated by 90 deg points north.
  g = GeoAnchor{};
  g.plan_rotation = M_PI / 2;
  EXPECT_LT((g.enu_from_plan({1, 0}) - Eigen::Vector2d(0, 1)).norm(), 1e-12);
}

TEST(Keyframes, ProgressiveOrderFollowsRank) {
  Keyframes k;
  k.indices = {0, 10, 20, 30};
  k.rank = {0, 3, 1, 2};
  EXPECT_EQ(k.progressive_order(), (std::vector<int>{0, 20, 30, 10}));
  k.rank.clear();
  EXPECT_EQ(k.progressive_order(), k.indices);
}

}  // namespace
}  // namespace plenopath
