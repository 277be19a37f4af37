// Closing the openings of outer walls. Truths: the gaps' positions as built by hand, hand areas.
#include "processing/plan/exterior_openings.h"

#include <gtest/gtest.h>

#include <limits>

#include "model/error.h"

namespace plenopath {
namespace {

// A wall as the POV-Ray scenes' plans draw it: a closed outline of thickness t round the centre line
// (x0, y0)-(x1, y1), extended by t/2 at both ends.
void add_wall(std::vector<Segment2>* walls, double x0, double y0, double x1, double y1, double t) {
  const Eigen::Vector2d a(x0, y0), b(x1, y1);
  const Eigen::Vector2d d = (b - a).normalized(), n(-d.y(), d.x());
  const Eigen::Vector2d c[4] = {a - d * t / 2 - n * t / 2, b + d * t / 2 - n * t / 2,
                                b + d * t / 2 + n * t / 2, a - d * t / 2 + n * t / 2};
  for (int k = 0; k < 4; ++k) walls->push_back({c[k], c[(k + 1) % 4]});
}

// A 10 x 6 m hall, walls 0.2 m thick; the south wall has openings of clear width `gap` centred on x = 3
// and x = 7.
std::vector<Segment2> hall_with_windows(double gap) {
  std::vector<Segment2> walls;
  const double t = 0.2;
  add_wall(&walls, 0, 0, 3 - gap / 2 - t / 2, 0, t);
  add_wall(&walls, 3 + gap / 2 + t / 2, 0, 7 - gap / 2 - t / 2, 0, t);
  add_wall(&walls, 7 + gap / 2 + t / 2, 0, 10, 0, t);
  add_wall(&walls, 10, 0, 10, 6, t);
  add_wall(&walls, 10, 6, 0, 6, t);
  add_wall(&walls, 0, 6, 0, 0, t);
  return walls;
}

bool crosses_any(const std::vector<Segment2>& closings, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  for (const Segment2& s : closings) {
    double t = 0, u = 0;
    if (intersect_segments(a, b, s.a, s.b, &t, &u)) return true;
  }
  return false;
}

TEST(ExteriorOpenings, WindowsDrawnAsGapsAreClosedWithinTheWall) {
  const std::vector<Segment2> closings = exterior_openings(hall_with_windows(1.6));
  ASSERT_FALSE(closings.empty());
  for (const Segment2& s : closings) {
    // Within a window's span and within the wall's thickness: never out in the hall or beyond.
    for (const Eigen::Vector2d& p : {s.a, s.b}) {
      EXPECT_NEAR(p.y(), 0.0, 0.1 + 1e-9) << p.transpose();
      EXPECT_TRUE(std::abs(p.x() - 3) <= 0.8 + 1e-9 || std::abs(p.x() - 7) <= 0.8 + 1e-9) << p.transpose();
    }
  }
  // Each window is closed: a line walked in through it meets a closing.
  EXPECT_TRUE(crosses_any(closings, {3, -1}, {3, 1}));
  EXPECT_TRUE(crosses_any(closings, {7, -1}, {7, 1}));
  EXPECT_TRUE(crosses_any(closings, {2.25, -1}, {2.25, 1}));
}

TEST(ExteriorOpenings, AGapWiderThanTheLimitStaysOpen) {
  ExteriorOpeningOptions options;
  options.max_opening_m = 3.0;
  EXPECT_FALSE(crosses_any(exterior_openings(hall_with_windows(3.4), options), {3, -1}, {3, 1}));
  options.max_opening_m = 4.5;
  EXPECT_TRUE(crosses_any(exterior_openings(hall_with_windows(3.4), options), {3, -1}, {3, 1}));
  options.max_opening_m = 0;
  EXPECT_TRUE(exterior_openings(hall_with_windows(1.6), options).empty());
}

TEST(ExteriorOpenings, AClosedBuildingWithReflexCornersGetsNothing) {
  // An L-shaped building drawn as one outline (single lines, with vertices 1 m either side of the outside's
  // concave corner, which a segment across the notch would join), and a square pillar inside near a wall.
  std::vector<Segment2> walls;
  const Eigen::Vector2d l[8] = {{0, 0}, {8, 0}, {8, 3}, {4, 3}, {3, 3}, {3, 4}, {3, 7}, {0, 7}};
  for (int k = 0; k < 8; ++k) walls.push_back({l[k], l[(k + 1) % 8]});
  const Eigen::Vector2d p[4] = {{1, 1}, {1.4, 1}, {1.4, 1.4}, {1, 1.4}};
  for (int k = 0; k < 4; ++k) walls.push_back({p[k], p[(k + 1) % 4]});
  EXPECT_TRUE(exterior_openings(walls).empty());
}

TEST(ExteriorOpenings, ADoorwayBetweenTheEndsOfOnePolylineIsClosed) {
  // A room drawn as one open polyline: the 1 m entrance is the gap between its two ends.
  std::vector<Segment2> walls;
  const Eigen::Vector2d u[6] = {{2, 0}, {5, 0}, {5, 4}, {0, 4}, {0, 0}, {1, 0}};
  for (int k = 0; k + 1 < 6; ++k) walls.push_back({u[k], u[k + 1]});
  const std::vector<Segment2> closings = exterior_openings(walls);
  ASSERT_EQ(closings.size(), 1u);
  EXPECT_NEAR(std::abs(closings[0].a.x() - closings[0].b.x()), 1.0, 1e-12);
  EXPECT_NEAR(closings[0].a.y(), 0.0, 1e-12);
  EXPECT_NEAR(closings[0].b.y(), 0.0, 1e-12);
}

TEST(ExteriorOpenings, ASlitBetweenTwoOutlinesIsClosed) {
  // Two wall outlines of the south side that miss each other by 5 mm.
  std::vector<Segment2> walls = hall_with_windows(1.6);
  walls.clear();
  add_wall(&walls, 0, 0, 4.9, 0, 0.2);
  add_wall(&walls, 5.105, 0, 10, 0, 0.2);
  add_wall(&walls, 10, 0, 10, 6, 0.2);
  add_wall(&walls, 10, 6, 0, 6, 0.2);
  add_wall(&walls, 0, 6, 0, 0, 0.2);
  const std::vector<Segment2> closings = exterior_openings(walls);
  ASSERT_FALSE(closings.empty());
  for (const Segment2& s : closings) EXPECT_LE((s.a - s.b).norm(), 0.3);
  EXPECT_TRUE(crosses_any(closings, {5.0025, -1}, {5.0025, 1}));
}

TEST(ExteriorOpenings, NonFiniteAndZeroLengthSegmentsAreLeftOut) {
  // A drawing's stray NaN, infinite and zero-length segments change nothing: the windows close as without
  // them.
  std::vector<Segment2> walls = hall_with_windows(1.6);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  walls.push_back({{nan, 0}, {1, 1}});
  walls.push_back({{0, 0}, {inf, 2}});
  walls.push_back({{4, 4}, {4, 4}});
  const std::vector<Segment2> closings = exterior_openings(walls);
  EXPECT_EQ(closings.size(), exterior_openings(hall_with_windows(1.6)).size());
  EXPECT_TRUE(crosses_any(closings, {3, -1}, {3, 1}));
  // Nothing but degenerate segments, or one lone point: nothing to close, no throw.
  EXPECT_TRUE(exterior_openings({{{nan, nan}, {nan, nan}}, {{1, 1}, {1, 1}}}).empty());
  EXPECT_TRUE(exterior_openings({{{0, 0}, {0.001, 0}}}).empty());
}

TEST(ExteriorOpenings, OptionsAreChecked) {
  ExteriorOpeningOptions options;
  options.max_opening_m = -1;
  EXPECT_THROW(options.check(), Error);
  options = {};
  options.cell_m = 0;
  EXPECT_THROW(options.check(), Error);
  EXPECT_NO_THROW(ExteriorOpeningOptions{}.check());
  EXPECT_TRUE(exterior_openings({}).empty());
}

}  // namespace
}  // namespace plenopath
