#include "processing/egomotion/path_refinement.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/egomotion/bearing_cost.h"

namespace plenopath {
namespace {

// Holds the distance between two poses near its initial value: fixes the scale gauge softly.
struct DistancePrior {
  DistancePrior(double distance, double weight) : distance(distance), weight(weight) {}
  template <typename T>
  bool operator()(const T* a, const T* b, T* residual) const {
    using std::sqrt;
    const T dx = a[0] - b[0], dy = a[1] - b[1];
    residual[0] = T(weight) * (sqrt(dx * dx + dy * dy + T(1e-18)) - T(distance)) / T(distance);
    return true;
  }
  double distance, weight;
};

// Reports each iteration to [begin, end] of `progress` and stops the solver when cancelled (no exception
// through Ceres: the caller throws once Solve() has returned).
class ProgressCallback : public ceres::IterationCallback {
 public:
  ProgressCallback(Progress& progress, double begin, double end, int max_iterations)
      : progress_(progress, begin, end), max_iterations_(std::max(1, max_iterations)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    progress_.report(std::min(1.0, static_cast<double>(summary.iteration) / max_iterations_));
    return progress_.is_cancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  SubProgress progress_;
  int max_iterations_;
};

// Ceres reports through glog. Uninitialised, glog prefixes a warning about that to every message; and what
// Ceres has to say (e.g. CHOLMOD on an ill-conditioned step, which the trust region then rejects and
// retries) is not for the user. Initialised once, errors only.
void quiet_ceres_logging() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("plenopath");
    FLAGS_logtostderr = true;
    FLAGS_minloglevel = google::GLOG_ERROR;
  });
}

double rms(const std::vector<double>& e) {
  double s = 0.0;
  for (double v : e) s += v * v;
  return e.empty() ? 0.0 : std::sqrt(s / e.size());
}

// Solves with poses [first, last] free except those in [first, held_end), those from held_from on, and pose
// 0, which are held. Throws Cancelled.
void solve_range(BundleProblem& p, const RefinementOptions& options, int first, int last, int held_end,
                 int max_iterations, Progress& progress, double begin, double end, RefinementReport* report,
                 int held_from = std::numeric_limits<int>::max()) {
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::CauchyLoss loss(options.loss_scale);
  // Points with two or more observations from the range.
  std::vector<int> count(p.points.size(), 0);
  for (const BundleObservation& o : p.observations)
    if (o.pose >= first && o.pose <= last) ++count[o.point];
  int residuals = 0;
  std::vector<bool> pose_used(p.poses.size(), false);
  const bool tilted = !p.tilts.empty();
  for (const BundleObservation& o : p.observations) {
    if (o.pose < first || o.pose > last || count[o.point] < 2) continue;
    if (tilted) {
      problem.AddResidualBlock(TiltedBearingCost::Create(o.bearing()), &loss, p.poses[o.pose].data(),
                               p.tilts[o.pose].data(), p.points[o.point].data());
    } else {
      problem.AddResidualBlock(PlanarBearingCost::Create(o.bearing()), &loss, p.poses[o.pose].data(),
                               p.points[o.point].data());
    }
    pose_used[o.pose] = true;
    ++residuals;
  }
  if (residuals == 0) return;
  // The prior's weight: a tilt of one prior spread costs as much as one observation at the loss scale.
  const double tilt_weight = tilted ? options.loss_scale / (options.tilt_prior_deg * M_PI / 180.0) : 0.0;
  bool any_free = false;
  for (int i = first; i <= last; ++i) {
    if (!pose_used[i]) continue;
    const bool held = i < held_end || i == 0 || i >= held_from;
    if (held) {
      problem.SetParameterBlockConstant(p.poses[i].data());
    } else {
      any_free = true;
    }
    if (tilted) {
      problem.AddResidualBlock(TiltPrior::Create(tilt_weight), nullptr, p.tilts[i].data());
      // Pose 0 holds the gauge of the plane only: its tilt is measured like any other. A window's held
      // poses were solved by the window before, tilt and all.
      if (held && i != 0) problem.SetParameterBlockConstant(p.tilts[i].data());
      if (i == 0) any_free = true;
    }
  }
  // Scale gauge: when fewer than two poses are held, hold the distance from the first used pose to the
  // farthest one.
  int held = 0;
  for (int i = first; i < std::min(held_end, last + 1); ++i) held += pose_used[i];
  for (int i = std::max(first, std::min(held_from, last + 1)); i <= last; ++i) held += pose_used[i];
  if (first == 0 && !pose_used[0]) held = 0;
  if (held < 2) {
    int anchor = first;
    while (anchor <= last && !pose_used[anchor]) ++anchor;
    int far = anchor;
    double best = 0.0;
    for (int i = anchor; i <= last; ++i) {
      if (!pose_used[i]) continue;
      const double d = (p.poses[i].head<2>() - p.poses[anchor].head<2>()).norm();
      if (d > best) {
        best = d;
        far = i;
      }
    }
    if (best > 0) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<DistancePrior, 1, 3, 3>(
                                   new DistancePrior(best, 1e3 * std::sqrt(static_cast<double>(residuals)))),
                               nullptr, p.poses[anchor].data(), p.poses[far].data());
    }
  }
  if (!any_free) return;
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_SCHUR;
  solver.max_num_iterations = max_iterations;
  solver.num_threads = options.threads;
  solver.function_tolerance = 1e-7;
  solver.parameter_tolerance = 1e-9;
  solver.logging_type = ceres::SILENT;
  ProgressCallback callback(progress, begin, end, max_iterations);
  solver.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  report->iterations += static_cast<int>(summary.iterations.size());
  progress.throw_if_cancelled();
}

// The points not marked in `done` (and marked there once placed) by least squares on their rays from the
// current poses (the point nearest all of them): for each, sum (I - d d^T) p = sum (I - d d^T) c. Points
// whose rays are too near parallel to fix a position are left as they are.
void retriangulate(BundleProblem& p, std::vector<char>& done) {
  std::vector<Eigen::Matrix3d> a(p.points.size(), Eigen::Matrix3d::Zero());
  std::vector<Eigen::Vector3d> rhs(p.points.size(), Eigen::Vector3d::Zero());
  const bool tilted = !p.tilts.empty();
  for (const BundleObservation& o : p.observations) {
    const std::size_t q = static_cast<std::size_t>(o.point);
    if (done[q]) continue;
    const Eigen::Vector3d& pose = p.poses[static_cast<std::size_t>(o.pose)];
    // world_from_camera = Rz(heading) Ry(pitch) Rx(roll), as tilted_camera_direction (bearing_cost.h) undoes.
    Eigen::Matrix3d r = Eigen::AngleAxisd(pose.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    if (tilted) {
      const Eigen::Vector2d& t = p.tilts[static_cast<std::size_t>(o.pose)];
      r = r * Eigen::AngleAxisd(t.x(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(t.y(), Eigen::Vector3d::UnitX());
    }
    const Eigen::Vector3d d = (r * o.bearing()).normalized();
    const Eigen::Matrix3d m = Eigen::Matrix3d::Identity() - d * d.transpose();
    a[q] += m;
    rhs[q] += m * Eigen::Vector3d(pose.x(), pose.y(), 0.0);
  }
  for (std::size_t q = 0; q < p.points.size(); ++q) {
    if (done[q] || a[q].isZero()) continue;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(a[q]);
    // The smallest eigenvalue is about n sin^2 of the rays' spread: below (1 deg)^2 a ray, no position.
    if (!(eigen.eigenvalues()[0] > 3e-4 * a[q].trace() / 2.0)) continue;
    p.points[q] = a[q].ldlt().solve(rhs[q]);
    done[q] = 1;
  }
}

// Moves the poses after `last` and the points first seen after it by the rigid motion that took pose
// `last` from `before` to `after`.
void carry_along(BundleProblem& p, const std::vector<int>& first_pose_of_point, int last,
                 const Eigen::Vector3d& before, const Eigen::Vector3d& after) {
  const double turn = after.z() - before.z();
  const double c = std::cos(turn), s = std::sin(turn);
  auto move = [&](double* x, double* y) {
    const double dx = *x - before.x(), dy = *y - before.y();
    *x = after.x() + c * dx - s * dy;
    *y = after.y() + s * dx + c * dy;
  };
  for (size_t i = last + 1; i < p.poses.size(); ++i) {
    move(&p.poses[i].x(), &p.poses[i].y());
    p.poses[i].z() += turn;
  }
  for (size_t q = 0; q < p.points.size(); ++q)
    if (first_pose_of_point[q] > last && first_pose_of_point[q] < static_cast<int>(p.poses.size()))
      move(&p.points[q].x(), &p.points[q].y());
}

// At most about `limit` observations: each point keeps its first and last and evenly spaced ones between
// (at least three), so that every point still ties together the stretch of path that saw it. When even three
// a point are too many (a long capture: 100 000 frames make about two million points), only some points take
// part, spread evenly over the poses: for each pose, of the points first seen there, those seen over the
// longest stretch of poses (a point tied by loop closure spans both visits).
std::vector<BundleObservation> thinned(const std::vector<BundleObservation>& observations,
                                       std::size_t limit) {
  // Observation indices by point, each point's in pose order (no per-point vectors: millions of points).
  std::vector<int> order(observations.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const BundleObservation &oa = observations[static_cast<std::size_t>(a)],
                            &ob = observations[static_cast<std::size_t>(b)];
    return oa.point != ob.point ? oa.point < ob.point : oa.pose < ob.pose;
  });
  struct Run {
    std::size_t begin, end;  // in `order`
  };
  std::vector<Run> runs;  // one per point with observations
  for (std::size_t k = 0; k < order.size();) {
    std::size_t e = k + 1;
    while (e < order.size() && observations[static_cast<std::size_t>(order[e])].point ==
                                   observations[static_cast<std::size_t>(order[k])].point)
      ++e;
    runs.push_back({k, e});
    k = e;
  }
  const std::size_t seen = runs.size();
  constexpr std::size_t kMinKeep = 3;
  const std::size_t keep = std::max<std::size_t>(kMinKeep, seen > 0 ? limit / seen : kMinKeep);
  if (seen * kMinKeep > limit) {
    // Too many points: by first pose, the longest-seen first, an even quota per pose.
    auto pose_at = [&](std::size_t k) { return observations[static_cast<std::size_t>(order[k])].pose; };
    auto span = [&](const Run& r) { return pose_at(r.end - 1) - pose_at(r.begin); };
    std::stable_sort(runs.begin(), runs.end(), [&](const Run& a, const Run& b) {
      return pose_at(a.begin) != pose_at(b.begin) ? pose_at(a.begin) < pose_at(b.begin) : span(a) > span(b);
    });
    int poses = 0;
    for (std::size_t r = 0; r < runs.size(); ++r)
      poses += r == 0 || pose_at(runs[r].begin) != pose_at(runs[r - 1].begin);
    const std::size_t quota =
        std::max<std::size_t>(1, limit / kMinKeep / static_cast<std::size_t>(std::max(1, poses)));
    std::vector<Run> chosen;
    std::size_t taken = 0;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      if (r > 0 && pose_at(runs[r].begin) != pose_at(runs[r - 1].begin)) taken = 0;
      if (taken++ < quota) chosen.push_back(runs[r]);
    }
    runs = std::move(chosen);
  }
  std::vector<BundleObservation> out;
  out.reserve(std::min(observations.size(), keep * runs.size()));
  for (const Run& run : runs) {
    const std::size_t size = run.end - run.begin;
    if (size <= keep) {
      for (std::size_t k = run.begin; k < run.end; ++k)
        out.push_back(observations[static_cast<std::size_t>(order[k])]);
      continue;
    }
    for (std::size_t j = 0; j < keep; ++j)
      out.push_back(observations[static_cast<std::size_t>(
          order[run.begin + static_cast<std::size_t>(std::lround(double(j) * (size - 1) / (keep - 1)))])]);
  }
  return out;
}

}  // namespace

void RefinementOptions::check() const {
  const std::string s = "RefinementOptions.";
  require_option(loss_scale > 0, s + "loss_scale", "must be > 0", loss_scale);
  require_option(window_keyframes == 0 || window_keyframes >= 4, s + "window_keyframes", "must be 0 or >= 4",
                 window_keyframes);
  require_option(window_overlap >= 2 && (window_keyframes == 0 || window_overlap < window_keyframes),
                 s + "window_overlap", "must be >= 2 and below window_keyframes", window_overlap);
  require_option(window_max_iterations >= 0, s + "window_max_iterations", "must be >= 0",
                 window_max_iterations);
  require_option(global_max_iterations >= 0, s + "global_max_iterations", "must be >= 0",
                 global_max_iterations);
  require_option(threads >= 1, s + "threads", "must be >= 1", threads);
  require_option(outlier_threshold >= 0, s + "outlier_threshold", "must be >= 0", outlier_threshold);
  require_option(tilt_prior_deg >= 0 && tilt_prior_deg <= 20, s + "tilt_prior_deg", "must be in [0, 20]",
                 tilt_prior_deg);
  require_option(global_max_observations >= 0, s + "global_max_observations", "must be >= 0 (0 = no limit)",
                 global_max_observations);
}

std::vector<double> observation_errors(const BundleProblem& p) {
  std::vector<double> e;
  e.reserve(p.observations.size());
  for (const BundleObservation& o : p.observations) {
    const Eigen::Vector3d& q = p.points[o.point];
    const Eigen::Vector3d& c = p.poses[o.pose];
    if (!p.tilts.empty()) {
      e.push_back(tilted_ray_error(c, p.tilts[o.pose], q, o.bearing()));
      continue;
    }
    const double ch = std::cos(c.z()), sh = std::sin(c.z());
    const Eigen::Vector3d d(ch * (q.x() - c.x()) + sh * (q.y() - c.y()),
                            -sh * (q.x() - c.x()) + ch * (q.y() - c.y()), q.z());
    const Eigen::Vector3d b = o.bearing();
    const double angle = std::atan2(d.cross(b).norm(), d.dot(b));
    e.push_back(std::isfinite(angle) ? angle : M_PI);
  }
  return e;
}

RefinementReport refine_bundle(BundleProblem& problem, const RefinementOptions& options, Progress& progress) {
  options.check();
  quiet_ceres_logging();
  RefinementReport report;
  if (options.tilt_prior_deg > 0 && problem.tilts.size() != problem.poses.size())
    problem.tilts.assign(problem.poses.size(), Eigen::Vector2d::Zero());
  if (options.tilt_prior_deg == 0) problem.tilts.clear();
  report.initial_rms = rms(observation_errors(problem));
  const int n = static_cast<int>(problem.poses.size());
  if (n < 2) {
    report.final_rms = report.initial_rms;
    return report;
  }
  const bool windowed = options.window_keyframes > 0 && n > options.window_keyframes;
  std::vector<int> first_pose_of_point(problem.points.size(), n);
  for (const BundleObservation& o : problem.observations)
    first_pose_of_point[o.point] = std::min(first_pose_of_point[o.point], o.pose);
  const double windowed_share = windowed ? (options.global_max_iterations > 0 ? 0.5 : 1.0) : 0.0;
  if (windowed) {
    const int stride = options.window_keyframes - options.window_overlap;
    const int windows = (n - options.window_overlap + stride - 1) / stride;
    for (int w = 0, first = 0; first + options.window_overlap < n; ++w, first += stride) {
      const int last = std::min(n - 1, first + options.window_keyframes - 1);
      const int held_end = w == 0 ? 1 : first + options.window_overlap;
      const double begin = windowed_share * w / windows, end = windowed_share * (w + 1) / windows;
      ++report.windows;
      const Eigen::Vector3d last_before = problem.poses[last];
      solve_range(problem, options, first, last, held_end, options.window_max_iterations, progress, begin,
                  end, &report);
      // The poses and points beyond the window have not moved yet: carry them along with the window's last
      // pose, so that the next window does not start from a kink (held poses corrected, free ones not),
      // which can trap its first free poses in a wrong minimum.
      carry_along(problem, first_pose_of_point, last, last_before, problem.poses[last]);
    }
  }
  // The global pass, on a thinned set of observations when there are too many (the full set is kept and
  // put back after each solve).
  const std::size_t limit = static_cast<std::size_t>(options.global_max_observations);
  bool thinned_any = false;
  // A thinned global pass fixed the path's shape; windows against every observation, each holding its first
  // and last poses (so the shape stays), restore the detail the thinning left out.
  auto restore_detail = [&]() {
    const int size = options.window_keyframes > 0 ? options.window_keyframes : 80;
    const int overlap = std::min(options.window_overlap, size / 4);
    for (int first = 0; first + overlap < n; first += size - 2 * overlap) {
      const int last = std::min(n - 1, first + size - 1);
      const int held_from = last == n - 1 ? n : last - overlap + 1;
      solve_range(problem, options, first, last, first == 0 ? 1 : first + overlap,
                  options.window_max_iterations, progress, 1.0, 1.0, &report, held_from);
      if (last == n - 1) break;
    }
  };
  auto solve_global = [&](int max_iterations, double begin, double end) {
    if (limit == 0 || problem.observations.size() <= limit) {
      solve_range(problem, options, 0, n - 1, 1, max_iterations, progress, begin, end, &report);
      return;
    }
    thinned_any = true;
    std::vector<BundleObservation> all = thinned(problem.observations, limit);
    // Points left out of the pass (too many for even three observations each) do not move with it: each
    // is then triangulated anew from the moved poses (or, where its rays are too near parallel, carried by
    // the motion of the first pose that saw it), so that the outlier test and the windows after start from
    // where its poses went (left behind, a sixth of all observations were dropped as outliers).
    std::vector<char> in_pass(problem.points.size(), 0);
    for (const BundleObservation& o : all) in_pass[static_cast<std::size_t>(o.point)] = 1;
    std::vector<char> observed(problem.points.size(), 0);
    for (const BundleObservation& o : problem.observations) observed[static_cast<std::size_t>(o.point)] = 1;
    bool subset = false;
    for (std::size_t q = 0; q < in_pass.size() && !subset; ++q) subset = observed[q] && !in_pass[q];
    const std::vector<Eigen::Vector3d> poses_before = subset ? problem.poses : std::vector<Eigen::Vector3d>();
    std::swap(all, problem.observations);
    solve_range(problem, options, 0, n - 1, 1, max_iterations, progress, begin, end, &report);
    std::swap(all, problem.observations);
    if (!subset) return;
    retriangulate(problem, in_pass);
    for (std::size_t q = 0; q < in_pass.size(); ++q) {
      const int k = first_pose_of_point[q];
      if (in_pass[q] || k >= n) continue;  // in_pass: also the points retriangulate() placed
      const Eigen::Vector3d &before = poses_before[static_cast<std::size_t>(k)],
                            &after = problem.poses[static_cast<std::size_t>(k)];
      const double turn = after.z() - before.z(), c = std::cos(turn), s = std::sin(turn);
      Eigen::Vector3d& point = problem.points[q];
      const double dx = point.x() - before.x(), dy = point.y() - before.y();
      point.x() = after.x() + c * dx - s * dy;
      point.y() = after.y() + s * dx + c * dy;
    }
    // With only some points in the pass, each pose was fixed by a few of them: the detail comes back before
    // anything is judged an outlier against it.
    restore_detail();
  };
  if (options.global_max_iterations > 0) {
    const double split = options.outlier_threshold > 0 ? windowed_share + 0.7 * (1 - windowed_share) : 1.0;
    solve_global(options.global_max_iterations, windowed_share, split);
    if (options.outlier_threshold > 0) {
      const std::vector<double> errors = observation_errors(problem);
      // Whole points that fit badly go too: a "corner" where an edge crosses a farther surface (no 3-D
      // point) slides smoothly as the camera moves, so each of its observations is only a little off.
      std::vector<double> point_sum(problem.points.size(), 0.0);
      std::vector<int> point_count(problem.points.size(), 0);
      for (size_t k = 0; k < errors.size(); ++k) {
        point_sum[problem.observations[k].point] += errors[k] * errors[k];
        ++point_count[problem.observations[k].point];
      }
      std::vector<double> point_rms;
      for (size_t q = 0; q < point_sum.size(); ++q)
        if (point_count[q] > 0) point_rms.push_back(std::sqrt(point_sum[q] / point_count[q]));
      double point_limit = std::numeric_limits<double>::infinity();
      if (options.point_outlier_factor > 0 && !point_rms.empty()) {
        std::nth_element(point_rms.begin(), point_rms.begin() + point_rms.size() / 2, point_rms.end());
        point_limit = options.point_outlier_factor * point_rms[point_rms.size() / 2];
      }
      // Compacted in place: a second copy of tens of millions of observations is what a long capture
      // cannot afford.
      std::vector<BundleObservation>& obs = problem.observations;
      std::size_t kept = 0;
      for (size_t k = 0; k < errors.size(); ++k) {
        const int q = obs[k].point;
        if (errors[k] <= options.outlier_threshold && std::sqrt(point_sum[q] / point_count[q]) <= point_limit)
          obs[kept++] = obs[k];
      }
      report.outliers_removed = static_cast<int>(obs.size() - kept);
      obs.resize(kept);
      solve_global(std::max(1, options.global_max_iterations / 2), split, 1.0);
    }
    if (thinned_any) restore_detail();
  }
  report.final_rms = rms(observation_errors(problem));
  return report;
}

}  // namespace plenopath
