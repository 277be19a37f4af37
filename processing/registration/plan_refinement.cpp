#include "processing/registration/plan_refinement.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <unordered_map>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/anchors/pose_graph_costs.h"
#include "processing/registration/registration_internal.h"

namespace plenopath {

using namespace registration_detail;

void PlanRefinementOptions::check() const {
  registration.check();
  const std::string s = "PlanRefinementOptions.";
  require_option(association_start_m > 0, s + "association_start_m", "must be > 0", association_start_m);
  require_option(association_end_m > 0 && association_end_m <= association_start_m, s + "association_end_m",
                 "must be in (0, association_start_m]", association_end_m);
  require_option(stiff_rounds >= 1 && stiff_rounds <= 10, s + "stiff_rounds", "must be in [1, 10]",
                 stiff_rounds);
  require_option(flexible_rounds >= 0 && flexible_rounds <= 10, s + "flexible_rounds", "must be in [0, 10]",
                 flexible_rounds);
  require_option(wall_sigma_m > 0, s + "wall_sigma_m", "must be > 0", wall_sigma_m);
  require_option(wall_loss_m > 0, s + "wall_loss_m", "must be > 0", wall_loss_m);
  require_option(loss_fraction >= 0, s + "loss_fraction", "must be >= 0", loss_fraction);
  require_option(max_wall_points >= 10, s + "max_wall_points", "must be >= 10", max_wall_points);
  require_option(step_sigma_fraction > 0, s + "step_sigma_fraction", "must be > 0", step_sigma_fraction);
  require_option(step_sigma_min_m > 0, s + "step_sigma_min_m", "must be > 0", step_sigma_min_m);
  require_option(turn_sigma_rad > 0, s + "turn_sigma_rad", "must be > 0", turn_sigma_rad);
  require_option(drift_scale_sigma > 0, s + "drift_scale_sigma", "must be > 0", drift_scale_sigma);
  require_option(drift_bias_sigma_rad > 0, s + "drift_bias_sigma_rad", "must be > 0", drift_bias_sigma_rad);
  require_option(start_sigma_m > 0, s + "start_sigma_m", "must be > 0", start_sigma_m);
  require_option(start_heading_sigma_rad > 0, s + "start_heading_sigma_rad", "must be > 0",
                 start_heading_sigma_rad);
  require_option(max_iterations >= 1, s + "max_iterations", "must be >= 1", max_iterations);
  require_option(min_wall_share >= 0 && min_wall_share <= 1, s + "min_wall_share", "must be in [0, 1]",
                 min_wall_share);
  require_option(max_free_share_loss >= 0 && max_free_share_loss <= 1, s + "max_free_share_loss",
                 "must be in [0, 1]", max_free_share_loss);
}

// The wall a point is clearly on: the first wall the ray from the camera that saw it meets on its way to the
// point (projective association: what the camera saw there), when the point lies within `within` of it.
bool registration_detail::wall_of(const Eigen::Vector2d& q, const Eigen::Vector2d& camera,
                                  const SegmentGrid& grid, double within, Eigen::Vector2d* on_wall,
                                  Eigen::Vector2d* normal) {
  const Eigen::Vector2d ray = q - camera;
  const double length = ray.norm();
  if (length < 0.05) return false;
  const Eigen::Vector2d end = camera + ray * ((length + within) / length);
  double first = 2.0;
  int hit = -1;
  for (int i : grid.along(camera, end)) {
    const Segment2& seg = grid.segments()[static_cast<std::size_t>(i)];
    double t = 0, u = 0;
    if (intersect_segments(camera, end, seg.a, seg.b, &t, &u) && t < first) {
      first = t;
      hit = i;
    }
  }
  if (hit < 0) return false;
  const Segment2& seg = grid.segments()[static_cast<std::size_t>(hit)];
  const Eigen::Vector2d ab = seg.b - seg.a;
  if (ab.squaredNorm() < 1e-8) return false;
  *normal = Eigen::Vector2d(-ab.y(), ab.x()).normalized();
  *on_wall = camera + first * (end - camera);
  return std::abs(normal->dot(q - *on_wall)) <= within;
}

bool PlanRefinementReport::any_kept() const {
  for (const PieceRefinement& p : pieces)
    if (p.kept) return true;
  return false;
}

namespace {

// The point of `tie` where the poses and the drift scale put it.
Eigen::Vector2d placed(const DriftTie& tie, const std::vector<std::array<double, 3>>& poses, double scale) {
  const std::array<double, 3>& p = poses[tie.pose];
  return Eigen::Vector2d(p[0], p[1]) + scale * rotate(tie.local, p[2]);
}

// Signed distance of the point to the line of a wall, robust-weighted by Ceres.
struct WallResidual {
  WallResidual(const Eigen::Vector2d& local, const Eigen::Vector2d& on_wall, const Eigen::Vector2d& normal,
               double sigma)
      : local_(local), on_wall_(on_wall), normal_(normal), sigma_(sigma) {}
  template <typename T>
  bool operator()(const T* pose, const T* drift, T* residual) const {
    const T c = ceres::cos(pose[2]), s = ceres::sin(pose[2]);
    const T x = pose[0] + drift[0] * (c * T(local_.x()) - s * T(local_.y()));
    const T y = pose[1] + drift[0] * (s * T(local_.x()) + c * T(local_.y()));
    residual[0] =
        (T(normal_.x()) * (x - T(on_wall_.x())) + T(normal_.y()) * (y - T(on_wall_.y()))) / T(sigma_);
    return true;
  }
  static ceres::CostFunction* Create(const Eigen::Vector2d& local, const Eigen::Vector2d& on_wall,
                                     const Eigen::Vector2d& normal, double sigma) {
    return new ceres::AutoDiffCostFunction<WallResidual, 1, 3, 2>(
        new WallResidual(local, on_wall, normal, sigma));
  }

 private:
  Eigen::Vector2d local_, on_wall_, normal_;
  double sigma_;
};

struct Fit {
  double wall_share = 0.0, rms_m = 0.0, free_share = 0.0;
};

// `measured`: the frames whose pose the images gave (bridged frames, held or interpolated, do not count
// for free space: frames held at the last pose inside a wall the camera passed through once cost the right
// placement of the gap walk's first room).
Fit fit_of(const std::vector<DriftTie>& ties, const std::vector<std::array<double, 3>>& poses, double scale,
           const std::vector<char>& measured, const PlanRaster& plan, const SegmentGrid& grid,
           double tolerance) {
  Fit fit;
  int inliers = 0;
  double sum2 = 0;
  for (const DriftTie& t : ties) {
    const double d = grid.distance_within(placed(t, poses, scale), 2 * tolerance);
    if (d > tolerance) continue;
    ++inliers;
    sum2 += d * d;
  }
  fit.wall_share = ties.empty() ? 0.0 : double(inliers) / ties.size();
  fit.rms_m = inliers ? std::sqrt(sum2 / inliers) : 0.0;
  int free = 0, counted = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!measured[i]) continue;
    ++counted;
    free += plan.is_free({poses[i][0], poses[i][1]}) ? 1 : 0;
  }
  fit.free_share = counted ? double(free) / counted : 0.0;
  return fit;
}

// Refines one placed piece; `out_poses` and `out_scale` get the result (kept or not: the caller decides
// by report.kept).
void refine_piece(const CameraPath& piece, const std::vector<DriftTie>& ties, const PlanRaster& plan,
                  const SegmentGrid& grid, const PlanRefinementOptions& options, PieceRefinement* report,
                  std::vector<std::array<double, 3>>* out_poses, double* out_scale, Progress& progress) {
  const std::size_t n = piece.frames.size();
  std::vector<std::array<double, 3>> start(n);
  std::vector<char> measured(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    start[i] = {piece.frames[i].x, piece.frames[i].y, piece.frames[i].heading};
    measured[i] = (piece.frames[i].flags & kFrameBridged) ? 0 : 1;
  }
  if (std::count(measured.begin(), measured.end(), 1) == 0) measured.assign(n, 1);
  const double tolerance = options.registration.inlier_tolerance_m;
  const Fit before = fit_of(ties, start, 1.0, measured, plan, grid, tolerance);
  report->wall_share_before = before.wall_share;
  report->rms_before_m = before.rms_m;
  report->free_share_before = before.free_share;

  // The subsample that enters the solver (the fit above and below sees every tie).
  std::vector<DriftTie> used;
  const std::size_t stride =
      std::max<std::size_t>(1, (ties.size() + options.max_wall_points - 1) / options.max_wall_points);
  for (std::size_t i = 0; i < ties.size(); i += stride) used.push_back(ties[i]);

  // Stiff rounds: the drift model and the placement only (drift_fit.cpp).
  std::vector<Eigen::Vector3d> start3(n);
  for (std::size_t i = 0; i < n; ++i) start3[i] = {start[i][0], start[i][1], start[i][2]};
  DriftFitOptions fit;
  fit.within_m.clear();
  for (int round = 0; round < options.stiff_rounds; ++round) {
    const double t = options.stiff_rounds == 1 ? 1.0 : double(round) / (options.stiff_rounds - 1);
    fit.within_m.push_back(options.association_start_m *
                           std::pow(options.association_end_m / options.association_start_m, t));
  }
  fit.loss_fraction = options.loss_fraction;
  fit.min_loss_m = options.wall_loss_m;
  fit.wall_sigma_m = options.wall_sigma_m;
  fit.shift_sigma_m = options.start_sigma_m;
  fit.turn_sigma_rad = options.start_heading_sigma_rad;
  fit.scale_sigma = options.drift_scale_sigma;
  fit.bias_sigma_rad = options.drift_bias_sigma_rad;
  const double stiff_share = double(options.stiff_rounds) / (options.stiff_rounds + options.flexible_rounds);
  SubProgress stiff_progress(progress, 0.0, stiff_share, "drift model");
  const DriftModel model = fit_drift_model(start3, used, grid, fit, stiff_progress);
  const std::vector<Eigen::Vector3d> modelled = apply_drift_model(start3, model);
  std::vector<std::array<double, 3>> poses(n);
  for (std::size_t i = 0; i < n; ++i) poses[i] = {modelled[i].x(), modelled[i].y(), modelled[i].z()};
  std::array<double, 2> drift = {model.scale, model.bias};

  // Flexible rounds: every step may bend by its own sigmas (a pose graph, Ceres), ties at the end distance.
  for (int round = 0; round < options.flexible_rounds; ++round) {
    const double within = options.association_end_m;
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    const double loss_m = std::max(options.wall_loss_m, options.loss_fraction * within);
    ceres::CauchyLoss wall_loss(loss_m / options.wall_sigma_m);
    problem.AddParameterBlock(drift.data(), 2);
    problem.AddResidualBlock(
        pose_graph::DriftPrior::Create(options.drift_scale_sigma, options.drift_bias_sigma_rad), nullptr,
        drift.data());
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const Eigen::Vector2d d(start[i + 1][0] - start[i][0], start[i + 1][1] - start[i][1]);
      const Eigen::Vector2d local = rotate(d, -start[i][2]);
      const double sigma_t = std::max(options.step_sigma_min_m, options.step_sigma_fraction * d.norm());
      problem.AddResidualBlock(
          pose_graph::StepResidual::Create(local, std::remainder(start[i + 1][2] - start[i][2], 2 * M_PI),
                                           sigma_t, options.turn_sigma_rad),
          nullptr, poses[i].data(), poses[i + 1].data(), drift.data());
    }
    problem.AddResidualBlock(
        pose_graph::AnchorPrior::Create({start[0][0], start[0][1]}, options.start_sigma_m), nullptr,
        poses[0].data());
    problem.AddResidualBlock(pose_graph::HeadingPrior::Create(start[0][2], options.start_heading_sigma_rad),
                             nullptr, poses[0].data());
    int tied = 0;
    for (const DriftTie& tie : used) {
      Eigen::Vector2d on_wall, normal;
      const std::array<double, 3>& camera = poses[tie.pose];
      if (!wall_of(placed(tie, poses, drift[0]), {camera[0], camera[1]}, grid, within, &on_wall, &normal))
        continue;
      problem.AddResidualBlock(WallResidual::Create(tie.local, on_wall, normal, options.wall_sigma_m),
                               &wall_loss, poses[tie.pose].data(), drift.data());
      ++tied;
    }
    report->wall_points = tied;
    if (tied < options.registration.min_wall_points) {
      std::ostringstream m;
      m << "too few wall points clearly on a wall to refine: " << tied << " within " << within
        << " m (at least " << options.registration.min_wall_points << " needed)";
      report->message = m.str();
      *out_poses = start;
      *out_scale = 1.0;
      return;
    }
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    solver.max_num_iterations = options.max_iterations;
    solver.num_threads = 1;  // repeatable to the last bit (see anchor_refinement.cpp)
    solver.logging_type = ceres::SILENT;
    const double share = (1 - stiff_share) / options.flexible_rounds;
    SubProgress round_progress(progress, stiff_share + round * share, stiff_share + (round + 1) * share,
                               "round " + std::to_string(round + 1));
    pose_graph::ProgressCallback callback(round_progress, options.max_iterations);
    solver.callbacks.push_back(&callback);
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    progress.throw_if_cancelled();
    report->iterations += static_cast<int>(summary.iterations.size());
  }
  report->refined = true;
  const Fit after = fit_of(ties, poses, drift[0], measured, plan, grid, tolerance);
  report->wall_share_after = after.wall_share;
  report->rms_after_m = after.rms_m;
  report->free_share_after = after.free_share;
  report->drift_scale = drift[0];
  report->drift_bias_deg_per_100_frames = degrees(drift[1]) * 100.0;
  for (std::size_t i = 0; i < n; ++i)
    report->max_shift_m =
        std::max(report->max_shift_m, std::hypot(poses[i][0] - start[i][0], poses[i][1] - start[i][1]));
  // Safeguard: the walls must fit at least as well (as many wall points on walls, within half a percent: a
  // good registration stays; and no farther from them), and the frames stay out of walls and pillars.
  std::ostringstream why;
  if (after.wall_share + 0.005 < before.wall_share)
    why << "the refined path fits the walls worse (" << std::lround(100 * after.wall_share)
        << " % of wall points on walls, " << std::lround(100 * before.wall_share)
        << " % before): kept as registered";
  else if (after.rms_m > before.rms_m)
    // It found no drift to take out: what it moved, it moved by the walls' noise. (POV-Ray gallery, tracked
    // to 0.007 %: refined 0.044 m and 0.23 deg off the truth, as registered 0.024 m and 0.12 deg.)
    why << std::setprecision(3) << "the refined path brings the wall points no closer to their walls (RMS "
        << after.rms_m << " m, " << before.rms_m << " m before): kept as registered";
  else if (after.wall_share < options.min_wall_share)
    why << "the path does not fit the walls (" << std::lround(100 * after.wall_share)
        << " % of wall points on walls after refinement, at least "
        << std::lround(100 * options.min_wall_share) << " % needed): kept as registered";
  else if (after.free_share + options.max_free_share_loss < before.free_share)
    why << "the refined path leaves free space (" << std::lround(100 * after.free_share)
        << " % of frames in free space, " << std::lround(100 * before.free_share)
        << " % before): kept as registered";
  report->message = why.str();
  report->kept = report->message.empty();
  *out_poses = report->kept ? poses : start;
  *out_scale = report->kept ? drift[0] : 1.0;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

CameraPath refine_on_plan(const CameraPath& path, std::vector<PathPoint>* points, const FloorPlan& plan,
                          const PlanRefinementOptions& options, PlanRefinementReport* report,
                          Progress& progress) {
  options.check();
  const auto t0 = std::chrono::steady_clock::now();
  if (path.empty()) throw Error("plan refinement: the path has no frames");
  const int piece_count = path.piece_count();
  static const std::vector<PathPoint> no_points;
  const std::vector<PathPoint>& all = points ? *points : no_points;
  for (const PathPoint& p : all)
    if (p.piece < 0 || p.piece >= piece_count)
      throw Error("plan refinement: a point names piece " + std::to_string(p.piece) + " but the path has " +
                  std::to_string(piece_count) + " piece(s)");
  const PlanRaster raster = build_plan_raster(plan, options.registration.cell_m, 2.0);
  const SegmentGrid grid(raster.walls);

  // Frame position (in the whole path) of each capture index.
  std::unordered_map<int, std::size_t> position_of;
  for (std::size_t i = 0; i < path.frames.size(); ++i) position_of[path.frames[i].index] = i;

  CameraPath out = path;
  std::vector<PathPoint> moved = all;
  PlanRefinementReport local;
  PlanRefinementReport& r = report ? *report : local;
  r = {};
  for (int k = 0; k < piece_count; ++k) {
    PieceRefinement pr;
    pr.piece = k;
    const bool placed_piece = path.pieces.empty() || path.pieces[static_cast<std::size_t>(k)].placed;
    if (!placed_piece) {
      pr.message = "not placed on the plan";
      r.pieces.push_back(pr);
      continue;
    }
    // The piece's frames, in path order, and where each sits in the whole path.
    std::vector<std::size_t> frame_at;
    CameraPath piece;
    for (std::size_t i = 0; i < path.frames.size(); ++i)
      if (path.frames[i].piece == k || piece_count == 1) {
        frame_at.push_back(i);
        piece.frames.push_back(path.frames[i]);
      }
    std::unordered_map<std::size_t, std::size_t> pose_of;  // whole-path position -> piece pose
    for (std::size_t j = 0; j < frame_at.size(); ++j) pose_of[frame_at[j]] = j;

    std::vector<const PathPoint*> own;
    for (const PathPoint& p : all)
      if (p.piece == k) own.push_back(&p);
    const double ceiling = estimate_ceiling(own, options.registration);
    std::vector<DriftTie> ties;
    int without_frame = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const PathPoint& p = all[i];
      if (p.piece != k || !in_wall_band(p, options.registration, ceiling)) continue;
      auto at = p.frame >= 0 ? position_of.find(p.frame) : position_of.end();
      if (at == position_of.end() || !pose_of.count(at->second)) {
        ++without_frame;
        continue;
      }
      const PathFrame& f = path.frames[at->second];
      DriftTie t;
      t.point = i;
      t.pose = pose_of[at->second];
      t.local = rotate(p.position.head<2>() - f.position(), -f.heading);
      ties.push_back(t);
    }
    if (static_cast<int>(ties.size()) < options.registration.min_wall_points) {
      std::ostringstream m;
      m << "too few wall points tied to frames to refine: " << ties.size();
      if (without_frame)
        m << " (" << without_frame << " name no frame of the piece: points from an older version?)";
      pr.message = m.str();
      r.pieces.push_back(pr);
      continue;
    }
    SubProgress sub(progress, double(k) / piece_count, double(k + 1) / piece_count,
                    piece_count == 1 ? std::string() : "piece " + std::to_string(k + 1));
    std::vector<std::array<double, 3>> poses;
    double scale = 1.0;
    refine_piece(piece, ties, raster, grid, options, &pr, &poses, &scale, sub);
    if (pr.kept) {
      for (std::size_t j = 0; j < frame_at.size(); ++j) {
        PathFrame& f = out.frames[frame_at[j]];
        f.x = poses[j][0];
        f.y = poses[j][1];
        f.heading = wrap_angle(poses[j][2]);
      }
      // Every point of the piece with a frame follows that frame's pose (offset scaled by the drift scale).
      for (std::size_t i = 0; i < all.size(); ++i) {
        const PathPoint& p = all[i];
        if (p.piece != k || p.frame < 0) continue;
        auto at = position_of.find(p.frame);
        if (at == position_of.end() || !pose_of.count(at->second)) continue;
        const PathFrame& before = path.frames[at->second];
        const PathFrame& after = out.frames[at->second];
        const Eigen::Vector2d local = rotate(p.position.head<2>() - before.position(), -before.heading);
        const Eigen::Vector2d xy = after.position() + scale * rotate(local, after.heading);
        moved[i].position = {xy.x(), xy.y(), scale * p.position.z()};
      }
    }
    r.pieces.push_back(pr);
  }
  progress.report(1.0);
  if (points) *points = std::move(moved);
  r.seconds = seconds_since(t0);
  return out;
}

std::string describe(const PieceRefinement& piece) {
  std::ostringstream o;
  o << "piece " << piece.piece + 1 << ": ";
  if (!piece.kept) return o.str() + "not refined on the walls: " + piece.message;
  o.setf(std::ios::fixed);
  o.precision(0);
  o << "refined on the walls: " << 100 * piece.wall_share_before << " % -> " << 100 * piece.wall_share_after
    << " % of wall points on walls";
  o.precision(3);
  o << ", scale x" << piece.drift_scale;
  o.precision(2);
  o << ", bias " << piece.drift_bias_deg_per_100_frames << " deg / 100 frames, largest move "
    << piece.max_shift_m << " m";
  return o.str();
}

}  // namespace plenopath
