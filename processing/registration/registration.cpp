#include "processing/registration/registration.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/registration/registration_internal.h"

namespace plenopath {

using namespace registration_detail;

// The ceiling above the floor: the highest crowd of points above the camera (30 cm sums of 10 cm bands: a
// local peak holding a quarter of the densest, twice the mean of the half metre above it and 1.5 times that
// of the half metre from 0.3 m below it: a crowd, not the top of the walls' spread), as nothing in a room
// lies above its ceiling; otherwise camera height + 1 m. Not the densest band: in a tall hall a row of
// pictures or window transoms at 3 m holds more points than the ceiling at 7 m.
double registration_detail::estimate_ceiling(const std::vector<const PathPoint*>& points,
                                             const RegistrationOptions& options) {
  if (options.ceiling_height_m > 0) return options.ceiling_height_m;
  const double fallback = options.camera_height_m + 1.0;
  constexpr int kBins = 100;  // 10 cm bands up to 10 m above the camera
  std::vector<int> bins(kBins + 8, 0);
  int above = 0;
  for (const PathPoint* p : points) {
    const double z = p->position.z();
    if (z < 0.2 || z > 10.0) continue;
    ++bins[static_cast<std::size_t>(std::min(kBins - 1, static_cast<int>(std::floor(z / 0.1))))];
    ++above;
  }
  if (above < 30) return fallback;
  std::vector<int> sums(bins.size(), 0);
  for (std::size_t i = 1; i + 1 < bins.size(); ++i) sums[i] = bins[i - 1] + bins[i] + bins[i + 1];
  const int densest = *std::max_element(sums.begin(), sums.end());
  const int enough = std::max(8, (densest + 3) / 4);
  int best_bin = -1;
  for (int i = kBins - 1; i >= 2 && best_bin < 0; --i) {
    const auto at = [&](int k) { return sums[static_cast<std::size_t>(k)]; };
    if (at(i) < enough || at(i) < at(i - 1) || at(i) < at(i + 1)) continue;
    // Sums below 0.3 m lack the bands under 0.2 m that were left out: not counted.
    double over = 0, under = 0;
    int under_n = 0;
    for (int k = i + 2; k <= i + 6; ++k) over += at(k) / 5.0;
    for (int k = std::max(3, i - 7); k <= i - 3; ++k, ++under_n) under += at(k);
    if (under_n > 0) under /= under_n;
    if (at(i) >= 2.0 * over && at(i) >= 1.5 * under) best_bin = i;
  }
  if (best_bin < 0) return fallback;
  // The mean height of the points in the band and its neighbours.
  double sum = 0;
  int n = 0;
  for (const PathPoint* p : points) {
    const double z = p->position.z();
    if (std::abs(z - (best_bin + 0.5) * 0.1) <= 0.15) {
      sum += z;
      ++n;
    }
  }
  return options.camera_height_m + sum / n;
}

bool registration_detail::in_wall_band(const PathPoint& p, const RegistrationOptions& options,
                                       double ceiling_m) {
  const double z = p.position.z();
  return p.observations >= options.min_observations &&
         z > -options.camera_height_m + options.floor_margin_m &&
         z < ceiling_m - options.camera_height_m - options.ceiling_margin_m;
}

void RegistrationOptions::check() const {
  const std::string s = "RegistrationOptions.";
  require_option(camera_height_m > 0, s + "camera_height_m", "must be > 0", camera_height_m);
  require_option(floor_margin_m >= 0, s + "floor_margin_m", "must be >= 0", floor_margin_m);
  require_option(ceiling_height_m == 0 || ceiling_height_m > camera_height_m, s + "ceiling_height_m",
                 "must be 0 (estimated) or above camera_height_m", ceiling_height_m);
  require_option(ceiling_margin_m >= 0, s + "ceiling_margin_m", "must be >= 0", ceiling_margin_m);
  require_option(min_observations >= 0, s + "min_observations", "must be >= 0", min_observations);
  require_option(cell_m >= 0.005 && cell_m <= 0.5, s + "cell_m", "must be in [0.005, 0.5]", cell_m);
  require_option(coarse_cell_m >= cell_m, s + "coarse_cell_m", "must be >= cell_m", coarse_cell_m);
  require_option(rotation_step_deg > 0 && rotation_step_deg <= 45, s + "rotation_step_deg",
                 "must be in (0, 45]", rotation_step_deg);
  require_option(scale_range >= 0 && scale_range < 0.5, s + "scale_range", "must be in [0, 0.5)",
                 scale_range);
  require_option(scale_prior_sigma > 0, s + "scale_prior_sigma", "must be > 0", scale_prior_sigma);
  require_option(inlier_tolerance_m > 0, s + "inlier_tolerance_m", "must be > 0", inlier_tolerance_m);
  require_option(free_space_weight >= 0, s + "free_space_weight", "must be >= 0", free_space_weight);
  require_option(refine_candidates >= 1, s + "refine_candidates", "must be >= 1", refine_candidates);
  require_option(max_candidates >= 1, s + "max_candidates", "must be >= 1", max_candidates);
  require_option(distinct_rotation_deg >= 0, s + "distinct_rotation_deg", "must be >= 0",
                 distinct_rotation_deg);
  require_option(distinct_translation_m >= 0, s + "distinct_translation_m", "must be >= 0",
                 distinct_translation_m);
  require_option(local_search_deg >= 0 && local_search_deg <= 45, s + "local_search_deg",
                 "must be in [0, 45]", local_search_deg);
  require_option(local_search_step_deg > 0, s + "local_search_step_deg", "must be > 0",
                 local_search_step_deg);
  require_option(local_search_m >= 0 && local_search_m <= 5, s + "local_search_m", "must be in [0, 5]",
                 local_search_m);
  require_option(icp_iterations >= 0, s + "icp_iterations", "must be >= 0", icp_iterations);
  require_option(huber_m > 0, s + "huber_m", "must be > 0", huber_m);
  require_option(seen_through_weight >= 0, s + "seen_through_weight", "must be >= 0", seen_through_weight);
  require_option(seen_through_depth_margin >= 0 && seen_through_depth_margin < 1,
                 s + "seen_through_depth_margin", "must be in [0, 1)", seen_through_depth_margin);
  require_option(min_score >= 0 && min_score <= 1, s + "min_score", "must be in [0, 1]", min_score);
  require_option(window_length_m >= 0, s + "window_length_m", "must be >= 0", window_length_m);
  require_option(min_wall_points >= 3, s + "min_wall_points", "must be >= 3", min_wall_points);
}

double PieceRegistration::ambiguity_ratio() const {
  if (candidates.size() < 2 || candidates[1].score <= 0) return std::numeric_limits<double>::infinity();
  return candidates[0].score / candidates[1].score;
}

bool RegistrationResult::all_ok() const {
  for (const PieceRegistration& p : pieces)
    if (!p.ok) return false;
  return !pieces.empty();
}

namespace {

int percent(double share) { return static_cast<int>(std::lround(100 * share)); }

// Every k-th element, k = max(1, size / count): an even sample of about `count` (all when fewer).
std::vector<Eigen::Vector2d> even_sample(const std::vector<Eigen::Vector2d>& all, std::size_t count) {
  std::vector<Eigen::Vector2d> out;
  const std::size_t step = std::max<std::size_t>(1, all.size() / count);
  for (std::size_t i = 0; i < all.size(); i += step) out.push_back(all[i]);
  return out;
}

// `frames`: the piece's frames whose pose the images gave; `frame_position`: every frame of the path by its
// index (where a point was measured from).
PieceRegistration register_piece(int piece, const std::vector<Eigen::Vector2d>& frames,
                                 const std::unordered_map<int, Eigen::Vector2d>& frame_position,
                                 const std::vector<const PathPoint*>& points, const PlanRaster& plan,
                                 const CoarseRaster& coarse, const SegmentGrid& grid,
                                 const std::vector<double>& plan_dirs, const RegistrationOptions& options,
                                 Progress& progress) {
  PieceRegistration out;
  out.piece = piece;
  out.ceiling_m = estimate_ceiling(points, options);
  const double z_min = -options.camera_height_m + options.floor_margin_m;
  const double z_max = out.ceiling_m - options.camera_height_m - options.ceiling_margin_m;
  // No point is seen by more keyframes than the piece has: a group of three stills counts the points two of
  // them saw (still two, the least that measures a point).
  RegistrationOptions band = options;
  band.min_observations =
      std::min(options.min_observations, std::max(2, static_cast<int>(frames.size()) - 1));
  std::vector<Eigen::Vector2d> wall, observers;
  const Eigen::Vector2d unknown = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (const PathPoint* p : points) {
    if (!in_wall_band(*p, band, out.ceiling_m)) continue;
    wall.push_back(p->position.head<2>());
    const auto at = frame_position.find(p->frame);
    observers.push_back(at == frame_position.end() ? unknown : at->second);
  }
  out.wall_points = static_cast<int>(wall.size());
  if (out.wall_points < options.min_wall_points) {
    out.message = "too few wall points to register: " + std::to_string(out.wall_points) + " (of " +
                  std::to_string(points.size()) + " points; at least " +
                  std::to_string(options.min_wall_points) + " needed between " + std::to_string(z_min) +
                  " and " + std::to_string(z_max) + " m from the camera)";
    return out;
  }
  // A path longer than the plan is wide fits nowhere: a wrong metric scale, or another building. Said so
  // here, before the search sizes its rasters by the path (a tracker that lost its scale once made one of
  // 13 TB). Wall points beyond the plan's reach from the path are dropped for the same reason.
  const double plan_span = coarse.cell * std::hypot(coarse.wall_proximity.cols, coarse.wall_proximity.rows);
  Eigen::Vector2d low = frames.empty() ? Eigen::Vector2d::Zero() : frames.front(), high = low;
  for (const Eigen::Vector2d& f : frames) {
    low = low.cwiseMin(f);
    high = high.cwiseMax(f);
  }
  const double path_span = (high - low).norm();
  if (!(path_span <= 1.2 * plan_span + 2.0)) {
    std::ostringstream m;
    m << std::fixed << std::setprecision(0) << "no placement fits: the path spans " << path_span
      << " m and the plan only " << plan_span
      << " m (is the metric scale right, or the plan another building?)";
    out.message = m.str();
    return out;
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < wall.size(); ++i) {
    const Eigen::Vector2d outside = (low - wall[i]).cwiseMax(wall[i] - high).cwiseMax(0.0);
    if (outside.norm() > plan_span) continue;
    wall[kept] = wall[i];
    observers[kept++] = observers[i];
  }
  wall.resize(kept);
  observers.resize(kept);
  if (static_cast<int>(wall.size()) < options.min_wall_points) {
    out.message = "too few wall points within the plan's reach of the path: " + std::to_string(wall.size());
    return out;
  }
  // The global search needs no more than ~20 000 points; the refinement and the score see them all.
  const std::vector<Eigen::Vector2d> sampled = even_sample(wall, 20000);
  const std::vector<Eigen::Vector2d> sampled_frames = even_sample(frames, 500);

  SubProgress search_progress(progress, 0.0, 0.7, "search");
  const std::vector<Placement> starts =
      global_search(sampled, sampled_frames, coarse, plan_dirs, options, search_progress);

  // Suppression after refinement on where the points' mean lands.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& q : wall) mean += q;
  mean /= static_cast<double>(wall.size());
  std::vector<Placement> refined;
  std::vector<RegistrationCandidate> scored;
  // The search's translation is a coarse cell's corner; along a corridor the few walls across it hold the
  // refinement loosely and the scale takes up the rest, so a start a cell off can settle a cell off (the
  // POV-Ray trolley walk: 0.25 m, scale 1.016, score 0.34 against 0.47 from the truth). The refinement
  // also starts a cell either way along the plan's two main directions, on at most 10 000 of the points
  // (an even sample), and the start whose refinement scores best is refined with them all.
  std::vector<Eigen::Vector2d> nudges = {Eigen::Vector2d::Zero()};
  if (options.nudged_starts) {
    const double main_direction = plan_dirs.empty() ? 0.0 : plan_dirs.front();
    for (int quarter = 0; quarter < 4; ++quarter)
      nudges.push_back(coarse.cell * rotate(Eigen::Vector2d::UnitX(), main_direction + quarter * M_PI / 2));
  }
  const std::vector<Eigen::Vector2d> nudge_wall = even_sample(wall, 10000),
                                     nudge_observers = even_sample(observers, 10000);
  const bool nudge_sample_is_all = nudge_wall.size() == wall.size();
  const cv::Mat soft = soft_wall_raster(plan, options.inlier_tolerance_m);
  const std::vector<Eigen::Vector2d> local_wall = even_sample(wall, 2000);
  for (std::size_t i = 0; i < starts.size(); ++i) {
    progress.checkpoint(0.7 + 0.3 * double(i) / starts.size(), "refinement");
    const Similarity2 local = local_search(local_wall, soft, plan, starts[i].transform, options);
    Similarity2 from = local, t;
    RegistrationCandidate c;
    bool refined_with_all = false;
    if (nudges.size() > 1) {
      double best = -1;
      for (const Eigen::Vector2d& nudge : nudges) {
        Similarity2 start = local;
        start.translation += nudge;
        const Similarity2 t_k = refine_icp(nudge_wall, plan, start, 3.0 * coarse.cell, options);
        const RegistrationCandidate c_k =
            score_placement(nudge_wall, nudge_observers, nudge_sample_is_all ? frames : sampled_frames, plan,
                            grid, t_k, options);
        if (c_k.score <= best) continue;
        best = c_k.score;
        from = start;
        t = t_k;
        c = c_k;
      }
      refined_with_all = nudge_sample_is_all;
    }
    if (!refined_with_all) {
      t = refine_icp(wall, plan, from, 3.0 * coarse.cell, options);
      c = score_placement(wall, observers, frames, plan, grid, t, options);
    }
    Placement p;
    p.transform = t;
    p.score = c.score;
    p.centre = t.apply(mean);
    refined.push_back(p);
    scored.push_back(c);
  }
  // Distinct placements, best first; each keeps its full score.
  std::vector<Placement> distinct = distinct_placements(refined, options, options.max_candidates);
  for (const Placement& p : distinct)
    for (std::size_t i = 0; i < refined.size(); ++i)
      if (refined[i].transform.rotation == p.transform.rotation &&
          refined[i].transform.translation == p.transform.translation) {
        out.candidates.push_back(scored[i]);
        break;
      }
  progress.report(1.0, "refinement");
  if (out.candidates.empty()) {
    out.message = "no placement fits: the search found no candidate";
    return out;
  }
  const RegistrationCandidate& best = out.candidates.front();
  out.ok = best.score >= options.min_score;
  if (!out.ok) {
    std::ostringstream m;
    m << "no placement fits: best candidate has " << percent(best.wall_share)
      << " % of wall points on walls, " << percent(best.through_share) << " % seen through walls and "
      << percent(best.free_share) << " % of frames in free space (score " << std::lround(100 * best.score)
      << " %, at least " << std::lround(100 * options.min_score) << " % needed)";
    out.message = m.str();
  }
  return out;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

RegistrationResult register_on_plan(const CameraPath& path, const std::vector<PathPoint>& points,
                                    const FloorPlan& plan, const RegistrationOptions& options,
                                    Progress& progress) {
  options.check();
  const auto t0 = std::chrono::steady_clock::now();
  if (path.empty()) throw Error("registration: the path has no frames");
  const int piece_count = path.piece_count();
  for (const PathPoint& p : points)
    if (p.piece < 0 || p.piece >= piece_count)
      throw Error("registration: a point names piece " + std::to_string(p.piece) + " but the path has " +
                  std::to_string(piece_count) + " piece(s)");
  progress.checkpoint(0.0, "rasters");
  const PlanRaster raster = build_plan_raster(plan, options.cell_m, 2.0);
  const CoarseRaster coarse = coarsen(raster, options.coarse_cell_m, 400);
  const SegmentGrid grid(raster.walls);
  const std::vector<double> dirs = plan_directions(raster.walls);
  progress.checkpoint(0.05, "rasters");

  std::vector<std::vector<const PathPoint*>> by_piece(static_cast<std::size_t>(piece_count));
  for (const PathPoint& p : points) by_piece[static_cast<std::size_t>(p.piece)].push_back(&p);
  // Frames the tracker bridged (held or interpolated where the images gave no pose, e.g. inside a wall the
  // camera passed through) are no evidence of where the piece lies; a piece of bridged frames only keeps
  // them.
  std::vector<std::vector<Eigen::Vector2d>> frames(static_cast<std::size_t>(piece_count)),
      bridged(static_cast<std::size_t>(piece_count));
  std::unordered_map<int, Eigen::Vector2d> frame_position;
  for (const PathFrame& f : path.frames) {
    frame_position[f.index] = f.position();
    if (f.piece >= 0 && f.piece < piece_count)
      ((f.flags & kFrameBridged) ? bridged : frames)[static_cast<std::size_t>(f.piece)].push_back(
          f.position());
  }
  for (std::size_t k = 0; k < frames.size(); ++k)
    if (frames[k].empty()) frames[k] = std::move(bridged[k]);

  // Pieces placed in the path's own frame share it (the runs of one group of stills, pieces the tracker
  // joined): they are registered together, by all their frames and points, and move alike.
  std::vector<int> shared;
  if (piece_count > 1)
    for (int k = 0; k < piece_count; ++k)
      if (path.pieces[static_cast<std::size_t>(k)].placed) shared.push_back(k);
  if (shared.size() < 2) shared.clear();
  for (std::size_t s = 1; s < shared.size(); ++s) {
    const auto k = static_cast<std::size_t>(shared[s]), first = static_cast<std::size_t>(shared.front());
    frames[first].insert(frames[first].end(), frames[k].begin(), frames[k].end());
    by_piece[first].insert(by_piece[first].end(), by_piece[k].begin(), by_piece[k].end());
  }

  RegistrationResult result;
  for (int k = 0; k < piece_count; ++k) {
    if (!shared.empty() && k != shared.front() && std::count(shared.begin(), shared.end(), k)) {
      PieceRegistration r = result.pieces[static_cast<std::size_t>(shared.front())];
      r.piece = k;
      r.message = "placed with piece " + std::to_string(shared.front() + 1) + " (they share one frame)" +
                  (r.message.empty() ? std::string() : "; " + r.message);
      result.pieces.push_back(std::move(r));
      continue;
    }
    const double begin = 0.05 + 0.95 * k / piece_count, end = 0.05 + 0.95 * (k + 1) / piece_count;
    SubProgress sub(progress, begin, end,
                    piece_count == 1 ? std::string() : "piece " + std::to_string(k + 1));
    if (!path.pieces.empty() && path.pieces[static_cast<std::size_t>(k)].scale_source == "relative") {
      PieceRegistration r;
      r.piece = k;
      r.message = "piece " + std::to_string(k + 1) +
                  " has no metric scale (no camera height or known distance): registration needs one";
      result.pieces.push_back(std::move(r));
      continue;
    }
    SubProgress whole(sub, 0.0, 0.5);
    PieceRegistration r =
        register_piece(k, frames[static_cast<std::size_t>(k)], frame_position,
                       by_piece[static_cast<std::size_t>(k)], raster, coarse, grid, dirs, options, whole);
    // A long piece that fits no similarity may have drifted (a heading bias bends it, passes over the same
    // wall smear apart): its first stretch, less bent, is placed instead, and the plan refinement
    // (plan_refinement.h) straightens the rest.
    if (!r.ok && options.window_length_m > 0) {
      std::vector<Eigen::Vector2d> window_frames;
      std::set<int> window_indices;
      double length = 0;
      const PathFrame* previous = nullptr;
      for (const PathFrame& f : path.frames) {
        if (f.piece != k && piece_count > 1) continue;
        if (previous) length += (f.position() - previous->position()).norm();
        previous = &f;
        if (length > options.window_length_m) break;
        if (!(f.flags & kFrameBridged)) window_frames.push_back(f.position());
        window_indices.insert(f.index);
      }
      std::vector<const PathPoint*> window_points;
      for (const PathPoint* p : by_piece[static_cast<std::size_t>(k)])
        if (p->frame >= 0 && window_indices.count(p->frame)) window_points.push_back(p);
      if (length > options.window_length_m && window_points.size() >= 100) {
        SubProgress part(sub, 0.5, 1.0, "first stretch");
        PieceRegistration w = register_piece(k, window_frames, frame_position, window_points, raster, coarse,
                                             grid, dirs, options, part);
        if (w.ok) {
          w.by_window = true;
          w.message = "the whole piece fits no single placement (drift?): placed by its first " +
                      std::to_string(static_cast<int>(options.window_length_m)) + " m";
          r = std::move(w);
        }
      }
    }
    result.pieces.push_back(std::move(r));
  }
  progress.report(1.0);
  result.seconds = seconds_since(t0);
  return result;
}

CameraPath apply_registration(const CameraPath& path, const RegistrationResult& result,
                              const std::vector<int>& choice, std::vector<PathPoint>* points) {
  CameraPath out = path;
  for (const PieceRegistration& r : result.pieces) {
    int pick = r.ok ? 0 : -1;
    if (r.piece < static_cast<int>(choice.size())) pick = choice[static_cast<std::size_t>(r.piece)];
    if (pick < 0) continue;
    if (pick >= static_cast<int>(r.candidates.size()))
      throw Error("registration: piece " + std::to_string(r.piece + 1) + " has no candidate " +
                  std::to_string(pick + 1) + " (it has " + std::to_string(r.candidates.size()) + ")");
    const Similarity2& t = r.candidates[static_cast<std::size_t>(pick)].transform;
    for (PathFrame& f : out.frames) {
      if (f.piece != r.piece) continue;
      const Eigen::Vector2d p = t.apply(f.position());
      f.x = p.x();
      f.y = p.y();
      f.heading = wrap_angle(f.heading + t.rotation);
    }
    if (!out.pieces.empty() && r.piece < static_cast<int>(out.pieces.size()))
      out.pieces[static_cast<std::size_t>(r.piece)].placed = true;
    if (points) transform_piece_points(points, r.piece, t.rotation, t.scale, t.translation);
  }
  return out;
}

int candidate_for_anchors(const CameraPath& path, const PieceRegistration& piece, const Anchors& anchors) {
  int best = -1;
  double best_error = std::numeric_limits<double>::max();
  for (std::size_t c = 0; c < piece.candidates.size(); ++c) {
    const Similarity2& t = piece.candidates[c].transform;
    double error = 0;
    int n = 0;
    for (const Anchor& a : anchors) {
      const PathFrame* f = path.find_frame(a.frame);
      if (!f || f->piece != piece.piece) continue;
      error += (t.apply(f->position()) - a.position).squaredNorm();
      if (a.heading) error += std::pow(wrap_angle(f->heading + t.rotation - *a.heading), 2);  // 1 rad ~ 1 m
      ++n;
    }
    if (n == 0) return -1;
    if (error < best_error) {
      best_error = error;
      best = static_cast<int>(c);
    }
  }
  return best;
}

std::string describe(const PieceRegistration& piece) {
  std::ostringstream o;
  o << "piece " << piece.piece + 1 << ": ";
  if (!piece.ok) return o.str() + piece.message;
  const RegistrationCandidate& c = piece.candidates.front();
  o.setf(std::ios::fixed);
  o.precision(3);
  o << "rotation " << degrees(c.transform.rotation) << " deg, translation (" << c.transform.translation.x()
    << ", " << c.transform.translation.y() << ") m, scale " << c.transform.scale;
  o.precision(0);
  o << ", " << 100 * c.wall_share << " % of " << piece.wall_points << " wall points on walls, "
    << 100 * c.free_share << " % of frames in free space";
  if (c.through_share >= 0.005) o << ", " << 100 * c.through_share << " % seen through walls";
  if (piece.candidates.size() > 1) {
    o.precision(2);
    o << "; next candidate scores " << piece.candidates[1].score / std::max(1e-12, c.score) << " of it";
  }
  if (piece.by_window) o << "; " << piece.message;
  return o.str();
}

}  // namespace plenopath
