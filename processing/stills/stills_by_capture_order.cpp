#include "processing/stills/stills_by_capture_order.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <queue>
#include <set>

#include "model/error.h"
#include "processing/plan/segment_grid.h"
#include "processing/walk/walk_route.h"

namespace plenopath {

void CaptureOrderPlacementOptions::check() const {
  fit.check();
  if (!(reach_m > 0)) throw Error("CaptureOrderPlacementOptions.reach_m must be > 0");
  if (!(coarse_step_m > 0) || coarse_step_m > reach_m)
    throw Error("CaptureOrderPlacementOptions.coarse_step_m must be > 0 and no larger than reach_m");
  if (coarse_width < 360 || coarse_width % 4)
    throw Error("CaptureOrderPlacementOptions.coarse_width must be >= 360 and a multiple of 4");
  if (!(max_fit_px > 0)) throw Error("CaptureOrderPlacementOptions.max_fit_px must be > 0");
  if (min_inliers < 1) throw Error("CaptureOrderPlacementOptions.min_inliers must be >= 1");
  if (!(turn_tolerance_deg > 0)) throw Error("CaptureOrderPlacementOptions.turn_tolerance_deg must be > 0");
  if (!(ambiguity_gap_m > 0) || !(min_ambiguity_ratio >= 1))
    throw Error("CaptureOrderPlacementOptions: ambiguity_gap_m must be > 0 and min_ambiguity_ratio >= 1");
}

std::vector<Eigen::Vector2d> spots_within_walking_reach(const FloorPlan& plan, const Eigen::Vector2d& from,
                                                        double reach, double step) {
  if (!(reach > 0) || !(step > 0)) throw Error("spots_within_walking_reach: reach and step must be > 0");
  const std::vector<PlanSegment> all = plan.occluder_segments();
  // Only the walls near enough to matter.
  std::vector<PlanSegment> walls;
  for (const PlanSegment& w : all)
    if (distance_point_segment(from, w.a, w.b) <= reach + step) walls.push_back(w);
  const auto on_a_wall = [&](const Eigen::Vector2d& p) {
    for (const PlanSegment& w : walls)
      if (distance_point_segment(p, w.a, w.b) < 1e-6) return true;
    return false;
  };
  const int r = static_cast<int>(std::ceil(reach / step));
  const int side = 2 * r + 1;
  const auto id = [&](int i, int k) { return (k + r) * side + (i + r); };
  const auto at = [&](int i, int k) { return Eigen::Vector2d(from + step * Eigen::Vector2d(i, k)); };
  std::vector<double> cost(static_cast<std::size_t>(side * side), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, std::pair<int, int>>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  cost[static_cast<std::size_t>(id(0, 0))] = 0.0;
  open.push({0.0, {0, 0}});
  std::vector<Eigen::Vector2d> spots;
  while (!open.empty()) {
    const auto [c, cell] = open.top();
    open.pop();
    const auto [i, k] = cell;
    if (c > cost[static_cast<std::size_t>(id(i, k))]) continue;
    spots.push_back(at(i, k));
    for (int di = -1; di <= 1; ++di)
      for (int dk = -1; dk <= 1; ++dk) {
        if ((di == 0 && dk == 0) || std::abs(i + di) > r || std::abs(k + dk) > r) continue;
        const double next = c + step * std::hypot(di, dk);
        if (next > reach + 1e-9 || next >= cost[static_cast<std::size_t>(id(i + di, k + dk))]) continue;
        // A step onto a wall and off it again crosses neither way: spots on a wall are not walked on.
        if (on_a_wall(at(i + di, k + dk)) || crosses_any_wall(walls, at(i, k), at(i + di, k + dk))) continue;
        cost[static_cast<std::size_t>(id(i + di, k + dk))] = next;
        open.push({next, {i + di, k + dk}});
      }
  }
  return spots;
}

CameraPath place_stills_by_capture_order(const CameraPath& path, const std::vector<StillsPair>& pairs,
                                         const std::function<cv::Mat(int)>& read, const FloorPlan& plan,
                                         std::vector<PathPoint>* points,
                                         const CaptureOrderPlacementOptions& options,
                                         CaptureOrderReport* report, Progress& progress) {
  options.check();
  CameraPath out = path;
  CaptureOrderReport local;
  CaptureOrderReport& r = report ? *report : local;
  const auto placed = [&](std::size_t position) {
    return position < out.frames.size() && out.piece_placed(out.frames[position].piece);
  };
  // Each still is tried again only when it has more placed neighbours than when it was last tried.
  std::map<int, int> tried;
  while (true) {
    progress.throw_if_cancelled();
    // The next still to try: movable, not tried since the last placement, with a placed neighbour in
    // capture order; two placed neighbours first (the spots reachable from both are fewer).
    std::size_t next = out.frames.size();
    int next_neighbours = 0;
    for (std::size_t q = 0; q < out.frames.size(); ++q) {
      const int index = out.frames[q].index;
      if (!still_can_be_moved(out, index)) continue;
      const int neighbours = (q > 0 && placed(q - 1)) + placed(q + 1);
      const auto last = tried.find(index);
      if (last != tried.end() && neighbours <= last->second) continue;
      if (neighbours > next_neighbours) next = q, next_neighbours = neighbours;
    }
    if (next == out.frames.size()) break;
    const int still = out.frames[next].index;
    tried[still] = next_neighbours;
    // The strongest pair with a placed still gives the heading (its turn is right even when a look-alike
    // room made its direction wrong): a room that looks the same turned round is then no longer ambiguous.
    const StillsPair* strongest = nullptr;
    for (const StillsPair& p : pairs) {
      if (p.inliers < options.min_inliers || (p.a != still && p.b != still)) continue;
      const PathFrame* o = out.find_frame(p.a == still ? p.b : p.a);
      if (o && out.piece_placed(o->piece) && (!strongest || p.inliers > strongest->inliers)) strongest = &p;
    }
    if (!strongest) {
      r.rejected.push_back({still, "no pair with a placed still confirms its heading"});
      continue;
    }
    StillOnPlanOptions coarse = options.fit;
    coarse.work_width = options.coarse_width;
    coarse.coarse_step_m = options.coarse_step_m;
    coarse.fine_step_m = std::min(coarse.fine_step_m * 2.0, options.coarse_step_m);
    coarse.elsewhere_gap_m = options.ambiguity_gap_m;
    const PathFrame& other = *out.find_frame(strongest->a == still ? strongest->b : strongest->a);
    const double other_deg = other.heading * 180.0 / M_PI;
    coarse.heading_hint_deg =
        strongest->a == still ? other_deg - strongest->turn_deg : other_deg + strongest->turn_deg;
    coarse.heading_hint_spread_deg = options.turn_tolerance_deg;
    // The spots within reach of the placed neighbours (of both: those of the first on the second's grid).
    std::vector<int> from;
    std::vector<Eigen::Vector2d> spots;
    for (const std::size_t q : {next - 1, next + 1}) {
      if (q >= out.frames.size() || !placed(q)) continue;  // next - 1 wraps for the first still
      const Eigen::Vector2d origin = out.frames[q].position();
      std::vector<Eigen::Vector2d> reach =
          spots_within_walking_reach(plan, origin, options.reach_m, options.coarse_step_m);
      if (from.empty()) {
        spots = std::move(reach);
      } else {
        const auto key = [&](const Eigen::Vector2d& p) {
          const Eigen::Vector2d g = (p - origin) / options.coarse_step_m;
          return std::make_pair(static_cast<int>(std::lround(g.x())), static_cast<int>(std::lround(g.y())));
        };
        std::set<std::pair<int, int>> second;
        for (const Eigen::Vector2d& p : reach) second.insert(key(p));
        std::vector<Eigen::Vector2d> both;
        for (const Eigen::Vector2d& p : spots)
          if (second.count(key(p))) both.push_back(p);
        spots = std::move(both);
      }
      from.push_back(out.frames[q].index);
    }
    progress.checkpoint(0.0, "placing still " + std::to_string(still) + " next to still " +
                                 std::to_string(from.front()) + " (capture order)");
    const cv::Mat image = read(still);
    StillPlacement rough, pose, elsewhere;
    elsewhere.score_px = std::numeric_limits<double>::infinity();
    try {
      if (spots.empty()) throw Error("no spot within reach of both neighbours");
      rough = place_still_among(image, plan, spots, coarse);
      // The chosen spot and the best ones elsewhere, each refined at the full width, where the plan's
      // curves tell look-alike spots apart best; the best of them is taken.
      StillOnPlanOptions fine = options.fit;
      fine.heading_hint_spread_deg = 2.0;
      fine.search_radius_m = options.coarse_step_m;
      std::vector<Eigen::Vector3d> tries = {{rough.x, rough.y, rough.heading_deg}};
      for (const Eigen::Vector4d& e : rough.elsewhere) tries.push_back(e.head<3>());
      std::vector<StillPlacement> refined;
      for (const Eigen::Vector3d& t : tries) {
        fine.heading_hint_deg = t.z();
        refined.push_back(place_still_on_plan(image, plan, t.head<2>(), fine));
      }
      std::size_t chosen = 0;
      for (std::size_t k = 1; k < refined.size(); ++k)
        if (refined[k].score_px < refined[chosen].score_px) chosen = k;
      pose = refined[chosen];
      for (const StillPlacement& k : refined)
        if ((Eigen::Vector2d(k.x, k.y) - Eigen::Vector2d(pose.x, pose.y)).norm() > options.ambiguity_gap_m &&
            k.score_px < elsewhere.score_px)
          elsewhere = k;
    } catch (const Error& e) {  // nowhere within reach is clear of the walls
      r.rejected.push_back({still, e.what()});
      continue;
    }
    char why[160] = "";
    if (!(pose.score_px <= options.max_fit_px))
      std::snprintf(why, sizeof why, "best fit %.2f px, worse than %.2f px", pose.score_px,
                    options.max_fit_px);
    else if (!(elsewhere.score_px >= options.min_ambiguity_ratio * pose.score_px))
      std::snprintf(why, sizeof why, "a spot %.1f m away fits %.2fx as well",
                    (Eigen::Vector2d(elsewhere.x, elsewhere.y) - Eigen::Vector2d(pose.x, pose.y)).norm(),
                    elsewhere.score_px / pose.score_px);
    if (why[0]) {
      r.rejected.push_back({still, why});
      continue;
    }
    // The pairs with placed stills vote on the heading: turn = heading(b) - heading(a).
    int voting = 0, agreeing = 0;
    for (const StillsPair& p : pairs) {
      if (p.inliers < options.min_inliers || (p.a != still && p.b != still)) continue;
      const int other = p.a == still ? p.b : p.a;
      const PathFrame* o = out.find_frame(other);
      if (!o || !out.piece_placed(o->piece)) continue;
      const double turn = p.a == still ? o->heading * 180.0 / M_PI - pose.heading_deg
                                       : pose.heading_deg - o->heading * 180.0 / M_PI;
      ++voting;
      agreeing += std::abs(std::remainder(turn - p.turn_deg, 360.0)) <= options.turn_tolerance_deg;
    }
    if (voting == 0) {
      r.rejected.push_back({still, "no pair with a placed still confirms its heading"});
      continue;
    }
    if (2 * agreeing < voting + 1) {  // fewer than half agree
      r.rejected.push_back({still, std::to_string(agreeing) + " of " + std::to_string(voting) +
                                       " pairs agree on the heading"});
      continue;
    }
    out = path_with_still_placed(out, still, pose, points);
    r.placed.push_back({still, from, pose, elsewhere.score_px, agreeing, voting});
  }
  progress.report(1.0);
  return out;
}

}  // namespace plenopath
