#include "processing/egomotion/path_refinement.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/egomotion/bearing_cost.h"
#include "processing/egomotion/path_evaluation.h"
#include "processing/egomotion/pose_graph.h"
#include "processing/util/statistics.h"

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

// Holds a floor point's height at the floor level (a parameter): weight = 1 / the spread in plan units.
struct FloorLevelCost {
  explicit FloorLevelCost(double weight) : weight(weight) {}
  template <typename T>
  bool operator()(const T* point, const T* level, T* residual) const {
    residual[0] = T(weight) * (point[2] - level[0]);
    return true;
  }
  double weight;
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

// Of all observations' errors, without a list of them (tens of millions in a long capture).
double error_rms(const BundleProblem& p) {
  double s = 0.0;
  for (const BundleObservation& o : p.observations) s += std::pow(observation_error(p, o), 2);
  return p.observations.empty() ? 0.0 : std::sqrt(s / p.observations.size());
}

bool pose_order(const BundleObservation& a, const BundleObservation& b) {
  return a.pose != b.pose ? a.pose < b.pose : a.point < b.point;
}

// The observations of poses [first, last]: refine_bundle keeps them sorted by pose (pose_order), so that a
// window of a long capture does not scan tens of millions of them.
std::pair<std::vector<BundleObservation>::const_iterator, std::vector<BundleObservation>::const_iterator>
pose_range(const std::vector<BundleObservation>& observations, int first, int last) {
  const auto begin = std::partition_point(observations.begin(), observations.end(),
                                          [&](const BundleObservation& o) { return o.pose < first; });
  const auto end = std::partition_point(begin, observations.end(),
                                        [&](const BundleObservation& o) { return o.pose <= last; });
  return {begin, end};
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
  const auto [range_begin, range_end] = pose_range(p.observations, first, last);
  std::vector<int> count(p.points.size(), 0);
  for (auto o = range_begin; o != range_end; ++o) ++count[o->point];
  int residuals = 0;
  std::vector<bool> pose_used(p.poses.size(), false);
  const bool tilted = !p.tilts.empty();
  for (auto it = range_begin; it != range_end; ++it) {
    const BundleObservation& o = *it;
    if (count[o.point] < 2) continue;
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
  // Poses held (two or more fix the scale).
  int held = 0;
  for (int i = first; i < std::min(held_end, last + 1); ++i) held += pose_used[i];
  for (int i = std::max(first, std::min(held_from, last + 1)); i <= last; ++i) held += pose_used[i];
  if (first == 0 && !pose_used[0]) held = 0;
  // The floor points seen twice or more in the range, at one level: a parameter started at their median
  // depth, free when held poses fix the scale, else held (the scale gauge).
  bool floor_gauge = false;
  double floor_level = 0.0;
  if (options.floor_sigma > 0) {
    std::vector<double> depths;
    for (int q : p.floor_points)
      if (count[static_cast<std::size_t>(q)] >= 2)
        depths.push_back(-p.points[static_cast<std::size_t>(q)].z());
    if (depths.size() >= 10) {
      std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
      floor_level = -depths[depths.size() / 2];
    }
    if (floor_level < 0) {
      // As the tilt prior: a point one spread off the level costs as much as one observation at the loss
      // scale, under the same robust loss.
      const double weight = options.loss_scale / (options.floor_sigma * -floor_level);
      for (int q : p.floor_points)
        if (count[static_cast<std::size_t>(q)] >= 2)
          problem.AddResidualBlock(
              new ceres::AutoDiffCostFunction<FloorLevelCost, 1, 3, 1>(new FloorLevelCost(weight)), &loss,
              p.points[static_cast<std::size_t>(q)].data(), &floor_level);
      if (held < 2) {
        problem.SetParameterBlockConstant(&floor_level);
        floor_gauge = true;
      }
    }
  }
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
  // Scale gauge without floor points: the distance from the first used pose to the farthest one. (With
  // them this chord is not held: held stiffly while the floor prior rescales stretches of the path, it
  // bends the path instead. POV-Ray gallery walk, heading RMS / ATE: 0.145 deg / 0.07 % with the chord,
  // 0.018 deg / 0.007 % with the level.)
  if (held < 2 && !floor_gauge) {
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

// Each point as the least-squares intersection of the rays of the observations `use` accepts (the point
// nearest all of them: sum (I - d d^T) p = sum (I - d d^T) c); `ok` marks the points whose rays fix a
// position (not too near parallel).
template <typename Use>
std::vector<char> triangulate(const BundleProblem& p, const Use& use, std::vector<Eigen::Vector3d>* placed) {
  std::vector<Eigen::Matrix3d> a(p.points.size(), Eigen::Matrix3d::Zero());
  std::vector<Eigen::Vector3d> rhs(p.points.size(), Eigen::Vector3d::Zero());
  const bool tilted = !p.tilts.empty();
  for (const BundleObservation& o : p.observations) {
    const std::size_t q = static_cast<std::size_t>(o.point);
    if (!use(o)) continue;
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
  std::vector<char> ok(p.points.size(), 0);
  placed->assign(p.points.size(), Eigen::Vector3d::Zero());
  for (std::size_t q = 0; q < p.points.size(); ++q) {
    if (a[q].isZero()) continue;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(a[q]);
    // The smallest eigenvalue is about n sin^2 of the rays' spread: below (1 deg)^2 a ray, no position.
    if (!(eigen.eigenvalues()[0] > 3e-4 * a[q].trace() / 2.0)) continue;
    (*placed)[q] = a[q].ldlt().solve(rhs[q]);
    ok[q] = 1;
  }
  return ok;
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

// At most about `limit` observations (refine_bundle calls it only where three a point fit): each point
// keeps its first and last and evenly spaced ones between (at least three), so that every point still ties
// together the stretch of path that saw it. Sorted by pose, as refine_bundle keeps them.
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
  std::sort(out.begin(), out.end(), pose_order);
  return out;
}

// ---- The pose-graph global pass (captures too long for one bundle over their points)

// Pairs of keyframes (a < b) where the walk came back: points whose observations fall into separate runs
// of keyframes (visits, more than `gap` keyframes apart; a KLT track is seen in consecutive keyframes, so
// only loop closure and joins make such points). Consecutive visits of each point give a pair of the
// visits' middle keyframes; pairs are pooled in cells of `cell` keyframes a side and each cell seen by at
// least `min_points` points gives its mean pair.
std::vector<std::pair<int, int>> revisited_pairs(const BundleProblem& p, int gap, int cell, int min_points) {
  const std::size_t points = p.points.size();
  std::vector<int> first(points, -1), last(points, -1), previous_middle(points, -1);
  struct Pool {
    long long a = 0, b = 0;
    int count = 0;
  };
  std::map<std::pair<int, int>, Pool> pools;
  auto add = [&](int a, int b) {
    Pool& pool = pools[{a / cell, b / cell}];
    pool.a += a;
    pool.b += b;
    ++pool.count;
  };
  for (const BundleObservation& o : p.observations) {  // in pose order
    const std::size_t q = static_cast<std::size_t>(o.point);
    if (first[q] < 0) {
      first[q] = last[q] = o.pose;
    } else if (o.pose - last[q] > gap) {
      const int middle = (first[q] + last[q]) / 2;
      if (previous_middle[q] >= 0) add(previous_middle[q], middle);
      previous_middle[q] = middle;
      first[q] = last[q] = o.pose;
    } else {
      last[q] = o.pose;
    }
  }
  for (std::size_t q = 0; q < points; ++q)
    if (previous_middle[q] >= 0) add(previous_middle[q], (first[q] + last[q]) / 2);
  std::vector<std::pair<int, int>> pairs;
  for (const auto& [key, pool] : pools)
    if (pool.count >= min_points)
      pairs.emplace_back(static_cast<int>(pool.a / pool.count), static_cast<int>(pool.b / pool.count));
  return pairs;
}

// The relative pose of keyframe b seen from keyframe a where the walk came back, by a local bundle: the
// keyframes within `half` of a held where they are, those around b free, every point either side sees.
// B's side is first moved onto A's by the similarity that best maps B's own triangulation of their shared
// points onto A's (so that the bundle starts inside its basin whatever the drift in between). False when
// the two sides do not agree well enough. `remap`: one entry per point of `p`, all -1 (left so).
bool measure_revisit(const BundleProblem& p, const RefinementOptions& options, int a, int b, int half,
                     std::vector<int>& remap, PoseGraphEdge* edge) {
  const int n = static_cast<int>(p.poses.size());
  const int a0 = std::max(0, a - half), a1 = std::min(n - 1, a + half);
  const int b0 = std::max(0, b - half), b1 = std::min(n - 1, b + half);
  if (b0 <= a1) return false;
  const int na = a1 - a0 + 1;
  BundleProblem sub;
  const bool tilted = !p.tilts.empty();
  for (int i : {a0, b0})
    for (int k = i; k <= (i == a0 ? a1 : b1); ++k) {
      sub.poses.push_back(p.poses[static_cast<std::size_t>(k)]);
      if (tilted) sub.tilts.push_back(p.tilts[static_cast<std::size_t>(k)]);
    }
  std::vector<int> touched;
  std::vector<unsigned char> side;  // per sub point: 1 seen from A, 2 from B
  for (int s = 0; s < 2; ++s) {
    const auto [begin, end] =
        s == 0 ? pose_range(p.observations, a0, a1) : pose_range(p.observations, b0, b1);
    for (auto it = begin; it != end; ++it) {
      const std::size_t q = static_cast<std::size_t>(it->point);
      if (remap[q] < 0) {
        remap[q] = static_cast<int>(sub.points.size());
        sub.points.push_back(p.points[q]);
        side.push_back(0);
        touched.push_back(static_cast<int>(q));
      }
      side[static_cast<std::size_t>(remap[q])] |= s == 0 ? 1 : 2;
      BundleObservation o = *it;
      o.pose = s == 0 ? it->pose - a0 : na + it->pose - b0;
      o.point = remap[q];
      sub.observations.push_back(o);
    }
  }
  for (int q : touched) remap[static_cast<std::size_t>(q)] = -1;
  // Each shared point triangulated from either side alone.
  auto from_side = [&](bool want_a) {
    return [&, want_a](const BundleObservation& o) {
      return side[static_cast<std::size_t>(o.point)] == 3 && (o.pose < na) == want_a;
    };
  };
  std::vector<Eigen::Vector3d> at_a, at_b;
  const std::vector<char> ok_a = triangulate(sub, from_side(true), &at_a);
  const std::vector<char> ok_b = triangulate(sub, from_side(false), &at_b);
  std::vector<int> shared;
  for (std::size_t q = 0; q < sub.points.size(); ++q)
    if (ok_a[q] && ok_b[q]) shared.push_back(static_cast<int>(q));
  constexpr int kMinShared = 12;
  if (static_cast<int>(shared.size()) < kMinShared) return false;
  // B's triangulation onto A's in the plane (scale included), twice: the second time without the points
  // farther off than three times the median (a far point's depth is uncertain along its ray).
  Similarity2 similarity;
  std::vector<int> used = shared;
  for (int round = 0; round < 2; ++round) {
    std::vector<Eigen::Vector2d> from, to;
    for (int q : used) {
      from.push_back(at_b[static_cast<std::size_t>(q)].head<2>());
      to.push_back(at_a[static_cast<std::size_t>(q)].head<2>());
    }
    similarity = align_similarity(from, to);
    if (round == 1) break;
    std::vector<double> off(used.size());
    for (std::size_t k = 0; k < used.size(); ++k) off[k] = (similarity.apply(from[k]) - to[k]).norm();
    std::vector<double> sorted = off;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double limit = 3.0 * sorted[sorted.size() / 2];
    std::vector<int> kept;
    for (std::size_t k = 0; k < used.size(); ++k)
      if (off[k] <= limit) kept.push_back(used[k]);
    if (static_cast<int>(kept.size()) < kMinShared) return false;
    used = std::move(kept);
  }
  const double scale = similarity.scale, turn = similarity.rotation;
  if (!(scale > 0.5 && scale < 2.0)) return false;
  auto move = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector2d xy = similarity.apply(x.head<2>());
    return Eigen::Vector3d(xy.x(), xy.y(), scale * x.z());
  };
  for (int i = na; i < static_cast<int>(sub.poses.size()); ++i) {
    Eigen::Vector3d& pose = sub.poses[static_cast<std::size_t>(i)];
    const Eigen::Vector3d moved = move(Eigen::Vector3d(pose.x(), pose.y(), 0.0));
    pose = Eigen::Vector3d(moved.x(), moved.y(), pose.z() + turn);
  }
  for (std::size_t q = 0; q < sub.points.size(); ++q) {
    if (side[q] == 2) sub.points[q] = move(sub.points[q]);
    if (side[q] == 3) sub.points[q] = ok_a[q] ? at_a[q] : move(sub.points[q]);
  }
  RefinementReport ignored;
  solve_range(sub, options, 0, static_cast<int>(sub.poses.size()) - 1, na, options.window_max_iterations,
              null_progress(), 0.0, 1.0, &ignored);
  // Agreement: the shared points' observations from B must fit A's map about as well as a window fits.
  const std::vector<double> errors = observation_errors(sub);
  std::vector<double> shared_errors;
  for (std::size_t k = 0; k < errors.size(); ++k)
    if (side[static_cast<std::size_t>(sub.observations[k].point)] == 3 && sub.observations[k].pose >= na)
      shared_errors.push_back(errors[k]);
  std::nth_element(shared_errors.begin(), shared_errors.begin() + shared_errors.size() / 2,
                   shared_errors.end());
  if (shared_errors.empty() || !(shared_errors[shared_errors.size() / 2] < 2.0 * options.loss_scale))
    return false;
  // B's scale against A's: its steps after the bundle over before (B's own, as the windows left it).
  double before = 0.0, after = 0.0;
  for (int i = b0 + 1; i <= b1; ++i) {
    before +=
        (p.poses[static_cast<std::size_t>(i)].head<2>() - p.poses[static_cast<std::size_t>(i - 1)].head<2>())
            .norm();
    after += (sub.poses[static_cast<std::size_t>(na + i - b0)].head<2>() -
              sub.poses[static_cast<std::size_t>(na + i - b0 - 1)].head<2>())
                 .norm();
  }
  const Eigen::Vector3d& pa = sub.poses[static_cast<std::size_t>(a - a0)];
  const Eigen::Vector3d& pb = sub.poses[static_cast<std::size_t>(na + b - b0)];
  const double c = std::cos(pa.z()), s = std::sin(pa.z());
  const Eigen::Vector2d d = pb.head<2>() - pa.head<2>();
  edge->from = a;
  edge->to = b;
  edge->translation = Eigen::Vector2d(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
  edge->turn = pb.z() - pa.z();
  // A camera that stood still there says nothing of the scale.
  const bool moved = before > 1e-9 && after > 1e-9;
  edge->log_scale = moved ? std::log(after / before) : 0.0;
  edge->log_scale_sigma = moved ? 1.0 : 1e3;
  return true;
}

// The global pass of a long capture on its keyframes alone: consecutive keyframes tied by their windowed
// solution, revisited places by measure_revisit, the pose graph solved, and the points carried with the
// first keyframe that saw them. Returns the number of revisits used. Throws Cancelled.
int pose_graph_pass(BundleProblem& p, const RefinementOptions& options,
                    const std::vector<int>& first_pose_of_point, Progress& progress, double begin,
                    double end) {
  const int n = static_cast<int>(p.poses.size());
  std::vector<double> steps;
  for (int i = 1; i < n; ++i)
    steps.push_back(
        (p.poses[static_cast<std::size_t>(i)].head<2>() - p.poses[static_cast<std::size_t>(i - 1)].head<2>())
            .norm());
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  const double step = std::max(1e-9, steps[steps.size() / 2]);
  // Standard deviations. A chain edge's error is small, but its errors add up along the walk (that is the
  // drift); a revisit's is larger, but it is one measurement however far apart the two visits are.
  constexpr double kChainTranslation = 0.005, kChainTurn = 2e-4, kChainScale = 0.002;
  constexpr double kRevisitTranslation = 0.02, kRevisitTurn = 1e-3, kRevisitScale = 0.01;
  std::vector<PoseGraphEdge> edges;
  for (int i = 0; i + 1 < n; ++i) {
    const Eigen::Vector3d &a = p.poses[static_cast<std::size_t>(i)],
                          &b = p.poses[static_cast<std::size_t>(i + 1)];
    PoseGraphEdge e;
    e.from = i;
    e.to = i + 1;
    const double c = std::cos(a.z()), s = std::sin(a.z());
    const Eigen::Vector2d d = b.head<2>() - a.head<2>();
    e.translation = Eigen::Vector2d(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
    e.turn = b.z() - a.z();
    e.translation_sigma = kChainTranslation * step;
    e.turn_sigma = kChainTurn;
    e.log_scale_sigma = kChainScale;
    edges.push_back(e);
  }
  constexpr int kHalf = 6;  // keyframes either side of a revisit's centre in its local bundle
  const std::vector<std::pair<int, int>> pairs = revisited_pairs(p, 3 * kHalf, 2 * kHalf + 1, 20);
  std::vector<int> remap(p.points.size(), -1);
  int revisits = 0;
  const double measured = begin + 0.8 * (end - begin);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    progress.checkpoint(begin + (measured - begin) * k / pairs.size());
    PoseGraphEdge e;
    if (!measure_revisit(p, options, pairs[k].first, pairs[k].second, kHalf, remap, &e)) continue;
    e.translation_sigma = kRevisitTranslation * step;
    e.turn_sigma = kRevisitTurn;
    e.log_scale_sigma *= kRevisitScale;
    e.robust = true;
    edges.push_back(e);
    ++revisits;
  }
  if (revisits == 0) return 0;
  std::vector<PoseGraphNode> nodes(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) nodes[static_cast<std::size_t>(i)].pose = p.poses[static_cast<std::size_t>(i)];
  SubProgress graph_progress(progress, measured, end);
  solve_pose_graph(nodes, edges, 100, graph_progress);
  for (std::size_t q = 0; q < p.points.size(); ++q) {
    const int k = first_pose_of_point[q];
    if (k >= n) continue;
    const Eigen::Vector3d &before = p.poses[static_cast<std::size_t>(k)],
                          &after = nodes[static_cast<std::size_t>(k)].pose;
    const double scale = std::exp(nodes[static_cast<std::size_t>(k)].log_scale),
                 turn = after.z() - before.z();
    const double c = std::cos(turn), s = std::sin(turn);
    Eigen::Vector3d& point = p.points[q];
    const double dx = point.x() - before.x(), dy = point.y() - before.y();
    point = Eigen::Vector3d(after.x() + scale * (c * dx - s * dy), after.y() + scale * (s * dx + c * dy),
                            scale * point.z());
  }
  for (int i = 0; i < n; ++i) p.poses[static_cast<std::size_t>(i)] = nodes[static_cast<std::size_t>(i)].pose;
  return revisits;
}

// The floor points' spread about their common level (1.4826 x the median absolute deviation of their
// heights), a share of the level's depth; 0 with fewer than 10 floor points below the camera.
double floor_level_spread(const BundleProblem& p) {
  std::vector<double> z;
  for (int q : p.floor_points)
    if (p.points[static_cast<std::size_t>(q)].z() < 0) z.push_back(p.points[static_cast<std::size_t>(q)].z());
  if (z.size() < 10) return 0.0;
  const double level = median(z);
  return 1.4826 * median_absolute_deviation(z, level) / -level;
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
  require_option(tilt_prior_from_data >= 0, s + "tilt_prior_from_data", "must be >= 0 (0 = off)",
                 tilt_prior_from_data);
  require_option(tilt_prior_min_deg > 0, s + "tilt_prior_min_deg", "must be > 0", tilt_prior_min_deg);
  require_option(floor_sigma >= 0, s + "floor_sigma", "must be >= 0 (0 = off)", floor_sigma);
  require_option(floor_sigma_from_data >= 0, s + "floor_sigma_from_data", "must be >= 0 (0 = off)",
                 floor_sigma_from_data);
  require_option(floor_sigma_min > 0, s + "floor_sigma_min", "must be > 0", floor_sigma_min);
  require_option(global_max_observations >= 0, s + "global_max_observations", "must be >= 0 (0 = no limit)",
                 global_max_observations);
}

double observation_error(const BundleProblem& p, const BundleObservation& o) {
  const Eigen::Vector3d& q = p.points[o.point];
  const Eigen::Vector3d& c = p.poses[o.pose];
  if (!p.tilts.empty()) return tilted_ray_error(c, p.tilts[o.pose], q, o.bearing());
  const double ch = std::cos(c.z()), sh = std::sin(c.z());
  const Eigen::Vector3d d(ch * (q.x() - c.x()) + sh * (q.y() - c.y()),
                          -sh * (q.x() - c.x()) + ch * (q.y() - c.y()), q.z());
  const Eigen::Vector3d b = o.bearing();
  const double angle = std::atan2(d.cross(b).norm(), d.dot(b));
  return std::isfinite(angle) ? angle : M_PI;
}

std::vector<double> observation_errors(const BundleProblem& p) {
  std::vector<double> e;
  e.reserve(p.observations.size());
  for (const BundleObservation& o : p.observations) e.push_back(observation_error(p, o));
  return e;
}

RefinementReport refine_bundle(BundleProblem& problem, const RefinementOptions& options, Progress& progress) {
  options.check();
  quiet_ceres_logging();
  RefinementReport report;
  if (options.tilt_prior_deg > 0 && problem.tilts.size() != problem.poses.size())
    problem.tilts.assign(problem.poses.size(), Eigen::Vector2d::Zero());
  if (options.tilt_prior_deg == 0) problem.tilts.clear();
  std::sort(problem.observations.begin(), problem.observations.end(), pose_order);
  report.initial_rms = error_rms(problem);
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
  // The global passes' options: the second takes its tilt prior from what the first found.
  RefinementOptions pass = options;
  bool thinned_any = false;
  // A thinned global pass fixed the path's shape; windows against every observation, each holding its first
  // and last poses (so the shape stays), restore the detail the thinning left out.
  auto restore_detail = [&](double begin, double end) {
    const int size = options.window_keyframes > 0 ? options.window_keyframes : 80;
    const int overlap = std::min(options.window_overlap, size / 4);
    for (int first = 0; first + overlap < n; first += size - 2 * overlap) {
      const int last = std::min(n - 1, first + size - 1);
      const int held_from = last == n - 1 ? n : last - overlap + 1;
      const double at = begin + (end - begin) * first / n;
      solve_range(problem, pass, first, last, first == 0 ? 1 : first + overlap, options.window_max_iterations,
                  progress, at, at, &report, held_from);
      if (last == n - 1) break;
    }
  };
  // Too many points for even three observations each in one bundle (about 10 000 frames and more): the
  // drift between revisits is taken out by a pose graph on the keyframes (pose_graph_pass), then the detail
  // is restored. (A bundle over a subset of the points, started where the windows left the poses, cannot
  // undo the drift: ATE 0.047 % on 30 000 frames.) bench_track, 10 000 frames with the limit at 60 000 (the
  // ratio of 100 000 frames at the default): keyframe ATE 0.033 % after the windows, 0.0127 % after the
  // graph, peak 313 MB; one bundle over every observation: 0.0011 %, 0.95 GB. A subset bundle after the
  // graph reached 0.0066 % there but made a short synthetic walk worse (0.0084 m against 0.0038 m): not
  // kept until that is understood.
  std::size_t points_seen = 0;
  for (int k : first_pose_of_point) points_seen += k < n;
  const bool graph = limit > 0 && 3 * points_seen > limit;
  auto solve_global = [&](int max_iterations, double begin, double end, bool first_time) {
    if (graph) {
      const double middle = begin + 0.5 * (end - begin);
      if (first_time)
        report.revisits = pose_graph_pass(problem, pass, first_pose_of_point, progress, begin, middle);
      restore_detail(first_time ? middle : begin, end);
      return;
    }
    if (limit == 0 || problem.observations.size() <= limit) {
      solve_range(problem, pass, 0, n - 1, 1, max_iterations, progress, begin, end, &report);
      return;
    }
    thinned_any = true;
    std::vector<BundleObservation> all = thinned(problem.observations, limit);
    std::swap(all, problem.observations);
    solve_range(problem, pass, 0, n - 1, 1, max_iterations, progress, begin, end, &report);
    std::swap(all, problem.observations);
  };
  // The floor prior's spread from the floor points, measured once under the widest spread (a narrower
  // prior pulls the points together, and measuring again would narrow it on its own evidence): before the
  // first global pass when the points (refined by the windows) already show a narrower one; else after it,
  // and then one more global pass runs at the end, as the first was made under a prior too wide.
  const bool floor_from_data = options.global_max_iterations > 0 && options.floor_sigma > 0 &&
                               options.floor_sigma_from_data > 0 && !problem.floor_points.empty();
  auto floor_sigma_from_points = [&] {
    const double spread = floor_level_spread(problem);
    if (spread <= 0) return options.floor_sigma;
    return std::clamp(options.floor_sigma_from_data * spread,
                      std::min(options.floor_sigma_min, options.floor_sigma), options.floor_sigma);
  };
  if (floor_from_data) pass.floor_sigma = floor_sigma_from_points();
  const bool floor_measured = pass.floor_sigma < options.floor_sigma;
  if (options.global_max_iterations > 0) {
    const double split = options.outlier_threshold > 0 ? windowed_share + 0.7 * (1 - windowed_share) : 1.0;
    solve_global(options.global_max_iterations, windowed_share, split, true);
    auto tilt_prior_from_tilts = [&] {
      double sum = 0;
      for (const Eigen::Vector2d& t : problem.tilts) sum += t.squaredNorm();
      const double rms_deg = std::sqrt(sum / problem.tilts.size()) * 180.0 / M_PI;
      return std::clamp(options.tilt_prior_from_data * rms_deg,
                        std::min(options.tilt_prior_min_deg, options.tilt_prior_deg), options.tilt_prior_deg);
    };
    const bool tilts_from_data = !problem.tilts.empty() && options.tilt_prior_from_data > 0;
    if (tilts_from_data) pass.tilt_prior_deg = tilt_prior_from_tilts();
    if (floor_from_data && !floor_measured) pass.floor_sigma = floor_sigma_from_points();
    bool refit = pass.floor_sigma < 0.7 * options.floor_sigma && !floor_measured;
    if (options.outlier_threshold > 0) {
      // Single precision: 4 bytes for each of tens of millions of observations.
      std::vector<float> errors;
      errors.reserve(problem.observations.size());
      for (const BundleObservation& o : problem.observations)
        errors.push_back(static_cast<float>(observation_error(problem, o)));
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
      solve_global(std::max(1, options.global_max_iterations / 2), split, 1.0, false);
    }
    // The tilts the first pass found under the wide prior are partly noise; under the narrower prior they
    // shrink. Where they shrink much (a level camera), once more with the prior they now show.
    if (tilts_from_data && options.tilt_prior_refit && options.outlier_threshold > 0) {
      const double narrower = tilt_prior_from_tilts();
      if (narrower < 0.7 * pass.tilt_prior_deg) {
        pass.tilt_prior_deg = narrower;
        refit = true;
      }
    }
    if (refit) solve_global(std::max(1, options.global_max_iterations / 2), 1.0, 1.0, false);
    if (thinned_any) restore_detail(1.0, 1.0);
  }
  report.tilt_prior_used_deg = problem.tilts.empty() ? 0.0 : pass.tilt_prior_deg;
  report.floor_sigma_used = problem.floor_points.empty() ? 0.0 : pass.floor_sigma;
  report.final_rms = error_rms(problem);
  return report;
}

}  // namespace plenopath
