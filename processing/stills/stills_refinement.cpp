#include "processing/stills/stills_refinement.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <string>

#include "model/option_check.h"
#include "processing/egomotion/bearing_cost.h"
#include "processing/egomotion/planar_two_view.h"

namespace plenopath {

void StillsRefinementOptions::check() const {
  const std::string s = "StillsRefinementOptions.";
  require_option(loss_scale_deg > 0, s + "loss_scale_deg", "must be > 0", loss_scale_deg);
  require_option(max_error_deg > 0, s + "max_error_deg", "must be > 0", max_error_deg);
  require_option(min_triangulation_deg > 0, s + "min_triangulation_deg", "must be > 0",
                 min_triangulation_deg);
  require_option(max_iterations >= 1, s + "max_iterations", "must be >= 1", max_iterations);
}

namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Vector3d world_direction(const Eigen::Vector3d& pose, const Eigen::Vector3d& bearing) {
  const double c = std::cos(pose.z()), s = std::sin(pose.z());
  return {c * bearing.x() - s * bearing.y(), s * bearing.x() + c * bearing.y(), bearing.z()};
}

double ray_error(const Eigen::Vector3d& pose, const Eigen::Vector3d& point, const Eigen::Vector3d& bearing) {
  const Eigen::Vector3d d = point - Eigen::Vector3d(pose.x(), pose.y(), 0.0);
  const Eigen::Vector3d w = world_direction(pose, bearing);
  return std::atan2(d.cross(w).norm(), d.dot(w));
}

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

void quiet_ceres_logging() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("plenopath");
    FLAGS_logtostderr = true;
    FLAGS_minloglevel = google::GLOG_ERROR;
  });
}

double rms_error(const StillsBundle& b) {
  double s = 0;
  for (const StillObservation& o : b.observations) {
    const double e = ray_error(b.poses[static_cast<std::size_t>(o.still)],
                               b.points[static_cast<std::size_t>(o.point)], o.bearing);
    s += e * e;
  }
  return b.observations.empty() ? 0.0 : std::sqrt(s / static_cast<double>(b.observations.size()));
}

}  // namespace

StillsBundle build_stills_bundle(const std::vector<std::vector<Eigen::Vector3d>>& bearings,
                                 const std::vector<PairMatches>& pairs, const std::vector<int>& group,
                                 const std::vector<Eigen::Vector3d>& poses,
                                 const StillsRefinementOptions& options) {
  options.check();
  StillsBundle out;
  out.poses = poses;
  std::vector<char> in_group(bearings.size(), 0);
  for (int i : group) in_group[static_cast<std::size_t>(i)] = 1;
  // Nodes (still, feature) numbered by still offsets; union-find over the verified matches.
  std::vector<int> offset(bearings.size() + 1, 0);
  for (std::size_t i = 0; i < bearings.size(); ++i)
    offset[i + 1] = offset[i] + static_cast<int>(bearings[i].size());
  std::vector<int> parent(static_cast<std::size_t>(offset.back()));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  };
  std::vector<char> used(parent.size(), 0);
  for (const PairMatches& p : pairs) {
    if (!in_group[static_cast<std::size_t>(p.a)] || !in_group[static_cast<std::size_t>(p.b)]) continue;
    for (const auto& [fa, fb] : p.features) {
      const int na = offset[static_cast<std::size_t>(p.a)] + fa,
                nb = offset[static_cast<std::size_t>(p.b)] + fb;
      used[static_cast<std::size_t>(na)] = used[static_cast<std::size_t>(nb)] = 1;
      const int ra = find(na), rb = find(nb);
      if (ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
    }
  }
  std::map<int, std::vector<int>> tracks;  // root -> nodes
  for (int node = 0; node < static_cast<int>(parent.size()); ++node)
    if (used[static_cast<std::size_t>(node)]) tracks[find(node)].push_back(node);
  const double min_angle = options.min_triangulation_deg * kDeg;
  for (const auto& [root, nodes] : tracks) {
    std::vector<int> stills;
    std::vector<Eigen::Vector3d> track_bearings, centres, directions;
    bool conflict = false;
    for (int node : nodes) {
      const int still =
          static_cast<int>(std::upper_bound(offset.begin(), offset.end(), node) - offset.begin()) - 1;
      if (std::find(stills.begin(), stills.end(), still) != stills.end()) conflict = true;
      stills.push_back(still);
      const Eigen::Vector3d& b =
          bearings[static_cast<std::size_t>(still)]
                  [static_cast<std::size_t>(node - offset[static_cast<std::size_t>(still)])];
      const Eigen::Vector3d& pose = poses[static_cast<std::size_t>(still)];
      track_bearings.push_back(b);
      centres.emplace_back(pose.x(), pose.y(), 0.0);
      directions.push_back(world_direction(pose, b));
    }
    if (conflict || stills.size() < 2) continue;  // two features of one still: a wrong match somewhere
    Eigen::Vector3d point;
    if (!triangulate_rays(centres, directions, min_angle, &point)) continue;
    const int q = static_cast<int>(out.points.size());
    out.points.push_back(point);
    out.point_views.push_back(static_cast<int>(stills.size()));
    for (std::size_t k = 0; k < stills.size(); ++k)
      out.observations.push_back({stills[k], q, track_bearings[k]});
  }
  return out;
}

StillsRefinementReport refine_stills(StillsBundle* bundle, const std::vector<int>& group,
                                     const StillsRefinementOptions& options, Progress& progress) {
  options.check();
  quiet_ceres_logging();
  StillsRefinementReport report;
  StillsBundle& b = *bundle;
  report.initial_rms_deg = rms_error(b) / kDeg;
  if (group.size() < 2 || b.observations.empty()) {
    report.final_rms_deg = report.initial_rms_deg;
    return report;
  }
  const int anchor = group.front();
  int far = anchor;
  double far_distance = 0;
  for (int i : group) {
    const double d =
        (b.poses[static_cast<std::size_t>(i)].head<2>() - b.poses[static_cast<std::size_t>(anchor)].head<2>())
            .norm();
    if (d > far_distance) {
      far_distance = d;
      far = i;
    }
  }
  for (int pass = 0; pass < 2; ++pass) {
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    ceres::CauchyLoss loss(options.loss_scale_deg * kDeg);
    std::vector<int> count(b.points.size(), 0);
    for (const StillObservation& o : b.observations) ++count[static_cast<std::size_t>(o.point)];
    int residuals = 0;
    for (const StillObservation& o : b.observations) {
      if (count[static_cast<std::size_t>(o.point)] < 2) continue;
      problem.AddResidualBlock(PlanarBearingCost::Create(o.bearing), &loss,
                               b.poses[static_cast<std::size_t>(o.still)].data(),
                               b.points[static_cast<std::size_t>(o.point)].data());
      ++residuals;
    }
    if (residuals == 0) break;
    if (problem.HasParameterBlock(b.poses[static_cast<std::size_t>(anchor)].data()))
      problem.SetParameterBlockConstant(b.poses[static_cast<std::size_t>(anchor)].data());
    if (far != anchor && far_distance > 0 &&
        problem.HasParameterBlock(b.poses[static_cast<std::size_t>(far)].data()) &&
        problem.HasParameterBlock(b.poses[static_cast<std::size_t>(anchor)].data()))
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<DistancePrior, 1, 3, 3>(new DistancePrior(
                                   far_distance, 1e3 * std::sqrt(static_cast<double>(residuals)))),
                               nullptr, b.poses[static_cast<std::size_t>(anchor)].data(),
                               b.poses[static_cast<std::size_t>(far)].data());
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::SPARSE_SCHUR;
    solver.max_num_iterations = options.max_iterations;
    solver.function_tolerance = 1e-8;
    solver.parameter_tolerance = 1e-10;
    solver.logging_type = ceres::SILENT;
    ProgressCallback callback(progress, 0.5 * pass, 0.5 * (pass + 1), options.max_iterations);
    solver.callbacks.push_back(&callback);
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    report.iterations += static_cast<int>(summary.iterations.size());
    progress.throw_if_cancelled();
    if (pass == 1) break;
    // Drop the observations far off, and points left with fewer than two.
    std::vector<StillObservation> kept;
    for (const StillObservation& o : b.observations) {
      if (ray_error(b.poses[static_cast<std::size_t>(o.still)], b.points[static_cast<std::size_t>(o.point)],
                    o.bearing) <= options.max_error_deg * kDeg)
        kept.push_back(o);
      else
        ++report.dropped_observations;
    }
    b.observations = std::move(kept);
  }
  // Points observed fewer than twice no longer count.
  std::vector<int> count(b.points.size(), 0);
  for (const StillObservation& o : b.observations) ++count[static_cast<std::size_t>(o.point)];
  std::vector<StillObservation> kept;
  for (const StillObservation& o : b.observations)
    if (count[static_cast<std::size_t>(o.point)] >= 2) kept.push_back(o);
  b.observations = std::move(kept);
  for (std::size_t q = 0; q < b.points.size(); ++q) {
    b.point_views[q] = count[q] >= 2 ? count[q] : 0;
    report.points += count[q] >= 2;
  }
  report.observations = static_cast<int>(b.observations.size());
  report.final_rms_deg = rms_error(b) / kDeg;
  return report;
}

}  // namespace plenopath
