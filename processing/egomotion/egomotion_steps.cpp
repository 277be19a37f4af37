#include "processing/egomotion/egomotion_steps.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "processing/egomotion/bearing_cost.h"

namespace plenopath::egomotion_steps {

Eigen::Vector3d rotate_z(const Eigen::Vector3d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}

void add_flag(PathFrame& f, FrameFlag flag, const std::string& why) {
  if (f.flags & flag) return;
  f.flags |= flag;
  f.reason += (f.reason.empty() ? "" : "; ") + why;
}

double ray_error(const Eigen::Vector3d& pose, const Eigen::Vector3d& point, const Eigen::Vector3d& bearing) {
  const Eigen::Vector3d d = rotate_z(bearing, pose.z());
  const Eigen::Vector3d v = point - Eigen::Vector3d(pose.x(), pose.y(), 0.0);
  return std::atan2(d.cross(v).norm(), d.dot(v));
}

int resect_pose(Eigen::Vector3d* pose, const std::vector<Eigen::Vector3d>& points,
                const std::vector<Eigen::Vector3d>& bearings, double huber, double inlier_threshold) {
  std::vector<PlanarBearingCost> costs;
  costs.reserve(bearings.size());
  for (const auto& b : bearings) costs.emplace_back(b);
  Eigen::Vector3d p = *pose;
  for (int it = 0; it < 10; ++it) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < points.size(); ++k) {
      double r[3];
      costs[k](p.data(), points[k].data(), r);
      Eigen::Matrix<double, 3, 3> j;
      for (int d = 0; d < 3; ++d) {
        Eigen::Vector3d q = p;
        const double h = 1e-7;
        q[d] += h;
        double rq[3];
        costs[k](q.data(), points[k].data(), rq);
        for (int e = 0; e < 3; ++e) j(e, d) = (rq[e] - r[e]) / h;
      }
      const Eigen::Vector3d rv(r[0], r[1], r[2]);
      const double n = rv.norm();
      const double w = n <= huber ? 1.0 : huber / n;
      jtj += w * j.transpose() * j;
      jtr += w * j.transpose() * rv;
    }
    const Eigen::Vector3d step = -(jtj + 1e-9 * Eigen::Matrix3d::Identity()).ldlt().solve(jtr);
    if (!step.allFinite()) break;
    p += step;
    if (step.norm() < 1e-9) break;
  }
  int inliers = 0;
  for (size_t k = 0; k < points.size(); ++k)
    inliers += ray_error(p, points[k], bearings[k]) < inlier_threshold;
  *pose = p;
  return inliers;
}

StepCheck check_step_against_points(const Eigen::Vector2d& a, const Eigen::Vector2d& measured,
                                    const Eigen::Vector2d& predicted, double heading_b,
                                    const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<Eigen::Vector3d>& bearings, double huber,
                                    double inlier_threshold, double factor, int min_points, double min_turn) {
  StepCheck out;
  out.position = measured;
  auto explained = [&](const Eigen::Vector2d& b) {
    const Eigen::Vector3d pose(b.x(), b.y(), heading_b);
    int count = 0;
    for (std::size_t q = 0; q < points.size(); ++q)
      count += ray_error(pose, points[q], bearings[q]) < inlier_threshold;
    return count;
  };
  Eigen::Vector3d resected(predicted.x(), predicted.y(), heading_b);
  resect_pose(&resected, points, bearings, huber, inlier_threshold);
  // The heading stays the tracked one: only the step is in question.
  const Eigen::Vector2d position = resected.head<2>();
  out.explained_measured = explained(measured);
  out.explained_resected = explained(position);
  const Eigen::Vector2d step_measured = measured - a, step_resected = position - a;
  if (step_measured.norm() <= 0 || step_resected.norm() <= 0) return out;
  const double turn = std::abs(std::remainder(
      std::atan2(step_resected.y(), step_resected.x()) - std::atan2(step_measured.y(), step_measured.x()),
      2 * M_PI));
  if (turn > min_turn && out.explained_resected >= min_points &&
      out.explained_resected >= factor * out.explained_measured) {
    out.replaced = true;
    out.position = position;
  }
  return out;
}

int resect_tilted_pose(Eigen::Vector3d* pose, Eigen::Vector2d* tilt,
                       const std::vector<Eigen::Vector3d>& points,
                       const std::vector<Eigen::Vector3d>& bearings, double huber, double inlier_threshold,
                       double tilt_weight) {
  using Vector5d = Eigen::Matrix<double, 5, 1>;
  using Matrix5d = Eigen::Matrix<double, 5, 5>;
  Vector5d x;
  x << *pose, *tilt;
  auto residual = [&](const Vector5d& v, std::size_t k) {
    const TiltedBearingCost cost(bearings[k]);
    Eigen::Vector3d r;
    cost(v.data(), v.data() + 3, points[k].data(), r.data());
    return r;
  };
  for (int it = 0; it < 10; ++it) {
    Matrix5d jtj = Matrix5d::Zero();
    Vector5d jtr = Vector5d::Zero();
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Eigen::Vector3d r = residual(x, k);
      Eigen::Matrix<double, 3, 5> j;
      for (int d = 0; d < 5; ++d) {
        Vector5d q = x;
        const double h = 1e-7;
        q[d] += h;
        j.col(d) = (residual(q, k) - r) / h;
      }
      const double n = r.norm();
      const double w = n <= huber ? 1.0 : huber / n;
      jtj += w * j.transpose() * j;
      jtr += w * j.transpose() * r;
    }
    const double w2 = tilt_weight * tilt_weight;
    jtj(3, 3) += w2;
    jtj(4, 4) += w2;
    jtr(3) += w2 * x(3);
    jtr(4) += w2 * x(4);
    const Vector5d step = -(jtj + 1e-9 * Matrix5d::Identity()).ldlt().solve(jtr);
    if (!step.allFinite()) break;
    x += step;
    if (step.norm() < 1e-9) break;
  }
  *pose = x.head<3>();
  *tilt = x.tail<2>();
  int inliers = 0;
  for (std::size_t k = 0; k < points.size(); ++k)
    inliers += tilted_ray_error(*pose, *tilt, points[k], bearings[k]) < inlier_threshold;
  return inliers;
}

int merge_loop_points(const std::vector<LoopMatch>& loops, BundleProblem* problem,
                      std::vector<int>* point_of_track) {
  std::vector<int> parent(problem->points.size());
  for (std::size_t q = 0; q < parent.size(); ++q) parent[q] = static_cast<int>(q);
  auto root = [&](int q) {
    while (parent[q] != q) q = parent[q] = parent[parent[q]];
    return q;
  };
  int merged = 0;
  for (const LoopMatch& m : loops)
    for (const auto& [ta, tb] : m.track_pairs) {
      const int pa = (*point_of_track)[ta], pb = (*point_of_track)[tb];
      if (pa < 0 || pb < 0) continue;
      const int ra = root(pa), rb = root(pb);
      if (ra == rb) continue;
      parent[std::max(ra, rb)] = std::min(ra, rb);
      ++merged;
    }
  if (merged == 0) return 0;
  std::vector<BundleObservation>& obs = problem->observations;
  for (BundleObservation& o : obs) o.point = root(o.point);
  std::sort(obs.begin(), obs.end(), [](const BundleObservation& a, const BundleObservation& b) {
    return a.point != b.point ? a.point < b.point : a.pose < b.pose;
  });
  obs.erase(std::unique(obs.begin(), obs.end(),
                        [](const BundleObservation& a, const BundleObservation& b) {
                          return a.point == b.point && a.pose == b.pose;
                        }),
            obs.end());
  for (int& q : *point_of_track)
    if (q >= 0) q = root(q);
  return merged;
}

TrackView::TrackView(const KltTracker& tracker, int frame_count)
    : klt(&tracker), frame_begin_(static_cast<std::size_t>(frame_count) + 1, 0) {
  // Counting sort by frame: tracks are visited in increasing order, so each frame's list is sorted.
  const int tracks = tracker.track_count();
  for (int t = 0; t < tracks; ++t)
    for (int f = tracker.first_frame(t); f <= std::min(tracker.last_frame(t), frame_count - 1); ++f)
      ++frame_begin_[static_cast<std::size_t>(f) + 1];
  for (std::size_t f = 1; f < frame_begin_.size(); ++f) frame_begin_[f] += frame_begin_[f - 1];
  track_ids_.resize(frame_begin_.back());
  std::vector<std::size_t> next(frame_begin_.begin(), frame_begin_.end() - 1);
  for (int t = 0; t < tracks; ++t)
    for (int f = tracker.first_frame(t); f <= std::min(tracker.last_frame(t), frame_count - 1); ++f)
      track_ids_[next[static_cast<std::size_t>(f)]++] = t;
}

Eigen::Vector3d TrackView::bearing(int track, int frame) const {
  return klt->bearing(klt->observation(track, frame));
}

}  // namespace plenopath::egomotion_steps
