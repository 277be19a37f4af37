#include "processing/stills/planar_two_point.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "model/camera_path.h"
#include "model/option_check.h"
#include "processing/util/statistics.h"

namespace plenopath {

void PlanarRansacOptions::check() const {
  const std::string s = "PlanarRansacOptions.";
  require_option(threshold_deg > 0, s + "threshold_deg", "must be > 0", threshold_deg);
  require_option(max_iterations >= 1, s + "max_iterations", "must be >= 1", max_iterations);
  require_option(confidence > 0 && confidence < 1, s + "confidence", "must be in (0, 1)", confidence);
  require_option(min_inliers >= 2, s + "min_inliers", "must be >= 2", min_inliers);
  require_option(min_elevation_deg >= 0 && min_elevation_deg < 90, s + "min_elevation_deg",
                 "must be in [0, 90)", min_elevation_deg);
}

namespace {

Eigen::Vector3d rotate_z(const Eigen::Vector3d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}

Eigen::Vector3d baseline(const PlanarMotion& m) {
  return {std::cos(m.direction), std::sin(m.direction), 0.0};
}

// p[0] + p[1] cos(psi) + p[2] sin(psi).
using Trig = std::array<double, 3>;

// The coefficients of t_x and t_y in a . (t x Rz(psi) b).
void epipolar_row(const Eigen::Vector3d& a, const Eigen::Vector3d& b, Trig* mx, Trig* my) {
  *mx = {-a.y() * b.z(), a.z() * b.y(), a.z() * b.x()};
  *my = {a.x() * b.z(), -a.z() * b.x(), a.z() * b.y()};
}

double eval(const Trig& p, double psi) { return p[0] + p[1] * std::cos(psi) + p[2] * std::sin(psi); }

// Real roots of sum coeffs[k] u^k (degree <= 4), by the companion matrix.
std::vector<double> real_roots(std::array<double, 5> coeffs) {
  double scale = 0;
  for (double c : coeffs) scale = std::max(scale, std::abs(c));
  std::vector<double> roots;
  if (scale == 0) return roots;
  int degree = 4;
  while (degree > 0 && std::abs(coeffs[static_cast<std::size_t>(degree)]) < 1e-12 * scale) --degree;
  if (degree == 0) return roots;
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
  for (int k = 0; k < degree; ++k)
    companion(0, k) =
        -coeffs[static_cast<std::size_t>(degree - 1 - k)] / coeffs[static_cast<std::size_t>(degree)];
  for (int k = 1; k < degree; ++k) companion(k, k - 1) = 1.0;
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(companion, false);
  for (int k = 0; k < degree; ++k) {
    const std::complex<double> r = solver.eigenvalues()[k];
    if (std::abs(r.imag()) <= 1e-8 * std::max(1.0, std::abs(r.real()))) roots.push_back(r.real());
  }
  return roots;
}

// Ray depths (lambda along a, mu along Rz(psi) b) of the nearest points of the two rays; false when they
// are nearly parallel.
bool ray_depths(const Eigen::Vector3d& a, const Eigen::Vector3d& rb, const Eigen::Vector3d& t, double* lambda,
                double* mu) {
  // lambda a - mu rb = t in the least-squares sense.
  const double aa = a.dot(a), ab = a.dot(rb), bb = rb.dot(rb);
  const double det = aa * bb - ab * ab;
  if (det < 1e-10) return false;
  const double at = a.dot(t), bt = rb.dot(t);
  *lambda = (bb * at - ab * bt) / det;
  *mu = (ab * at - aa * bt) / det;
  return true;
}

}  // namespace

bool in_front_of_both(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const PlanarMotion& motion) {
  double lambda = 0, mu = 0;
  if (!ray_depths(a, rotate_z(b, motion.turn), baseline(motion), &lambda, &mu)) return true;
  return lambda > 0 && mu > 0;
}

double planar_epipolar_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const PlanarMotion& motion) {
  const Eigen::Vector3d t = baseline(motion);
  const Eigen::Vector3d rb = rotate_z(b, motion.turn);
  const Eigen::Vector3d an = a.normalized(), bn = rb.normalized();
  const Eigen::Vector3d n_a = t.cross(an), n_b = t.cross(bn);
  const double la = n_a.norm(), lb = n_b.norm();
  // A ray along the baseline lies in every epipolar plane.
  const double angle_b = la < 1e-12 ? 0.0 : std::asin(std::min(1.0, std::abs(n_a.dot(bn)) / la));
  const double angle_a = lb < 1e-12 ? 0.0 : std::asin(std::min(1.0, std::abs(n_b.dot(an)) / lb));
  return 0.5 * (angle_a + angle_b);
}

std::vector<PlanarMotion> solve_planar_two_point(const Eigen::Vector3d& a0, const Eigen::Vector3d& b0,
                                                 const Eigen::Vector3d& a1, const Eigen::Vector3d& b1) {
  Trig mx0, my0, mx1, my1;
  epipolar_row(a0, b0, &mx0, &my0);
  epipolar_row(a1, b1, &mx1, &my1);
  // det(psi) = mx0 my1 - my0 mx1 = F + D c + E s + A c^2 + B s^2 + C c s.
  auto product = [](const Trig& p, const Trig& q, double sign, std::array<double, 6>* acc) {
    (*acc)[0] += sign * p[0] * q[0];                  // F
    (*acc)[1] += sign * (p[0] * q[1] + p[1] * q[0]);  // D
    (*acc)[2] += sign * (p[0] * q[2] + p[2] * q[0]);  // E
    (*acc)[3] += sign * p[1] * q[1];                  // A
    (*acc)[4] += sign * p[2] * q[2];                  // B
    (*acc)[5] += sign * (p[1] * q[2] + p[2] * q[1]);  // C
  };
  std::array<double, 6> k{};
  product(mx0, my1, 1.0, &k);
  product(my0, mx1, -1.0, &k);
  const double F = k[0], D = k[1], E = k[2], A = k[3], B = k[4], C = k[5];
  // u = tan(psi / 2): c = (1 - u^2) / (1 + u^2), s = 2u / (1 + u^2); times (1 + u^2)^2.
  const std::array<double, 5> quartic = {F + D + A, 2 * E + 2 * C, 2 * F - 2 * A + 4 * B, 2 * E - 2 * C,
                                         F - D + A};
  std::vector<double> turns;
  for (double u : real_roots(quartic)) turns.push_back(2.0 * std::atan(u));
  // psi = pi is u = infinity: a root when the quartic's leading coefficient vanishes.
  const double scale =
      std::max({std::abs(F), std::abs(D), std::abs(E), std::abs(A), std::abs(B), std::abs(C)});
  if (scale == 0) return {};
  if (std::abs(quartic[4]) < 1e-9 * scale) turns.push_back(M_PI);

  std::vector<PlanarMotion> out;
  for (double psi : turns) {
    // t is orthogonal to both rows (mx, my); take the better conditioned row.
    const Eigen::Vector2d r0(eval(mx0, psi), eval(my0, psi)), r1(eval(mx1, psi), eval(my1, psi));
    const Eigen::Vector2d row = r0.squaredNorm() >= r1.squaredNorm() ? r0 : r1;
    if (row.squaredNorm() < 1e-24) continue;
    PlanarMotion m;
    m.turn = wrap_angle(psi);
    m.direction = std::atan2(row.x(), -row.y());  // t = (-my, mx)
    // The sign of t: both points in front of both cameras.
    bool kept = false;
    for (int flip = 0; flip < 2 && !kept; ++flip) {
      PlanarMotion candidate = m;
      if (flip) candidate.direction = wrap_angle(m.direction + M_PI);
      double l0, u0, l1, u1;
      const Eigen::Vector3d t = baseline(candidate);
      const bool ok0 = ray_depths(a0, rotate_z(b0, candidate.turn), t, &l0, &u0);
      const bool ok1 = ray_depths(a1, rotate_z(b1, candidate.turn), t, &l1, &u1);
      if ((!ok0 || (l0 > 0 && u0 > 0)) && (!ok1 || (l1 > 0 && u1 > 0)) && (ok0 || ok1)) {
        out.push_back(candidate);
        kept = true;
      }
    }
  }
  return out;
}

namespace {

// Inliers of a motion: within the threshold and in front of both cameras.
int count_inliers(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                  const PlanarMotion& m, double threshold, std::vector<bool>* mask, double* cost) {
  int count = 0;
  double sum = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double e = planar_epipolar_angle(a[k], b[k], m);
    const bool in = e < threshold && in_front_of_both(a[k], b[k], m);
    if (mask) (*mask)[k] = in;
    count += in;
    sum += std::min(e, threshold);  // MSAC: ties between equal counts go to the tighter fit
  }
  if (cost) *cost = sum;
  return count;
}

// Gauss-Newton on (psi, phi) over the inliers, signed residuals (sine of b's angle from the plane (t, a),
// scaled by 1 / |t x a|), numeric Jacobian.
PlanarMotion refine(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                    const std::vector<bool>& inlier, PlanarMotion m) {
  auto residual = [&](std::size_t k, const PlanarMotion& x) {
    const Eigen::Vector3d t = baseline(x);
    const Eigen::Vector3d n = t.cross(a[k]);
    const double nn = n.norm();
    if (nn < 1e-9) return 0.0;
    return n.dot(rotate_z(b[k], x.turn)) / nn;
  };
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::Matrix2d jtj = Eigen::Matrix2d::Zero();
    Eigen::Vector2d jtr = Eigen::Vector2d::Zero();
    const double h = 1e-6;
    for (std::size_t k = 0; k < a.size(); ++k) {
      if (!inlier[k]) continue;
      const double r = residual(k, m);
      PlanarMotion dt = m, dp = m;
      dt.turn += h;
      dp.direction += h;
      const Eigen::Vector2d j((residual(k, dt) - r) / h, (residual(k, dp) - r) / h);
      jtj += j * j.transpose();
      jtr += j * r;
    }
    jtj.diagonal() *= 1.0 + 1e-9;
    if (std::abs(jtj.determinant()) < 1e-30) break;
    const Eigen::Vector2d step = -jtj.ldlt().solve(jtr);
    m.turn = wrap_angle(m.turn + step.x());
    m.direction = wrap_angle(m.direction + step.y());
    if (step.norm() < 1e-10) break;
  }
  return m;
}

}  // namespace

PlanarPoseEstimate estimate_planar_pose(const std::vector<Eigen::Vector3d>& a,
                                        const std::vector<Eigen::Vector3d>& b,
                                        const PlanarRansacOptions& options, std::mt19937& rng) {
  options.check();
  PlanarPoseEstimate out;
  const int n = static_cast<int>(a.size());
  out.inlier.assign(static_cast<std::size_t>(n), false);
  if (n < options.min_inliers || b.size() != a.size()) return out;
  // Only correspondences off the horizon constrain the motion.
  const double min_z = std::sin(options.min_elevation_deg * M_PI / 180.0);
  std::vector<int> drawable;
  for (int k = 0; k < n; ++k)
    if (std::abs(a[k].normalized().z()) > min_z || std::abs(b[k].normalized().z()) > min_z)
      drawable.push_back(k);
  if (static_cast<int>(drawable.size()) < 2) return out;
  const double threshold = options.threshold_deg * M_PI / 180.0;
  std::uniform_int_distribution<int> pick(0, static_cast<int>(drawable.size()) - 1);
  int best = -1;
  double best_cost = 0;
  PlanarMotion best_motion;
  int needed = options.max_iterations;
  for (int it = 0; it < needed && it < options.max_iterations; ++it) {
    const int i = drawable[static_cast<std::size_t>(pick(rng))];
    const int j = drawable[static_cast<std::size_t>(pick(rng))];
    if (i == j) continue;
    for (const PlanarMotion& m : solve_planar_two_point(a[i], b[i], a[j], b[j])) {
      double cost = 0;
      const int count = count_inliers(a, b, m, threshold, nullptr, &cost);
      if (count > best || (count == best && cost < best_cost)) {
        best = count;
        best_cost = cost;
        best_motion = m;
        // Adaptive stop: draws needed to see two inliers at least once with the wanted confidence.
        const double w = static_cast<double>(count) / n;
        const double p_good = std::max(1e-12, w * w);
        if (p_good >= 1.0)
          needed = it + 1;
        else
          needed = static_cast<int>(std::ceil(std::log(1 - options.confidence) / std::log(1 - p_good)));
      }
    }
  }
  if (best < options.min_inliers) return out;
  PlanarMotion m = best_motion;
  std::vector<bool> mask(static_cast<std::size_t>(n));
  count_inliers(a, b, m, threshold, &mask, nullptr);
  for (int pass = 0; pass < 3; ++pass) {
    m = refine(a, b, mask, m);
    count_inliers(a, b, m, threshold, &mask, nullptr);
  }
  out.motion = m;
  out.inlier = mask;
  std::vector<double> errors, parallax;
  for (int k = 0; k < n; ++k) {
    if (!mask[static_cast<std::size_t>(k)]) continue;
    errors.push_back(planar_epipolar_angle(a[k], b[k], m));
    const Eigen::Vector3d rb = rotate_z(b[k], m.turn);
    parallax.push_back(std::atan2(a[k].cross(rb).norm(), a[k].dot(rb)));
  }
  out.inliers = static_cast<int>(errors.size());
  if (out.inliers < options.min_inliers) return out;
  double sq = 0;
  for (double e : errors) sq += e * e;
  out.rms_error_deg = std::sqrt(sq / out.inliers) * 180.0 / M_PI;
  out.median_parallax_deg = median(parallax) * 180.0 / M_PI;
  out.valid = true;
  return out;
}

}  // namespace plenopath
