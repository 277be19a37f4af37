#include "processing/egomotion/planar_two_view.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace plenopath {
namespace {

Eigen::Vector3d rotate_z(const Eigen::Vector3d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}

// Positive-depth count of a two-view configuration (A at 0, B at t) via midpoint triangulation.
bool in_front(const Eigen::Vector3d& a, const Eigen::Vector3d& rb, const Eigen::Vector3d& t) {
  // lambda a - mu rb = t
  Eigen::Matrix<double, 3, 2> m;
  m.col(0) = a;
  m.col(1) = -rb;
  const Eigen::Vector2d lm = (m.transpose() * m).ldlt().solve(m.transpose() * t);
  return lm[0] > 0 && lm[1] > 0;
}

}  // namespace

double planar_epipolar_error(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double turn,
                             double direction) {
  const Eigen::Vector3d t(std::cos(direction), std::sin(direction), 0.0);
  const Eigen::Vector3d n = t.cross(a);
  const double nn = n.norm();
  if (nn < 1e-9) return 0.0;
  return n.dot(rotate_z(b, turn)) / nn;
}

PlanarRelativePose estimate_planar_relative_pose(const std::vector<Eigen::Vector3d>& a,
                                                 const std::vector<Eigen::Vector3d>& b, double turn_guess,
                                                 const PlanarTwoViewOptions& options, std::mt19937& rng) {
  PlanarRelativePose out;
  const int n = static_cast<int>(a.size());
  out.inlier.assign(n, false);
  if (n < options.min_inliers) return out;

  std::vector<double> parallax(n);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d rb = rotate_z(b[k], turn_guess);
    parallax[k] = std::atan2(a[k].cross(rb).norm(), a[k].dot(rb));
  }
  {
    std::vector<double> p = parallax;
    std::nth_element(p.begin(), p.begin() + n / 2, p.end());
    out.median_parallax = p[n / 2];
  }
  if (out.median_parallax < options.min_parallax) return out;

  auto count_inliers = [&](double turn, double direction, std::vector<bool>* mask) {
    int count = 0;
    for (int k = 0; k < n; ++k) {
      const bool in = std::abs(planar_epipolar_error(a[k], b[k], turn, direction)) < options.threshold;
      if (mask) (*mask)[k] = in;
      count += in;
    }
    return count;
  };

  std::uniform_int_distribution<int> pick(0, n - 1);
  int best = -1;
  double best_direction = 0.0, best_turn = turn_guess;
  auto hypotheses = [&](double turn, int iterations) {
    for (int it = 0; it < iterations; ++it) {
      const int k = pick(rng);
      if (parallax[k] < options.min_parallax) continue;
      // t . (a x R b) = 0 with t = (cos, sin, 0).
      const Eigen::Vector3d m = a[k].cross(rotate_z(b[k], turn));
      if (std::hypot(m.x(), m.y()) < 1e-12) continue;
      const double direction = std::atan2(-m.x(), m.y());  // t perpendicular to (m.x, m.y)
      const int c = count_inliers(turn, direction, nullptr);
      if (c > best) {
        best = c;
        best_direction = direction;
        best_turn = turn;
      }
    }
  };
  hypotheses(turn_guess, options.iterations);
  if (best < n / 2) {
    // The turn guess may be far off (a fast turn the rings misread): scan turns around it.
    const double step = M_PI / 180.0;
    const int at_guess = best;
    const double guess_direction = best_direction;
    best = std::max(at_guess, static_cast<int>(std::ceil(options.turn_scan_margin * at_guess)) - 1);
    for (int j = -options.turn_scan_deg; j <= options.turn_scan_deg; ++j)
      if (j != 0) hypotheses(turn_guess + j * step, 12);
    if (best_turn == turn_guess) {  // no turn explained enough more
      best = at_guess;
      best_direction = guess_direction;
    }
  }
  if (best < options.min_inliers) return out;

  // Gauss-Newton on (turn, direction) over the inliers (numerical derivatives; two unknowns).
  double turn = best_turn, direction = best_direction;
  std::vector<bool> mask(n);
  for (int round = 0; round < 3; ++round) {
    count_inliers(turn, direction, &mask);
    for (int it = 0; it < 8; ++it) {
      Eigen::Matrix2d jtj = Eigen::Matrix2d::Zero();
      Eigen::Vector2d jtr = Eigen::Vector2d::Zero();
      const double h = 1e-6;
      for (int k = 0; k < n; ++k) {
        if (!mask[k]) continue;
        const double r = planar_epipolar_error(a[k], b[k], turn, direction);
        const Eigen::Vector2d j((planar_epipolar_error(a[k], b[k], turn + h, direction) - r) / h,
                                (planar_epipolar_error(a[k], b[k], turn, direction + h) - r) / h);
        // Huber weight keeps borderline inliers from dominating.
        const double w = std::abs(r) < 0.5 * options.threshold ? 1.0 : 0.5 * options.threshold / std::abs(r);
        jtj += w * j * j.transpose();
        jtr += w * j * r;
      }
      const Eigen::Vector2d step = -(jtj + 1e-12 * Eigen::Matrix2d::Identity()).ldlt().solve(jtr);
      turn += step[0];
      direction += step[1];
      if (step.norm() < 1e-10) break;
    }
  }
  out.inliers = count_inliers(turn, direction, &mask);
  // The epipolar constraint does not see the sign of t: pick the one that puts points in front.
  const Eigen::Vector3d t(std::cos(direction), std::sin(direction), 0.0);
  int front = 0, back = 0;
  double sum2 = 0.0;
  for (int k = 0; k < n; ++k) {
    if (!mask[k]) continue;
    const Eigen::Vector3d rb = rotate_z(b[k], turn);
    if (parallax[k] < options.min_parallax) continue;
    if (in_front(a[k], rb, t)) ++front;
    if (in_front(a[k], rb, -t)) ++back;
    const double r = planar_epipolar_error(a[k], b[k], turn, direction);
    sum2 += r * r;
  }
  if (back > front) direction += M_PI;
  direction = std::remainder(direction, 2 * M_PI);
  out.turn = turn;
  out.direction = direction;
  out.inlier = mask;
  out.rms_error = out.inliers > 0 ? std::sqrt(sum2 / out.inliers) : 0.0;
  out.valid = out.inliers >= options.min_inliers && front + back > 0;
  return out;
}

bool triangulate_rays(const std::vector<Eigen::Vector3d>& centres,
                      const std::vector<Eigen::Vector3d>& directions, double min_angle,
                      Eigen::Vector3d* point) {
  const size_t n = centres.size();
  if (n < 2) return false;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  double max_angle = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Matrix3d p = Eigen::Matrix3d::Identity() - directions[i] * directions[i].transpose();
    a += p;
    rhs += p * centres[i];
  }
  // The widest pair (first against the others is enough for sequential tracks: the first and last).
  for (size_t i = 1; i < n; ++i)
    max_angle = std::max(max_angle, std::acos(std::clamp(directions[0].dot(directions[i]), -1.0, 1.0)));
  if (max_angle < min_angle) return false;
  const Eigen::Vector3d x = a.ldlt().solve(rhs);
  if (!x.allFinite()) return false;
  for (size_t i = 0; i < n; ++i)
    if ((x - centres[i]).dot(directions[i]) <= 0) return false;
  // The baseline must subtend the angle too, seen from the point: rays from one centre (a turn on the spot,
  // with headings a little off) diverge and "meet" at that centre, which no scene point is.
  double subtended = 0.0;
  for (size_t i = 1; i < n; ++i) {
    const Eigen::Vector3d u = centres[0] - x, v = centres[i] - x;
    subtended = std::max(subtended, std::atan2(u.cross(v).norm(), u.dot(v)));
  }
  if (subtended < min_angle) return false;
  *point = x;
  return true;
}

}  // namespace plenopath
