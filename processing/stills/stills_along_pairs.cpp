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

CameraPath place_stills_along_pairs(const CameraPath& path, const std::vector<StillsPair>& pairs,
                                    const std::function<cv::Mat(int)>& read, const FloorPlan& plan,
                                    const PairPlacementOptions& options, PairPlacementReport* report,
                                    Progress& progress) {
  options.check();
  CameraPath out = path;
  PairPlacementReport local;
  PairPlacementReport& r = report ? *report : local;
  const auto placed = [&](int frame) {
    const PathFrame* f = out.find_frame(frame);
    return f && out.piece_placed(f->piece);
  };
  // A still that may be moved: in an unplaced piece of its own, or of several at metric scale.
  const auto movable = [&](int frame) {
    const PathFrame* f = out.find_frame(frame);
    if (!f || out.piece_placed(f->piece)) return false;
    const CameraPath piece = out.piece_path(f->piece);
    return piece.size() == 1 ||
           (!out.pieces.empty() &&
            out.pieces[static_cast<std::size_t>(f->piece)].scale_source == "camera_height");
  };
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
    const double turn = best->turn_deg * M_PI / 180.0, direction = best->direction_deg * M_PI / 180.0;
    // B = A + L (cos(hA + phi), sin(hA + phi)), hB = hA + psi; seen from B, A lies at phi + pi - psi.
    const double world_direction =
        a_placed ? known.heading + direction : known.heading + direction + M_PI - turn;
    const double heading = a_placed ? known.heading + turn : known.heading - turn;
    const Eigen::Vector2d along(std::cos(world_direction), std::sin(world_direction));
    const Eigen::Vector2d side(-along.y(), along.x());
    std::vector<Eigen::Vector2d> spots;
    for (double t = options.min_distance_m; t <= options.max_distance_m + 1e-9; t += options.step_m)
      for (double l : {0.0, -options.lateral_m, options.lateral_m}) {
        if (l != 0.0 && options.lateral_m <= 0) continue;
        const Eigen::Vector2d q = known.position() + t * along + l * side;
        if (!options.require_line_of_sight || !crosses_any_wall(walls, known.position(), q))
          spots.push_back(q);
      }
    if (spots.empty()) {  // the pair points straight into a wall
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
    out = path_with_still_placed(out, to, pose);
    r.placed.push_back({to, from, pose, runner_up});
    tried.clear();  // a newly placed still may carry others
    tried.insert(to);
    for (const PairPlacement& q : r.placed) tried.insert(q.frame);
  }
  progress.report(1.0);
  return out;
}

}  // namespace plenopath
