// The chaining's check of a keyframe step against the points triangulated so far
// (egomotion_steps.h: check_step_against_points), on points and bearings made from known poses.
#include "processing/egomotion/egomotion_steps.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace plenopath::egomotion_steps {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kPixel = 2 * M_PI / 1024;

struct Scene {
  Eigen::Vector2d a, b;  // keyframe a and the true b
  double heading_b = 0.0;
  std::vector<Eigen::Vector3d> points, bearings;  // b's camera frame
};

// A corridor 2.4 m wide along +x (walls at y = -1.1 and +1.3, floor at z = -1.5), the camera stepping
// 0.3 m along it with a 4 deg turn; points on both walls and the floor within 1-6 m, seen from the true b
// with 0.1 px of noise.
Scene corridor_step() {
  Scene s;
  s.a = {2.0, 0.1};
  s.b = s.a + 0.3 * Eigen::Vector2d(std::cos(2 * kDeg), std::sin(2 * kDeg));
  s.heading_b = 4 * kDeg;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> along(-6.0, 6.0), height(-1.5, 1.2);
  std::normal_distribution<double> noise(0.0, 0.1 * kPixel);
  for (int k = 0; k < 40; ++k) {
    double x = s.b.x() + along(rng);
    if (std::abs(x - s.b.x()) < 1.0) x += 2.0;
    Eigen::Vector3d p = k % 3 == 0   ? Eigen::Vector3d(x, -1.1, height(rng))
                        : k % 3 == 1 ? Eigen::Vector3d(x, 1.3, height(rng))
                                     : Eigen::Vector3d(x, 0.9 * std::sin(k), -1.5);
    const Eigen::Vector3d d = p - Eigen::Vector3d(s.b.x(), s.b.y(), 0.0);
    Eigen::Vector3d bearing = (Eigen::AngleAxisd(-s.heading_b, Eigen::Vector3d::UnitZ()) * d).normalized();
    bearing = (bearing + Eigen::Vector3d(noise(rng), noise(rng), noise(rng))).normalized();
    s.points.push_back(p);
    s.bearings.push_back(bearing);
  }
  return s;
}

StepCheck check(const Scene& s, const Eigen::Vector2d& measured, const Eigen::Vector2d& predicted) {
  return check_step_against_points(s.a, measured, predicted, s.heading_b, s.points, s.bearings, 0.003,
                                   3 * kPixel, 2.0, 12, 20 * kDeg);
}

TEST(StepAgainstPoints, ASidewaysTwoViewStepIsReplacedByThePoints) {
  const Scene s = corridor_step();
  // Two-view turned the step 80 deg sideways (a walker's tracks outvoting the walls'); the last speed
  // predicts 0.28 m straight on.
  const Eigen::Vector2d sideways = s.a + 0.3 * Eigen::Vector2d(std::cos(82 * kDeg), std::sin(82 * kDeg));
  const Eigen::Vector2d predicted = s.a + Eigen::Vector2d(0.28, 0.0);
  const StepCheck c = check(s, sideways, predicted);
  EXPECT_TRUE(c.replaced);
  EXPECT_LT((c.position - s.b).norm(), 0.005);  // the true b, to 5 mm
  EXPECT_GE(c.explained_resected, 36);          // nearly all 40
  EXPECT_LT(c.explained_measured, 10);
}

TEST(StepAgainstPoints, AGoodStepIsKeptEvenWhereTheLengthDiffers) {
  const Scene s = corridor_step();
  const Eigen::Vector2d predicted = s.a + Eigen::Vector2d(0.28, 0.0);
  // The two-view step in the right direction is kept, whatever its length: the check judges directions.
  for (double length : {0.3, 0.2, 0.45}) {
    const Eigen::Vector2d measured = s.a + length * Eigen::Vector2d(std::cos(2 * kDeg), std::sin(2 * kDeg));
    const StepCheck c = check(s, measured, predicted);
    EXPECT_FALSE(c.replaced) << length;
    EXPECT_EQ(c.position, measured);
  }
  // Where the walk turned (the last direction predicts b 29 deg off the measured step, which is right):
  // kept, since the resection from the prediction lands on the measured step too.
  const Eigen::Vector2d ahead = s.a + Eigen::Vector2d(0.3, 0.0);
  EXPECT_FALSE(check(s, s.b, ahead + Eigen::Vector2d(0.0, -0.15)).replaced);
}

TEST(StepAgainstPoints, TooFewPointsChangeNothing) {
  Scene s = corridor_step();
  s.points.resize(8);
  s.bearings.resize(8);
  const Eigen::Vector2d sideways = s.a + 0.3 * Eigen::Vector2d(std::cos(82 * kDeg), std::sin(82 * kDeg));
  const StepCheck c = check(s, sideways, s.a + Eigen::Vector2d(0.28, 0.0));
  EXPECT_FALSE(c.replaced);  // 8 explained at best, 12 needed
  EXPECT_EQ(c.position, sideways);
}

}  // namespace
}  // namespace plenopath::egomotion_steps
