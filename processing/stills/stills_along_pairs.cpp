#include "processing/stills/stills_along_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "model/error.h"
#include "processing/walk/walk_route.h"

namespace plenopath {

void PairPlacementOptions::check() const {
  fit.check();
  if (!(min_distance_m > 0) || !(max_distance_m > min_distance_m) || !(step_m > 0))
    throw Error("PairPlacementOptions: need 0 < min_distance_m < max_distance_m and step_m > 0");
  if (!(lateral_m >= 0)) throw Error("PairPlacementOptions.lateral_m must be >= 0");
  if (!(heading_spread_deg > 0)) throw Error("PairPlacementOptions.heading_spread_deg must be > 0");
  if (min_inliers < 1) throw Error("PairPlacementOptions.min_inliers must be >= 1");
  if (!(max_fit_px > 0)) throw Error("PairPlacementOptions.max_fit_px must be > 0");
  if (!(ambiguity_gap_m > 0) || !(min_ambiguity_ratio >= 1))
    throw Error("PairPlacementOptions: ambiguity_gap_m must be > 0 and min_ambiguity_ratio >= 1");
}

int split_unscaled_groups(CameraPath* path, std::vector<PathPoint>* points) {
  if (path->pieces.empty()) return 0;
  const auto split = [&](const PathPiece& piece) {
    return !piece.placed && piece.scale_source != "camera_height" && piece.last_index > piece.first_index;
  };
  // first_new[k]: the new number of old piece k's first still; later stills of a split piece follow it.
  std::vector<int> first_new;
  std::vector<PathPiece> pieces;
  int count = 0;
  for (const PathPiece& piece : path->pieces) {
    first_new.push_back(static_cast<int>(pieces.size()));
    if (!split(piece)) {
      pieces.push_back(piece);
      continue;
    }
    ++count;
    bool first = true;
    for (const PathFrame& f : path->frames) {
      if (f.index < piece.first_index || f.index > piece.last_index) continue;
      PathPiece one = piece;
      one.first_index = one.last_index = f.index;
      if (!first)
        one.break_reason = "still " + std::to_string(f.index) +
                           "'s group has no metric scale: its stills are placed one by one";
      first = false;
      pieces.push_back(one);
    }
  }
  if (count == 0) return 0;
  // The new piece of a frame of old piece k: its own when k was split, else k's.
  std::vector<int> new_piece_of_frame(path->frames.size());
  for (std::size_t i = 0; i < path->frames.size(); ++i) {
    PathFrame& f = path->frames[i];
    const int k = f.piece;
    int n = first_new[static_cast<std::size_t>(k)];
    if (split(path->pieces[static_cast<std::size_t>(k)])) {
      while (pieces[static_cast<std::size_t>(n)].first_index != f.index) ++n;
      f.flags |= kFramePieceStart;
    }
    f.piece = n;
  }
  if (points) {
    for (PathPoint& p : *points) {
      if (p.piece < 0 || p.piece >= static_cast<int>(path->pieces.size())) continue;
      const int k = p.piece;
      p.piece = first_new[static_cast<std::size_t>(k)];
      if (!split(path->pieces[static_cast<std::size_t>(k)])) continue;
      const PathFrame* f = path->find_frame(p.frame);
      const PathPiece& old = path->pieces[static_cast<std::size_t>(k)];
      if (f && f->index >= old.first_index && f->index <= old.last_index) p.piece = f->piece;
    }
  }
  path->pieces = std::move(pieces);
  return count;
}

double pair_bearing_from(const StillsPair& pair, int placed_frame, double placed_heading) {
  const double turn = pair.turn_deg * M_PI / 180.0, direction = pair.direction_deg * M_PI / 180.0;
  // B = A + L (cos(hA + phi), sin(hA + phi)); seen from B, A lies at phi + pi - psi.
  return pair.a == placed_frame ? placed_heading + direction : placed_heading + direction + M_PI - turn;
}

bool pair_sees_spot(const StillsPair& pair, int placed_frame, const Eigen::Vector2d& placed_position,
                    double placed_heading, const Eigen::Vector2d& spot, const PairPlacementOptions& options) {
  const double predicted = pair_bearing_from(pair, placed_frame, placed_heading);
  const Eigen::Vector2d to_spot = spot - placed_position;
  const double distance = to_spot.norm();
  if (!(distance > 0)) return false;
  const double off = std::remainder(std::atan2(to_spot.y(), to_spot.x()) - predicted, 2 * M_PI);
  const double miss = distance * std::abs(std::sin(off));
  return std::abs(off) <= options.heading_spread_deg * M_PI / 180.0 || miss <= 2 * options.lateral_m;
}

CameraPath place_stills_along_pairs(const CameraPath& path, const std::vector<StillsPair>& pairs,
                                    const std::function<cv::Mat(int)>& read, const FloorPlan& plan,
                                    std::vector<PathPoint>* points, const PairPlacementOptions& options,
                                    PairPlacementReport* report, Progress& progress) {
  options.check();
  CameraPath out = path;
  split_unscaled_groups(&out, points);
  PairPlacementReport local;
  PairPlacementReport& r = report ? *report : local;
  const auto placed = [&](int frame) {
    const PathFrame* f = out.find_frame(frame);
    return f && out.piece_placed(f->piece);
  };
  const auto movable = [&](int frame) { return still_can_be_moved(out, frame); };
  const std::vector<PlanSegment> walls = plan.occluder_segments();
  std::set<int> tried;
  while (true) {
    progress.throw_if_cancelled();
    // The strongest pair from a placed still to a movable one not tried yet.
    const StillsPair* best = nullptr;
    for (const StillsPair& p : pairs) {
      if (p.inliers < options.min_inliers || p.median_parallax_deg < 1.0) continue;
      const bool a_to_b = placed(p.a) && movable(p.b), b_to_a = placed(p.b) && movable(p.a);
      if (!a_to_b && !b_to_a) continue;
      if (tried.count(a_to_b ? p.b : p.a)) continue;
      if (!best || p.inliers > best->inliers) best = &p;
    }
    if (!best) break;
    const bool a_placed = placed(best->a);
    const int from = a_placed ? best->a : best->b, to = a_placed ? best->b : best->a;
    tried.insert(to);
    const PathFrame& known = *out.find_frame(from);
    const double turn = best->turn_deg * M_PI / 180.0;
    const double world_direction = pair_bearing_from(*best, from, known.heading);
    const double heading = a_placed ? known.heading + turn : known.heading - turn;
    const Eigen::Vector2d along(std::cos(world_direction), std::sin(world_direction));
    const Eigen::Vector2d side(-along.y(), along.x());
    // The still's other pairs with placed stills (and those stills): the spots tried are those every one
    // of them sees.
    std::vector<std::pair<const StillsPair*, const PathFrame*>> others;
    int crossing = 0;
    for (const StillsPair& p : pairs) {
      if (&p == best || (p.a != to && p.b != to)) continue;
      if (p.inliers < options.min_inliers || p.median_parallax_deg < 1.0) continue;
      const PathFrame* other = out.find_frame(p.a == to ? p.b : p.a);
      if (!other || !out.piece_placed(other->piece)) continue;
      others.push_back({&p, other});
      const double bearing = pair_bearing_from(p, other->index, other->heading);
      crossing += std::abs(std::sin(bearing - world_direction)) >= std::sin(15.0 * M_PI / 180.0);
    }
    const auto seen_by_others = [&](const Eigen::Vector2d& q) {
      for (const auto& [p, f] : others)
        if (!pair_sees_spot(*p, f->index, f->position(), f->heading, q, options)) return false;
      return true;
    };
    std::vector<Eigen::Vector2d> spots;
    for (double t = options.min_distance_m; t <= options.max_distance_m + 1e-9; t += options.step_m)
      for (double l : {0.0, -options.lateral_m, options.lateral_m}) {
        if (l != 0.0 && options.lateral_m <= 0) continue;
        const Eigen::Vector2d q = known.position() + t * along + l * side;
        if ((!options.require_line_of_sight || !crosses_any_wall(walls, known.position(), q)) &&
            seen_by_others(q))
          spots.push_back(q);
      }
    if (spots.empty()) {  // the pair points straight into a wall, or its other pairs see it elsewhere
      r.rejected.push_back(to);
      continue;
    }
    StillOnPlanOptions fit = options.fit;
    fit.heading_hint_deg = heading * 180.0 / M_PI;
    fit.heading_hint_spread_deg = options.heading_spread_deg;
    progress.checkpoint(
        0.0, "placing still " + std::to_string(to) + " along its pair with still " + std::to_string(from));
    StillPlacement pose;
    try {
      pose = place_still_among(read(to), plan, spots, fit);
    } catch (const Error&) {  // every spot inside a wall: the pair points out of the building
      r.rejected.push_back(to);
      continue;
    }
    if (!(pose.score_px <= options.max_fit_px)) {
      r.rejected.push_back(to);
      continue;
    }
    std::vector<Eigen::Vector2d> elsewhere;
    for (const Eigen::Vector2d& q : spots)
      if ((q - Eigen::Vector2d(pose.x, pose.y)).norm() > options.ambiguity_gap_m) elsewhere.push_back(q);
    double runner_up = std::numeric_limits<double>::infinity();
    if (!elsewhere.empty()) {
      try {
        runner_up = place_still_among(read(to), plan, elsewhere, fit).score_px;
      } catch (const Error&) {  // nowhere else clear of the walls
      }
    }
    if (!(runner_up >= options.min_ambiguity_ratio * pose.score_px)) {
      r.rejected.push_back(to);
      continue;
    }
    // The refined pose may leave the spots tried: the other pairs must still see it there.
    if (!seen_by_others({pose.x, pose.y})) {
      r.rejected.push_back(to);
      continue;
    }
    out = path_with_still_placed(out, to, pose, points);
    r.placed.push_back({to, from, pose, runner_up, static_cast<int>(others.size()), crossing});
    tried.clear();  // a newly placed still may carry others
    tried.insert(to);
    for (const PairPlacement& q : r.placed) tried.insert(q.frame);
  }
  progress.report(1.0);
  return out;
}

}  // namespace plenopath
