// A hall whose windows are drawn as gaps in its outer wall, each wall a closed outline (as the POV-Ray
// scenes' plans and many architects' plans draw them): the hall is inside, not part of the outside.
// Truths: a ray caster against the plan glazed by hand at the walls' inner face, and hand-built geometry.
#include <gtest/gtest.h>

#include "processing/visibility/visibility.h"
#include "tests/processing/plan/plan_oracle.h"

namespace plenopath {
namespace {

using Vec = Eigen::Vector2d;

// 10 x 6 m, walls 0.2 m thick, two 1.6 m windows in the south wall (x 2.2-3.8 and 6.2-7.8), a 0.4 m
// square column at (5, 3).
FloorPlan hall() {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  test::add_thick_wall(&plan, {0, 0}, {2.1, 0}, 0.2);
  test::add_thick_wall(&plan, {3.9, 0}, {6.1, 0}, 0.2);
  test::add_thick_wall(&plan, {7.9, 0}, {10, 0}, 0.2);
  test::add_thick_wall(&plan, {10, 0}, {10, 6}, 0.2);
  test::add_thick_wall(&plan, {10, 6}, {0, 6}, 0.2);
  test::add_thick_wall(&plan, {0, 6}, {0, 0}, 0.2);
  test::add_rectangle(&plan, {5, 3}, 0.4, 0.4, 0.0);
  return plan;
}

TEST(VisibilityOpenings, AHallWithWindowsDrawnAsGapsIsInside) {
  const FloorPlan plan = hall();
  const VisibilityIndex index(plan);
  EXPECT_GE(index.closed_openings().size(), 2u);
  // The oracle: the same plan with glass drawn by hand across each window at the inner face (y = 0.1).
  std::vector<PlanSegment> glazed = plan.segments;
  glazed.push_back({{2.2, 0.1}, {3.8, 0.1}, "GLASS", true});
  glazed.push_back({{6.2, 0.1}, {7.8, 0.1}, "GLASS", true});
  for (const Vec& p : {Vec(2, 3), Vec(3, 0.5), Vec(8.5, 4.5), Vec(5, 1.2)}) {
    const Envelope e = index.envelope(p);
    ASSERT_EQ(e.status, EnvelopeStatus::ok) << p.transpose() << ": " << to_string(e.status);
    EXPECT_NEAR(e.area / test::ray_cast_area(glazed, p, 20000), 1.0, 1e-3) << p.transpose();
    EXPECT_NEAR(index.envelope_area(p) / e.area, 1.0, 1e-6) << p.transpose();
  }
  EXPECT_EQ(index.classify({5, 3}), EnvelopeStatus::inside_obstacle);  // the column
  EXPECT_EQ(index.classify({5, 6.05}), EnvelopeStatus::on_wall);       // the north wall's body
  EXPECT_EQ(index.classify({1, 0.02}), EnvelopeStatus::on_wall);       // the south wall's body
  EXPECT_NE(index.classify({3, 0.0}), EnvelopeStatus::ok);             // in a window's reveal
  EXPECT_EQ(index.classify({3, -1.0}), EnvelopeStatus::outside);
  EXPECT_EQ(index.classify({-1, 3}), EnvelopeStatus::outside);

  // A walk along the hall has cells with envelopes all the way.
  CameraPath path;
  for (int i = 0; i <= 80; ++i) path.frames.push_back({i, "", 0.6 + 0.1 * i, 1.5, 0.0, 1.0, 0, ""});
  const VisibilityCells cells = index.cells_along_path(path);
  ASSERT_FALSE(cells.cells.empty());
  for (const VisibilityCell& c : cells.cells) EXPECT_GT(c.area_mid, 40.0);
}

TEST(VisibilityOpenings, WithClosingOffTheHallIsTheOutside) {
  VisibilityOptions options;
  options.close_openings_up_to_m = 0;
  const VisibilityIndex index(hall(), options);
  EXPECT_TRUE(index.closed_openings().empty());
  EXPECT_EQ(index.classify({2, 3}), EnvelopeStatus::outside);
}

}  // namespace
}  // namespace plenopath
