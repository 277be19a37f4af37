// An outer wall drawn with two lines, each a closed loop of its own (as in the office sample): the rooms
// inside are free space and the wall's body is not (regression: the nesting once made the rooms obstacles).
#include <gtest/gtest.h>

#include "processing/visibility/visibility.h"

namespace plenopath {
namespace {

FloorPlan double_wall_plan() {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  auto loop = [&](double x0, double y0, double x1, double y1) {
    const Eigen::Vector2d c[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (int k = 0; k < 4; ++k) plan.segments.push_back({c[k], c[(k + 1) % 4], "WALLS", true});
  };
  loop(0, 0, 10, 6);                                             // outer line of the outer wall
  loop(0.3, 0.3, 9.7, 5.7);                                      // inner line: a 30 cm wall
  plan.segments.push_back({{5, 0.3}, {5, 5.7}, "WALLS", true});  // a partition from wall to wall
  return plan;
}

TEST(VisibilityDoubleWall, RoomsInsideATwoLineOuterWallAreFree) {
  const VisibilityIndex index(double_wall_plan());
  const Envelope left = index.envelope({2.0, 3.0});
  ASSERT_EQ(left.status, EnvelopeStatus::ok) << to_string(left.status);
  EXPECT_NEAR(left.area, 4.7 * 5.4, 1e-9);  // (5 - 0.3) x (5.7 - 0.3), by hand
  const Envelope right = index.envelope({8.0, 1.0});
  ASSERT_EQ(right.status, EnvelopeStatus::ok);
  EXPECT_NEAR(right.area, 4.7 * 5.4, 1e-9);
  EXPECT_NE(index.classify({0.15, 3.0}), EnvelopeStatus::ok);  // inside the wall's body
  EXPECT_EQ(index.classify({-1.0, 3.0}), EnvelopeStatus::outside);
  // A path from one room into the wall is cut where it meets the partition and the inner line.
  CameraPath path;
  for (int i = 0; i <= 40; ++i) path.frames.push_back({i, "", 2.0 + 0.15 * i, 3.0, 0.0, 1.0, 0, ""});
  const VisibilityCells cells = index.cells_along_path(path);
  ASSERT_GE(cells.cells.size(), 2u);
  EXPECT_NEAR(cells.cells.front().area_mid, 4.7 * 5.4, 1e-6);
}

}  // namespace
}  // namespace plenopath
