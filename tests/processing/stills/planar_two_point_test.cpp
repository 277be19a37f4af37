// The planar two-point solver and its RANSAC against independent truth: exact synthetic correspondences
// (known motion), the general linear 8-point essential matrix on the same bearings, and a brute-force scan
// of (turn, direction) on noisy data with outliers.
#include "processing/stills/planar_two_point.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "model/camera_path.h"

namespace plenopath {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Vector3d rotate_z(const Eigen::Vector3d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}

// A camera B at `position` (A's frame, z = 0) with heading `turn` sees world point p along this bearing.
Eigen::Vector3d seen_from_b(const Eigen::Vector3d& p, const Eigen::Vector2d& position, double turn) {
  return rotate_z(p - Eigen::Vector3d(position.x(), position.y(), 0), -turn).normalized();
}

// A point of a room around the two cameras: 1-6 m away, 1.5 m below to 1.2 m above the lens, not level.
Eigen::Vector3d room_point(std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), range(1.0, 6.0), z(-1.5, 1.2);
  for (;;) {
    const double a = angle(rng), r = range(rng), h = z(rng);
    if (std::abs(h) > 0.15) return {r * std::cos(a), r * std::sin(a), h};
  }
}

double angle_error(double x, double y) { return std::abs(wrap_angle(x - y)); }

TEST(PlanarTwoPoint, RecoversTheMotionFromTwoExactCorrespondences) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), length(0.5, 3.0);
  int solved = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const double turn = angle(rng), direction = angle(rng), d = length(rng);
    const Eigen::Vector2d position = d * Eigen::Vector2d(std::cos(direction), std::sin(direction));
    const Eigen::Vector3d p0 = room_point(rng), p1 = room_point(rng);
    const std::vector<PlanarMotion> solutions = solve_planar_two_point(
        p0.normalized(), seen_from_b(p0, position, turn), p1.normalized(), seen_from_b(p1, position, turn));
    EXPECT_LE(solutions.size(), 4u);
    bool found = false;
    for (const PlanarMotion& m : solutions)
      found |= angle_error(m.turn, turn) < 1e-6 && angle_error(m.direction, direction) < 1e-6;
    solved += found;
  }
  // Nearly every pair; the few misses are pairs whose points are almost coplanar with the baseline.
  EXPECT_GE(solved, 495);
}

TEST(PlanarTwoPoint, HalfTurnIsFound) {
  // psi = pi is the root at infinity of the quartic in tan(psi / 2).
  std::mt19937 rng(9);
  const Eigen::Vector2d position(1.2, -0.7);
  const Eigen::Vector3d p0 = room_point(rng), p1 = room_point(rng);
  bool found = false;
  for (const PlanarMotion& m : solve_planar_two_point(p0.normalized(), seen_from_b(p0, position, M_PI),
                                                      p1.normalized(), seen_from_b(p1, position, M_PI)))
    found |= angle_error(m.turn, M_PI) < 1e-6 && angle_error(m.direction, std::atan2(-0.7, 1.2)) < 1e-6;
  EXPECT_TRUE(found);
}

TEST(PlanarTwoPoint, LevelPointsGiveNoSolution) {
  // Points at the cameras' height lie in the horizon plane, which is an epipolar plane of every motion.
  const Eigen::Vector3d a0(1, 0, 0), a1(0, 1, 0);
  EXPECT_TRUE(solve_planar_two_point(a0, a0, a1, a1).empty());
}

// The general (non-planar) linear 8-point essential matrix on bearings, a^T E b = 0, unit Frobenius norm.
Eigen::Matrix3d eight_point_essential(const std::vector<Eigen::Vector3d>& a,
                                      const std::vector<Eigen::Vector3d>& b) {
  Eigen::MatrixXd m(a.size(), 9);
  for (std::size_t k = 0; k < a.size(); ++k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m(static_cast<Eigen::Index>(k), 3 * i + j) = a[k](i) * b[k](j);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullV);
  const Eigen::VectorXd e = svd.matrixV().col(8);
  Eigen::Matrix3d out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out(i, j) = e(3 * i + j);
  return out / out.norm();
}

Eigen::Matrix3d planar_essential(const PlanarMotion& m) {
  Eigen::Matrix3d tx;
  const double x = std::cos(m.direction), y = std::sin(m.direction);
  tx << 0, 0, y, 0, 0, -x, -y, x, 0;
  Eigen::Matrix3d r;
  r << std::cos(m.turn), -std::sin(m.turn), 0, std::sin(m.turn), std::cos(m.turn), 0, 0, 0, 1;
  const Eigen::Matrix3d e = tx * r;
  return e / e.norm();
}

double essential_distance(const Eigen::Matrix3d& e, const Eigen::Matrix3d& f) {
  return std::min((e - f).norm(), (e + f).norm());
}

TEST(PlanarTwoPoint, AgreesWithTheGeneralEightPointEssentialMatrix) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int trial = 0; trial < 50; ++trial) {
    const double turn = angle(rng), direction = angle(rng);
    const Eigen::Vector2d position = 2.0 * Eigen::Vector2d(std::cos(direction), std::sin(direction));
    std::vector<Eigen::Vector3d> a, b;
    for (int k = 0; k < 12; ++k) {
      const Eigen::Vector3d p = room_point(rng);
      a.push_back(p.normalized());
      b.push_back(seen_from_b(p, position, turn));
    }
    const Eigen::Matrix3d general = eight_point_essential(a, b);
    // The 8-point E of exact planar data is itself planar: [t]x Rz with t horizontal.
    double best = 1e9;
    for (const PlanarMotion& m : solve_planar_two_point(a[0], b[0], a[1], b[1]))
      best = std::min(best, essential_distance(planar_essential(m), general));
    EXPECT_LT(best, 1e-6) << "trial " << trial;
  }
}

struct NoisyPair {
  std::vector<Eigen::Vector3d> a, b;
  std::vector<bool> outlier;
};

NoisyPair noisy_pair(double turn, const Eigen::Vector2d& position, int count, double noise_deg,
                     double outlier_fraction, std::mt19937& rng) {
  NoisyPair out;
  std::normal_distribution<double> noise(0.0, noise_deg * kDeg);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto jitter = [&](const Eigen::Vector3d& v) {
    return (v + Eigen::Vector3d(noise(rng), noise(rng), noise(rng))).normalized();
  };
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d p = room_point(rng);
    const bool outlier = unit(rng) < outlier_fraction;
    out.a.push_back(jitter(p.normalized()));
    // An outlier is a wrong match: B's bearing of another random point.
    out.b.push_back(jitter(seen_from_b(outlier ? room_point(rng) : p, position, turn)));
    out.outlier.push_back(outlier);
  }
  return out;
}

TEST(PlanarRansac, FindsTheMotionAmongNoiseAndOutliers) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), length(1.0, 3.0);
  PlanarRansacOptions options;
  for (int trial = 0; trial < 20; ++trial) {
    const double turn = angle(rng), direction = angle(rng);
    const Eigen::Vector2d position = length(rng) * Eigen::Vector2d(std::cos(direction), std::sin(direction));
    const NoisyPair pair = noisy_pair(turn, position, 400, 0.05, 0.4, rng);
    const PlanarPoseEstimate e = estimate_planar_pose(pair.a, pair.b, options, rng);
    ASSERT_TRUE(e.valid) << "trial " << trial;
    EXPECT_LT(angle_error(e.motion.turn, turn), 0.05 * kDeg) << "trial " << trial;
    EXPECT_LT(angle_error(e.motion.direction, direction), 0.3 * kDeg) << "trial " << trial;
    // The inliers are the true matches, give or take outliers that happen to fit.
    int true_in = 0, false_in = 0, true_count = 0;
    for (std::size_t k = 0; k < pair.a.size(); ++k) {
      true_count += !pair.outlier[k];
      if (e.inlier[k]) (pair.outlier[k] ? false_in : true_in)++;
    }
    EXPECT_GT(true_in, 0.95 * true_count);
    EXPECT_LT(false_in, 0.05 * (static_cast<double>(pair.a.size()) - true_count));
  }
}

TEST(PlanarRansac, MatchesABruteForceScanOfTheRobustCost) {
  std::mt19937 rng(17);
  const double turn = 2.1, direction = -0.6;
  const Eigen::Vector2d position = 1.7 * Eigen::Vector2d(std::cos(direction), std::sin(direction));
  const NoisyPair pair = noisy_pair(turn, position, 300, 0.1, 0.3, rng);
  const PlanarRansacOptions options;
  const PlanarPoseEstimate e = estimate_planar_pose(pair.a, pair.b, options, rng);
  ASSERT_TRUE(e.valid);
  // Truncated quadratic cost on a 1 deg grid over the whole (turn, direction) torus, then finer grids
  // around the best cell: the RANSAC answer must sit at the scan's minimum.
  const double cap = options.threshold_deg * kDeg;
  auto cost = [&](const PlanarMotion& m) {
    double c = 0;
    for (std::size_t k = 0; k < pair.a.size(); ++k) {
      const double err =
          in_front_of_both(pair.a[k], pair.b[k], m) ? planar_epipolar_angle(pair.a[k], pair.b[k], m) : cap;
      c += std::min(err * err, cap * cap);
    }
    return c;
  };
  PlanarMotion best;
  double best_cost = 1e300;
  auto scan = [&](double t0, double d0, double half_range, double step) {
    for (double t = -half_range; t <= half_range; t += step)
      for (double d = -half_range; d <= half_range; d += step) {
        const PlanarMotion m{wrap_angle(t0 + t), wrap_angle(d0 + d)};
        const double c = cost(m);
        if (c < best_cost) {
          best_cost = c;
          best = m;
        }
      }
  };
  scan(0.0, 0.0, M_PI, 1.0 * kDeg);
  scan(best.turn, best.direction, 1.5 * kDeg, 0.02 * kDeg);
  scan(best.turn, best.direction, 0.05 * kDeg, 0.002 * kDeg);
  // RANSAC's refinement minimises a slightly different cost (one-sided, not truncated): within a few
  // hundredths of a degree, about the estimate's own spread at this noise.
  EXPECT_LT(angle_error(e.motion.turn, best.turn), 0.03 * kDeg);
  EXPECT_LT(angle_error(e.motion.direction, best.direction), 0.1 * kDeg);
  EXPECT_LT(angle_error(best.turn, turn), 0.05 * kDeg);
}

TEST(PlanarRansac, TooFewCorrespondencesGiveNoPose) {
  std::mt19937 rng(1);
  const NoisyPair pair = noisy_pair(0.3, Eigen::Vector2d(1, 0), 10, 0.05, 0.0, rng);
  EXPECT_FALSE(estimate_planar_pose(pair.a, pair.b, PlanarRansacOptions{}, rng).valid);
}

}  // namespace
}  // namespace plenopath
