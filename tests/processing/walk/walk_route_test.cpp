// The walkable line between two spots of the office sample: from the open office to the lab it must go
// through both doorways (the open office's at y 8.5, x 3.0-4.8; the lab's at y 6.5, x 4.0-4.9, as
// rig/office_sample.cpp draws them) and cross no wall, checked by an orientation test of its own (not the
// router's); within one room it is the straight line; a spot walled in has no route.
#include "processing/walk/walk_route.h"

#include <gtest/gtest.h>

#include "model/error.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool properly_cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                    const Eigen::Vector2d& b) {
  return orient(p, q, a) * orient(p, q, b) < 0 && orient(a, b, p) * orient(a, b, q) < 0;
}

// Where the route crosses the line y = level (x), or NaN.
double crossing_x(const std::vector<Eigen::Vector2d>& route, double level) {
  for (std::size_t k = 1; k < route.size(); ++k) {
    const Eigen::Vector2d &p = route[k - 1], &q = route[k];
    if ((p.y() - level) * (q.y() - level) <= 0 && p.y() != q.y())
      return p.x() + (level - p.y()) / (q.y() - p.y()) * (q.x() - p.x());
  }
  return std::nan("");
}

TEST(WalkRoute, FromTheOpenOfficeToTheLabThroughBothDoors) {
  const FloorPlan plan = make_office_sample_plan();
  const WalkRouter router(plan);
  const std::vector<Eigen::Vector2d> route = router.route({2.6, 9.4}, {1.0, 1.0});
  ASSERT_GE(route.size(), 3u);
  EXPECT_EQ(route.front(), Eigen::Vector2d(2.6, 9.4));
  EXPECT_EQ(route.back(), Eigen::Vector2d(1.0, 1.0));
  for (std::size_t k = 1; k < route.size(); ++k)
    for (const PlanSegment& w : plan.occluder_segments())
      EXPECT_FALSE(properly_cross(route[k - 1], route[k], w.a, w.b))
          << "leg " << k << " crosses the wall (" << w.a.transpose() << ") - (" << w.b.transpose() << ")";
  const double office_door = crossing_x(route, 8.5), lab_door = crossing_x(route, 6.5);
  EXPECT_GT(office_door, 3.0);
  EXPECT_LT(office_door, 4.8);
  EXPECT_GT(lab_door, 4.0);
  EXPECT_LT(lab_door, 4.9);
  double length = 0.0;
  for (std::size_t k = 1; k < route.size(); ++k) length += (route[k] - route[k - 1]).norm();
  // Longer than the straight line (8.6 m), not much longer than the way through both doors.
  EXPECT_GT(length, 8.6);
  EXPECT_LT(length, 12.5);
}

TEST(WalkRoute, WithinOneRoomItIsTheStraightLineAndAWalledInSpotHasNone) {
  const FloorPlan plan = make_office_sample_plan();
  const WalkRouter router(plan);
  EXPECT_EQ(router.route({2.6, 9.4}, {5.5, 11.2}).size(), 2u);
  FloorPlan boxed = plan;
  for (auto [a, b] : {std::pair<Eigen::Vector2d, Eigen::Vector2d>{{1.5, 10.0}, {2.0, 10.0}},
                      {{2.0, 10.0}, {2.0, 10.5}},
                      {{2.0, 10.5}, {1.5, 10.5}},
                      {{1.5, 10.5}, {1.5, 10.0}}})
    boxed.segments.push_back({a, b, "WALLS", true});
  EXPECT_TRUE(WalkRouter(boxed).route({1.75, 10.25}, {5.5, 11.2}).empty());
  WalkRouteOptions bad;
  bad.cell_m = 0.0;
  EXPECT_THROW(bad.check(), Error);
}

}  // namespace
}  // namespace plenopath
