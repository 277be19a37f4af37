// Registration, step 4 (registration.h): robust point-to-segment ICP of a similarity, and the final score.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "processing/registration/registration_internal.h"

namespace plenopath::registration_detail {
Similarity2 refine_icp(const std::vector<Eigen::Vector2d>& wall_points, const PlanRaster& plan,
                       const Similarity2& start, double start_truncation_m,
                       const RegistrationOptions& options) {
  // Centred on the points' mean for a well-conditioned system: q = s R (p - m) + u, u = t + s R m.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : wall_points) mean += p;
  mean /= static_cast<double>(wall_points.size());
  double rotation = start.rotation, log_scale = std::log(start.scale);
  Eigen::Vector2d u = start.apply(mean);
  const double max_log_scale = std::log1p(options.scale_range);
  const double final_truncation = 1.5 * options.inlier_tolerance_m;
  double truncation = std::max(start_truncation_m, final_truncation);
  const double prior_weight = std::pow(options.huber_m / options.scale_prior_sigma, 2);
  for (int iteration = 0; iteration < options.icp_iterations; ++iteration) {
    Eigen::Matrix4d h = Eigen::Matrix4d::Zero();
    Eigen::Vector4d g = Eigen::Vector4d::Zero();
    const double s = std::exp(log_scale);
    int used = 0;
    for (const Eigen::Vector2d& p : wall_points) {
      const Eigen::Vector2d v = s * rotate(p - mean, rotation);  // q - u
      const Eigen::Vector2d q = v + u;
      int col = 0, row = 0;
      if (!plan.cell_of(q, &col, &row)) continue;
      if (plan.distance.at<float>(row, col) > truncation + 2 * plan.cell) continue;
      const Segment2& seg = plan.walls[static_cast<std::size_t>(plan.nearest.at<int>(row, col))];
      const Eigen::Vector2d ab = seg.b - seg.a;
      const double len2 = ab.squaredNorm();
      const double t = len2 > 0 ? std::clamp((q - seg.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const Eigen::Vector2d closest = seg.a + t * ab;
      Eigen::Vector2d normal;
      if (t > 0 && t < 1 && len2 > 0) {
        normal = Eigen::Vector2d(-ab.y(), ab.x()) / std::sqrt(len2);
      } else {
        const Eigen::Vector2d d = q - closest;
        if (d.norm() < 1e-9) continue;
        normal = d / d.norm();
      }
      const double r = normal.dot(q - closest);
      const double ar = std::abs(r);
      if (ar > truncation) continue;
      const double w = ar <= options.huber_m ? 1.0 : options.huber_m / ar;
      // d q / d (rotation, u.x, u.y, log scale) = (perp(v), I, v).
      const Eigen::Vector4d j(normal.dot(Eigen::Vector2d(-v.y(), v.x())), normal.x(), normal.y(),
                              normal.dot(v));
      h += w * j * j.transpose();
      g += w * j * r;
      ++used;
    }
    if (used < 4) break;
    h(3, 3) += prior_weight;
    g(3) += prior_weight * log_scale;
    const Eigen::Vector4d delta = -h.ldlt().solve(g);
    if (!delta.allFinite()) break;
    rotation += delta(0);
    u += delta.segment<2>(1);
    log_scale = std::clamp(log_scale + delta(3), -max_log_scale, max_log_scale);
    const bool converged = std::abs(delta(0)) < 1e-6 && delta.segment<2>(1).norm() < 1e-5;
    if (truncation <= final_truncation && converged) break;
    truncation = std::max(final_truncation, 0.7 * truncation);
  }
  Similarity2 out;
  out.rotation = std::remainder(rotation, 2 * M_PI);
  out.scale = std::exp(log_scale);
  out.translation = u - out.scale * rotate(mean, out.rotation);
  return out;
}

bool seen_through_wall(const Eigen::Vector2d& camera, const Eigen::Vector2d& q, const SegmentGrid& grid,
                       double margin, double depth_margin) {
  // Beyond the wall by more than the point's depth uncertainty (a far wall's points scatter behind it), and
  // not on that wall (seen at a grazing angle, a point a few cm off its wall's line crosses that line well
  // before it).
  const double length = (q - camera).norm();
  const double behind = std::max(margin, depth_margin * length);
  for (int i : grid.along(camera, q)) {
    const Segment2& seg = grid.segments()[static_cast<std::size_t>(i)];
    double t = 0, u = 0;
    if (intersect_segments(camera, q, seg.a, seg.b, &t, &u) && (1 - t) * length > behind &&
        distance_point_segment(q, seg.a, seg.b) > margin)
      return true;
  }
  return false;
}

RegistrationCandidate score_placement(const std::vector<Eigen::Vector2d>& wall_points,
                                      const std::vector<Eigen::Vector2d>& observers,
                                      const std::vector<Eigen::Vector2d>& frames, const PlanRaster& plan,
                                      const SegmentGrid& grid, const Similarity2& transform,
                                      const RegistrationOptions& options) {
  RegistrationCandidate c;
  c.transform = transform;
  const double tol = options.inlier_tolerance_m;
  double soft = 0, sum2 = 0;
  int inliers = 0;
  for (const Eigen::Vector2d& p : wall_points) {
    const double d = grid.distance_within(transform.apply(p), tol);
    if (d >= tol) continue;
    soft += 1.0 - (d / tol) * (d / tol);
    sum2 += d * d;
    ++inliers;
  }
  // A point the placement puts beyond a wall from where it was measured contradicts it.
  int through = 0;
  if (options.seen_through_weight > 0 && observers.size() == wall_points.size())
    for (std::size_t i = 0; i < wall_points.size(); ++i)
      if (observers[i].allFinite() &&
          seen_through_wall(transform.apply(observers[i]), transform.apply(wall_points[i]), grid, tol,
                            options.seen_through_depth_margin))
        ++through;
  int free = 0;
  for (const Eigen::Vector2d& f : frames) free += plan.is_free(transform.apply(f));
  const double n = static_cast<double>(wall_points.size());
  c.wall_share = wall_points.empty() ? 0.0 : inliers / n;
  c.through_share = wall_points.empty() ? 0.0 : through / n;
  c.free_share = frames.empty() ? 1.0 : double(free) / frames.size();
  c.rms_m = inliers ? std::sqrt(sum2 / inliers) : 0.0;
  c.score = wall_points.empty()
                ? 0.0
                : std::max(0.0, (soft - options.seen_through_weight * through) / n) * c.free_share;
  return c;
}

}  // namespace plenopath::registration_detail
