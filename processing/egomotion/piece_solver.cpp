// Steps 2-5 of EgomotionTracker::finish() for one piece of the capture (egomotion.h lists them).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "processing/egomotion/egomotion_steps.h"
#include "processing/egomotion/floor_points.h"
#include "processing/egomotion/planar_two_view.h"
#include "processing/util/statistics.h"

namespace plenopath::egomotion_steps {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kFloorDepression = 25.0 * kDeg;  // floor points are seen at least this steeply (as step 4)

}  // namespace

PieceSolution solve_piece(const PiecePlan& plan, const std::vector<CaptureJoin>& joins,
                          const TrackerMeasurements& m, std::vector<PathFrame>* frames_out, std::mt19937& rng,
                          Progress& progress) {
  // The stages' shares of this piece's progress: chaining, refinement (windows, then global), resection.
  auto report = [&](const std::string& stage, double f) {
    const double begin = stage == "chaining" ? 0.0 : stage == "refinement" ? 0.2 : 0.75;
    const double end = stage == "chaining" ? 0.2 : stage == "refinement" ? 0.75 : 1.0;
    progress.checkpoint(begin + (end - begin) * f, stage);
  };
  const EgomotionOptions& opt = *m.options;
  const TrackView& view = *m.view;
  const int track_count = view.track_count();
  const std::vector<double>& heading = m.heading;
  const PlanarTwoViewOptions& two_view = m.two_view;
  const RefinementOptions& refinement = m.refinement;
  const double coarseness = m.coarseness;
  std::vector<PathFrame>& frames = *frames_out;
  const int first = plan.first, last = plan.last;
  PieceSolution result;
  auto observation = [&](int t, int frame) { return view.seen(t, frame); };
  auto bearing = [&](int t, int frame) { return view.bearing(t, frame); };
  // The joins inside this piece, by their first frame.
  std::map<int, const CaptureJoin*> join_at;
  std::set<int> join_ends;
  for (const CaptureJoin& j : joins)
    if (j.frame_a >= first && j.frame_b <= last) {
      join_at[j.frame_a] = &j;
      join_ends.insert(j.frame_b);
    }
  auto inside_join = [&](int f) {
    auto it = join_at.upper_bound(f - 1);  // first join with frame_a >= f
    if (it != join_at.begin()) {
      --it;  // the last join with frame_a < f
      return f > it->second->frame_a && f < it->second->frame_b;
    }
    return false;
  };

  // ---- 2a. keyframes (chunk cuts); both sides of a join are keyframes, the stretch between is not.
  std::vector<int> keyframes = {first};
  for (int f = first + 1; f <= last; ++f) {
    if (inside_join(f)) continue;
    const bool join_side = join_at.count(f) > 0 || join_ends.count(f) > 0;
    if (m.textureless[f] && !join_side) continue;
    const int kf = keyframes.back();
    std::vector<double> parallax;
    for (int t : view.frame_tracks(kf)) {
      if (!observation(t, f)) continue;
      const Eigen::Vector3d a = rotate_z(bearing(t, kf), heading[kf]);
      const Eigen::Vector3d b = rotate_z(bearing(t, f), heading[f]);
      parallax.push_back(std::atan2(a.cross(b).norm(), a.dot(b)));
    }
    const double shared =
        view.frame_tracks(kf).empty() ? 0.0 : double(parallax.size()) / view.frame_tracks(kf).size();
    const bool cut = median(parallax) > opt.keyframe_parallax_deg * kDeg ||
                     shared < opt.keyframe_min_shared || parallax.size() < 60 ||
                     std::abs(heading[f] - heading[kf]) > opt.keyframe_max_turn_deg * kDeg || f == last ||
                     join_side;
    if (cut) keyframes.push_back(f);
  }
  const int kfn = static_cast<int>(keyframes.size());
  result.keyframes = keyframes;
  std::map<int, int> kf_of_frame;
  for (int k = 0; k < kfn; ++k) kf_of_frame[keyframes[k]] = k;

  // ---- 2b. chain the chunks: direction by two-view RANSAC, length by resection against known points
  std::vector<Eigen::Vector3d> kf_pose(kfn, Eigen::Vector3d::Zero());
  kf_pose[0].z() = heading[keyframes[0]];
  std::vector<Eigen::Vector3d> point(static_cast<std::size_t>(track_count), Eigen::Vector3d::Zero());
  std::vector<char> point_valid(static_cast<std::size_t>(track_count), 0);
  std::vector<bool> kf_bridged(kfn, false);
  // Speeds (length per frame) rather than keyframe steps: keyframes are a varying number of frames apart,
  // and a gap bridged with the last step's length instead of the last speed shrinks (or stretches) the scale
  // of everything after it (seen: a 9-frame gap bridged with a 2-frame step left the rest of a 2 600-frame
  // walk at 0.3 of its scale).
  std::vector<double> recent_speeds;  // the last measured keyframe steps per frame
  double last_speed = 0.0, last_direction = kf_pose[0].z();
  // The directions of the last measured steps, each in its first keyframe's frame.
  std::vector<double> recent_relative_directions;
  // A point explains a bearing within this (the chaining's check against the points, and the resection).
  const double inlier_threshold = std::max(4.0 * refinement.loss_scale, 3.0 * m.pixel_angle);
  double chain_floor_level = 0.0;  // the floor's depth below the centres, chain units (0: not known yet)
  std::vector<double> chain_floor_depths;
  auto triangulate_track = [&](int t, int up_to_kf) {
    const int track_first = view.klt->first_frame(t), track_last = view.klt->last_frame(t);
    std::vector<Eigen::Vector3d> centres, dirs;
    const auto start = std::lower_bound(keyframes.begin(), keyframes.begin() + up_to_kf + 1, track_first);
    for (auto it = start; it != keyframes.begin() + up_to_kf + 1 && *it <= track_last; ++it) {
      const int k = static_cast<int>(it - keyframes.begin());
      centres.emplace_back(kf_pose[k].x(), kf_pose[k].y(), 0.0);
      dirs.push_back(rotate_z(bearing(t, *it), kf_pose[k].z()));
    }
    Eigen::Vector3d p;
    if (triangulate_rays(centres, dirs, opt.min_triangulation_deg * coarseness * kDeg, &p)) {
      point[t] = p;
      point_valid[t] = 1;
    }
  };
  for (int k = 1; k < kfn; ++k) {
    const int a = keyframes[k - 1], b = keyframes[k];
    const int gap = b - a;
    Eigen::Vector3d& pa = kf_pose[k - 1];
    Eigen::Vector3d& pb = kf_pose[k];
    double direction = last_direction, length = 0.0;
    const auto join = join_at.find(a);
    if (join != join_at.end() && join->second->frame_b == b) {
      // A stretch no track crosses, tied by descriptor matches: their verified turn and (when the baseline
      // shows it) direction; the length at the last speed, corrected by the global refinement, which sees the
      // matched points as one.
      pb.z() = pa.z() + join->second->turn;
      if (std::isfinite(join->second->direction)) direction = pa.z() + join->second->direction;
      length = (last_speed > 0 ? last_speed : 1.0 / gap) * gap;
      kf_bridged[k] = true;
    } else {
      std::vector<Eigen::Vector3d> ba, bb;
      std::vector<int> shared;
      for (int t : view.frame_tracks(a)) {
        if (!observation(t, b)) continue;
        ba.push_back(bearing(t, a));
        bb.push_back(bearing(t, b));
        shared.push_back(t);
      }
      const double turn_guess = heading[b] - heading[a];
      const double bridge_length = (last_speed > 0 ? last_speed : 1.0 / gap) * gap;  // first step: unit
      PlanarRelativePose rel = estimate_planar_relative_pose(ba, bb, turn_guess, two_view, rng);
      // The tracked turn is good to a fraction of a degree: a two-view turn far from it is a wrong solution.
      if (rel.valid && std::abs(rel.turn - turn_guess) > opt.max_step_turn_disagreement_deg * kDeg)
        rel.valid = false;
      pb.z() = pa.z() + (rel.valid ? rel.turn : turn_guess);
      // A trolley or a walker carries the camera forward: the direction of travel in the camera's frame
      // changes slowly from step to step, even round corners. A two-view direction far from the usual one
      // (the median of the last five measured) that the usual one explains nearly as well is the walkers'
      // motion, not the camera's (POV-Ray `people` at 30 cm steps: 78, 90 and 88 deg off on straight
      // steps, where the usual direction explained 72-89 % as many moving tracks).
      const double usual_direction =
          recent_relative_directions.size() >= 3 ? median(recent_relative_directions) : 0.0;
      if (rel.valid && opt.step_direction_prior_share > 0 && recent_relative_directions.size() >= 3 &&
          std::abs(std::remainder(rel.direction - usual_direction, 2 * M_PI)) >
              opt.step_map_check_deg * kDeg) {
        // Counted over the tracks that moved: the rig's still tracks fit every direction.
        std::vector<bool> explained(ba.size(), false);
        int all = 0, by_prior = 0, by_two_view = 0;
        for (std::size_t q = 0; q < ba.size(); ++q) {
          explained[q] =
              std::abs(planar_epipolar_error(ba[q], bb[q], rel.turn, usual_direction)) < two_view.threshold;
          all += explained[q];
          const Eigen::Vector3d rb = rotate_z(bb[q], rel.turn);
          if (std::atan2(ba[q].cross(rb).norm(), ba[q].dot(rb)) < two_view.min_parallax) continue;
          by_prior += explained[q];
          by_two_view +=
              std::abs(planar_epipolar_error(ba[q], bb[q], rel.turn, rel.direction)) < two_view.threshold;
        }
        if (by_prior >= two_view.min_inliers && by_prior >= opt.step_direction_prior_share * by_two_view) {
          rel.direction = usual_direction;
          rel.inlier = explained;
          rel.inliers = all;
        }
      }
      if (rel.valid) {
        direction = pa.z() + rel.direction;
        const Eigen::Vector3d t_dir(std::cos(direction), std::sin(direction), 0.0);
        // Length: each known point seen from b along d gives the lambda with a + lambda t + mu d = P.
        std::vector<double> lengths;
        for (size_t q = 0; q < shared.size(); ++q) {
          const int t = shared[q];
          if (!point_valid[t] || !rel.inlier[q]) continue;
          const Eigen::Vector3d d = rotate_z(bb[q], pb.z());
          if (t_dir.cross(d).norm() < 0.2) continue;  // near the focus of expansion: lambda ill-conditioned
          Eigen::Matrix<double, 3, 2> mat;
          mat.col(0) = t_dir;
          mat.col(1) = d;
          const Eigen::Vector3d rhs = point[t] - Eigen::Vector3d(pa.x(), pa.y(), 0.0);
          const Eigen::Vector2d lm = (mat.transpose() * mat).ldlt().solve(mat.transpose() * rhs);
          if (lm[1] > 0 && std::isfinite(lm[0])) lengths.push_back(lm[0]);
        }
        if (lengths.size() >= 8) {
          length = std::max(0.0, median(lengths));
        } else if (k == 1 || lengths.empty()) {
          length = bridge_length;
          if (k > 1) kf_bridged[k] = true;
        } else {
          length = std::max(0.0, median(lengths));
        }
        // Once the floor's level is known, the floor measures the step by itself: a floor point seen at a
        // depression e lies level / tan(e) away, from either keyframe. Unlike the points triangulated so far,
        // this does not carry the last step's error into the next, so the scale cannot decay along the walk
        // (tracks stuck on edges parallel to the walk shorten every step a little: POV-Ray corridor, 1.0 ->
        // 0.03 over 35 keyframes).
        bool from_floor = false;
        if (chain_floor_level > 0) {
          std::vector<Eigen::Vector3d> floor_a, floor_b;
          for (std::size_t q = 0; q < shared.size(); ++q)
            if (rel.inlier[q]) {
              floor_a.push_back(ba[q]);
              floor_b.push_back(bb[q]);
            }
          FloorStepInput in;
          in.bearings_a = &floor_a;
          in.bearings_b = &floor_b;
          in.heading_a = pa.z();
          in.heading_b = pb.z();
          in.level = chain_floor_level;
          in.direction = t_dir.head<2>();
          const FloorStep on_floor = floor_step(in, kFloorDepression, 3.0 * m.pixel_angle);
          // The more precise of the two (spread over the square root of the count) measures the step: where
          // the points known so far are many and agree, they do, as before.
          double known_precision = std::numeric_limits<double>::infinity();
          if (lengths.size() >= 8 && length > 0) {
            known_precision = median_absolute_deviation(lengths, length) / length /
                              std::sqrt(static_cast<double>(lengths.size()));
          }
          const double floor_precision = on_floor.spread / std::sqrt(std::max(1, on_floor.points));
          if (on_floor.points >= opt.floor_step_min_points && on_floor.length > 0 &&
              on_floor.spread < opt.floor_step_max_spread && floor_precision < known_precision) {
            length = on_floor.length;
            from_floor = true;
            ++result.steps_on_floor;
          }
        }
        // A step many times longer or shorter than the recent ones is a bad measurement (points near the
        // direction of travel, or too few), not a trolley that suddenly ran or crawled: bridge it. (Keyframes
        // are cut by parallax, so their steps stay alike; a turn on the spot is handled above.) A wrong short
        // step would also shrink every later step, which is measured against the points it placed.
        // Unless many points agree on it: frames dropped from a capture (or subsampled video) make real
        // steps many times the usual.
        double spread = 1.0;
        if (lengths.size() >= 20 && length > 0) {
          spread = median_absolute_deviation(lengths, length) / length;
        }
        const bool agreed = spread < opt.max_step_spread || from_floor;
        if (recent_speeds.size() >= 3 && !agreed) {
          const double typical = median(recent_speeds) * gap;
          if (length > opt.max_step_ratio * typical || length < typical / opt.max_step_ratio) {
            length = typical;
            kf_bridged[k] = true;
          }
        }
      } else if (rel.median_parallax < two_view.min_parallax && !ba.empty()) {
        length = 0.0;  // a turn on the spot: no translation to see
      } else {
        length = bridge_length;  // a short dropout the rings bridge (capture_pieces.cpp): at the last speed
        kf_bridged[k] = true;
      }
      // The points triangulated so far are the evidence of many frames; a two-view step is that of two. Where
      // few tracks link the keyframes (plain walls, big steps), a walker's tracks can outvote the static
      // scene's and turn the step sideways (POV-Ray `people` every 2nd frame: 77-89 deg off, on 60 inliers
      // against the truth's 45). So the step is checked against those points: resected from where the last
      // speed would carry the camera, b may be placed with far more of them than by the step measured.
      if (opt.step_map_check_factor > 0 && k > 1 && last_speed > 0) {
        std::vector<Eigen::Vector3d> known_points, known_bearings;
        for (std::size_t q = 0; q < shared.size(); ++q)
          if (point_valid[shared[q]]) {
            known_points.push_back(point[shared[q]]);
            known_bearings.push_back(bb[q]);
          }
        if (static_cast<int>(known_points.size()) >= opt.resection_min_points) {
          const Eigen::Vector2d from = pa.head<2>();
          const StepCheck check = check_step_against_points(
              from, from + length * Eigen::Vector2d(std::cos(direction), std::sin(direction)),
              from + last_speed * gap * Eigen::Vector2d(std::cos(last_direction), std::sin(last_direction)),
              pb.z(), known_points, known_bearings, refinement.loss_scale, inlier_threshold,
              opt.step_map_check_factor, opt.resection_min_points, opt.step_map_check_deg * kDeg);
          if (check.replaced) {
            const Eigen::Vector2d step = check.position - from;
            length = step.norm();
            direction = std::atan2(step.y(), step.x());
            kf_bridged[k] = false;
            ++result.steps_from_points;
          }
        }
      }
    }
    pb.x() = pa.x() + length * std::cos(direction);
    pb.y() = pa.y() + length * std::sin(direction);
    if (length > 0) {
      last_speed = length / gap;
      last_direction = direction;
      if (!kf_bridged[k]) {
        recent_relative_directions.push_back(std::remainder(direction - pa.z(), 2 * M_PI));
        if (recent_relative_directions.size() > 5)
          recent_relative_directions.erase(recent_relative_directions.begin());
        recent_speeds.push_back(length / gap);
        if (recent_speeds.size() > 9) recent_speeds.erase(recent_speeds.begin());
      }
    }
    for (int t : view.frame_tracks(b)) triangulate_track(t, k);
    // The floor's level below the camera centres, from the points seen steeply downwards by the first
    // keyframes (the camera rides at one height: RefinementOptions::floor_sigma > 0).
    if (chain_floor_level == 0 && refinement.floor_sigma > 0 && opt.floor_step_min_points > 0) {
      for (int t : view.frame_tracks(b)) {
        if (!point_valid[t]) continue;
        const Eigen::Vector3d d = point[t] - Eigen::Vector3d(pb.x(), pb.y(), 0.0);
        if (-d.z() > std::sin(kFloorDepression) * d.norm()) chain_floor_depths.push_back(-d.z());
      }
      if (chain_floor_depths.size() >= 40) chain_floor_level = floor_depth(chain_floor_depths);
    }
    if (k % 16 == 0) report("chaining", double(k) / kfn);
  }

  // Coarse pose of every frame: keyframes interpolated, headings from the tracked turns.
  auto interpolate = [&](const std::vector<Eigen::Vector3d>& kp, int f) {
    const auto it = std::upper_bound(keyframes.begin(), keyframes.end(), f);
    const int k1 = static_cast<int>(it - keyframes.begin());
    const int k0 = k1 - 1;
    if (k1 >= kfn) {
      Eigen::Vector3d p = kp[k0];
      p.z() += heading[f] - heading[keyframes[k0]];
      return p;
    }
    const double w = double(f - keyframes[k0]) / (keyframes[k1] - keyframes[k0]);
    Eigen::Vector3d p = (1 - w) * kp[k0] + w * kp[k1];
    const double off0 = kp[k0].z() - heading[keyframes[k0]], off1 = kp[k1].z() - heading[keyframes[k1]];
    p.z() = heading[f] + (1 - w) * off0 + w * off1;
    if (inside_join(f)) p.z() = (1 - w) * kp[k0].z() + w * kp[k1].z();  // no tracked turns in there
    return p;
  };
  const int count = last - first + 1;
  std::vector<Eigen::Vector3d> coarse(count);
  for (int f = first; f <= last; ++f) coarse[f - first] = interpolate(kf_pose, f);

  // ---- 3. refinement of keyframes and points
  BundleProblem problem;
  problem.poses = kf_pose;
  std::vector<int> point_of_track(static_cast<std::size_t>(track_count), -1);
  {
    // Reserved up front (an upper bound: the keyframes within each track's span): a long capture's tens of
    // millions of observations must not be copied as the vector doubles.
    std::size_t observations = 0, points = 0;
    for (int t = 0; t < track_count; ++t) {
      const int track_first = view.klt->first_frame(t), track_last = view.klt->last_frame(t);
      if (track_last < first || track_first > last) continue;
      const auto a = std::lower_bound(keyframes.begin(), keyframes.end(), track_first);
      const auto b = std::upper_bound(keyframes.begin(), keyframes.end(), track_last);
      if (b - a < opt.min_point_keyframes) continue;
      observations += static_cast<std::size_t>(b - a);
      ++points;
    }
    problem.observations.reserve(observations);
    problem.points.reserve(points);
  }
  for (int t = 0; t < track_count; ++t) {
    // The tracks seen in this piece (in increasing order, as a set of them would be).
    const int track_first = view.klt->first_frame(t), track_last = view.klt->last_frame(t);
    if (track_last < first || track_first > last) continue;
    triangulate_track(t, kfn - 1);
    if (!point_valid[t]) continue;
    std::vector<BundleObservation> obs;
    for (auto it = std::lower_bound(keyframes.begin(), keyframes.end(), track_first);
         it != keyframes.end() && *it <= track_last; ++it) {
      const int k = static_cast<int>(it - keyframes.begin());
      const Eigen::Vector3d b = bearing(t, *it);
      // A tilted camera's bearings are off the planar model by up to its tilt until the refinement knows it.
      if (ray_error(kf_pose[k], point[t], b) >
          (opt.max_initial_error_deg * coarseness + refinement.tilt_prior_deg) * kDeg)
        continue;
      obs.push_back({k, static_cast<int>(problem.points.size()), b});
    }
    if (static_cast<int>(obs.size()) < opt.min_point_keyframes) continue;
    point_of_track[t] = static_cast<int>(problem.points.size());
    problem.points.push_back(point[t]);
    problem.observations.insert(problem.observations.end(), obs.begin(), obs.end());
  }
  if (refinement.floor_sigma > 0) problem.floor_points = find_floor_points(problem);
  result.points = static_cast<int>(problem.points.size());
  result.observations = static_cast<int>(problem.observations.size());
  report("refinement", 0.0);
  // Windows first; then the places the walk came back to (and the joins) are tied together, and one global
  // pass removes the drift in between.
  RefinementOptions windowed = refinement, global = refinement;
  windowed.global_max_iterations = 0;
  global.window_keyframes = 0;
  SubProgress windows_progress(progress, 0.2, 0.475, "refinement");
  const RefinementReport windows = refine_bundle(problem, windowed, windows_progress);
  {
    std::vector<double> kf_travelled(kfn, 0.0);
    for (int k = 1; k < kfn; ++k)
      kf_travelled[k] =
          kf_travelled[k - 1] + (problem.poses[k].head<2>() - problem.poses[k - 1].head<2>()).norm();
    std::vector<double> steps;
    for (int k = 1; k < kfn; ++k) steps.push_back(kf_travelled[k] - kf_travelled[k - 1]);
    const std::vector<Eigen::Vector3d> kf_now = problem.poses;
    progress.checkpoint(0.475, "loop closure");
    std::vector<LoopMatch> loops = find_loop_closures(
        *m.described, first, last, [&](int f) { return interpolate(kf_now, f); },
        [&](int f) {
          const int k1 =
              static_cast<int>(std::upper_bound(keyframes.begin(), keyframes.end(), f) - keyframes.begin());
          if (k1 >= kfn) return kf_travelled.back();
          const int k0 = k1 - 1;
          const double w = double(f - keyframes[k0]) / (keyframes[k1] - keyframes[k0]);
          return (1 - w) * kf_travelled[k0] + w * kf_travelled[k1];
        },
        bearing, median(steps), two_view, opt.loop, rng);
    for (const LoopMatch& l : loops) result.loop_frames.emplace_back(l.frame_a, l.frame_b);
    for (const auto& [frame, j] : join_at) {
      LoopMatch tie;
      tie.frame_a = j->frame_a;
      tie.frame_b = j->frame_b;
      tie.turn = j->turn;
      tie.track_pairs = j->track_pairs;
      loops.push_back(std::move(tie));
    }
    result.merged_points = merge_loop_points(loops, &problem, &point_of_track);
  }
  SubProgress global_progress(progress, 0.475, 0.75, "global refinement");
  const RefinementReport global_report = refine_bundle(problem, global, global_progress);
  result.refinement = global_report;
  result.refinement.initial_rms = windows.initial_rms;
  result.refinement.windows = windows.windows;
  result.refinement.iterations += windows.iterations;
  const std::vector<Eigen::Vector3d> refined_kf = problem.poses;

  // ---- every frame against the refined points
  std::vector<double> kf_steps;
  for (int k = 1; k < kfn; ++k)
    kf_steps.push_back((refined_kf[k].head<2>() - refined_kf[k - 1].head<2>()).norm());
  const double typical_kf_step = median(kf_steps);  // turns on the spot have none: bounds need a floor
  // Points the refinement dropped (every observation an outlier) keep their coarse positions: resecting
  // against them pulls a frame towards the coarse chain.
  std::vector<char> point_alive(problem.points.size(), 0);
  for (const auto& o : problem.observations) point_alive[o.point] = 1;
  // Tilts (when the refinement estimated them): keyframes' as refined, other frames resected with five
  // degrees of freedom from their keyframes' interpolated tilt.
  const bool tilted = !problem.tilts.empty();
  const double tilt_weight = tilted ? refinement.loss_scale / (refinement.tilt_prior_deg * kDeg) : 0.0;
  auto interpolated_tilt = [&](int f) -> Eigen::Vector2d {
    const int k1 =
        static_cast<int>(std::upper_bound(keyframes.begin(), keyframes.end(), f) - keyframes.begin());
    if (k1 >= kfn) return problem.tilts[kfn - 1];
    const int k0 = std::max(0, k1 - 1);
    const double w =
        keyframes[k1] > keyframes[k0] ? double(f - keyframes[k0]) / (keyframes[k1] - keyframes[k0]) : 0.0;
    return (1 - w) * problem.tilts[k0] + w * problem.tilts[k1];
  };
  std::vector<Eigen::Vector3d> pose(count);
  for (int f = first; f <= last; ++f) {
    Eigen::Vector3d& pf = pose[f - first];
    pf = interpolate(refined_kf, f);
    std::vector<Eigen::Vector3d> pts, brs;
    for (int t : view.frame_tracks(f)) {
      if (point_of_track[t] < 0) continue;
      if (!point_alive[point_of_track[t]]) continue;
      pts.push_back(problem.points[point_of_track[t]]);
      brs.push_back(bearing(t, f));
    }
    const auto kf = kf_of_frame.find(f);
    if (kf != kf_of_frame.end()) {
      pf = refined_kf[kf->second];
    } else if (inside_join(f)) {
      add_flag(frames[f], kFrameBridged,
               "bridged: no track crosses this stretch (its two sides matched by descriptors)");
    } else if (static_cast<int>(pts.size()) >= opt.resection_min_points) {
      Eigen::Vector3d p = pf;
      Eigen::Vector2d tilt = tilted ? interpolated_tilt(f) : Eigen::Vector2d::Zero();
      const int inliers = tilted ? resect_tilted_pose(&p, &tilt, pts, brs, refinement.loss_scale,
                                                      inlier_threshold, tilt_weight)
                                 : resect_pose(&p, pts, brs, refinement.loss_scale, inlier_threshold);
      // The frame lies between its keyframes: a resection that lands farther from the interpolated pose
      // than the keyframe step (or turns more than the tracked turn allows) has slipped.
      const int k1 =
          static_cast<int>(std::upper_bound(keyframes.begin(), keyframes.end(), f) - keyframes.begin());
      const int k0 = std::max(0, k1 - 1);
      const double kf_step =
          k1 < kfn ? (refined_kf[k1].head<2>() - refined_kf[k0].head<2>()).norm()
                   : (k0 > 0 ? (refined_kf[k0].head<2>() - refined_kf[k0 - 1].head<2>()).norm() : 0.0);
      const bool slipped = (p.head<2>() - pf.head<2>()).norm() > std::max(kf_step, 0.5 * typical_kf_step) ||
                           std::abs(p.z() - pf.z()) > opt.max_step_turn_disagreement_deg * kDeg;
      if (slipped) {
        add_flag(frames[f], kFrameBridged, "bridged: the frame's points place it away from its keyframes");
      } else if (inliers >= opt.resection_min_points) {
        pf = p;
      } else {
        add_flag(frames[f], kFrameBridged, "bridged: too few consistent points to place the frame");
      }
    } else {
      add_flag(frames[f], kFrameBridged, "bridged: too few tracked points to place the frame");
    }
    if (m.moving_share[f] >= 0) {
      if (m.moving_share[f] > opt.moving_outlier_fraction)
        add_flag(frames[f], kFrameMovingObjects,
                 "moving objects: " + std::to_string(int(std::round(100 * m.moving_share[f]))) +
                     "% of tracks move against the static scene");
      frames[f].confidence = 1.0 - m.moving_share[f];
    }
    if ((f - first) % 64 == 0) report("resection", double(f - first) / count);
  }
  for (int k = 1; k < kfn; ++k) {
    if (!kf_bridged[k] || join_at.count(keyframes[k - 1])) continue;
    for (int f = keyframes[k - 1] + 1; f <= keyframes[k]; ++f)
      add_flag(frames[f], kFrameBridged, "bridged: the step into this chunk could not be measured");
  }

  // ---- 4. metric scale
  double scale = 0.0;
  if (opt.camera_height_m > 0) {
    scale = scale_from_camera_height(problem, opt.camera_height_m, &result.floor_points);
    if (scale > 0) result.scale_source = "camera_height";
  }
  if (scale == 0 && opt.scale_distance_m > 0 && opt.scale_frame_a >= first && opt.scale_frame_a <= last &&
      opt.scale_frame_b >= first && opt.scale_frame_b <= last) {
    const double d =
        (pose[opt.scale_frame_a - first].head<2>() - pose[opt.scale_frame_b - first].head<2>()).norm();
    if (d > 0) {
      scale = opt.scale_distance_m / d;
      result.scale_source = "distance";
    }
  }
  if (scale == 0) {
    // Unit: the first keyframe step.
    const double d = kfn > 1 ? (refined_kf[1].head<2>() - refined_kf[0].head<2>()).norm() : 0.0;
    scale = d > 0 ? 1.0 / d : 1.0;
    result.scale_source = "relative";
  }
  result.scale_factor = scale;

  // ---- jumps: a step far longer than its neighbours'
  std::vector<double> steps(count, 0.0);
  for (int i = 1; i < count; ++i) steps[i] = (pose[i].head<2>() - pose[i - 1].head<2>()).norm();
  const double typical_step =
      median(std::vector<double>(steps.begin() + std::min(1, count - 1), steps.end()));
  for (int i = 1; i < count; ++i) {
    std::vector<double> local;
    for (int g = std::max(1, i - 10); g <= std::min(count - 1, i + 10); ++g)
      if (g != i) local.push_back(steps[g]);
    const double mm = std::max(median(local), 0.25 * typical_step);  // a turn on the spot: steps near 0
    if (mm > 0 && steps[i] > opt.jump_factor * mm)
      add_flag(frames[first + i], kFrameJump, "jump: the step is much longer than its neighbours'");
  }

  // ---- own gauge: the piece's first frame at the origin with heading 0, metric
  auto gauge = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& origin) {
    const Eigen::Vector3d d(p.x() - origin.x(), p.y() - origin.y(), 0.0);
    const Eigen::Vector3d r = rotate_z(d, -origin.z()) * scale;
    return Eigen::Vector3d(r.x(), r.y(), p.z() - origin.z());
  };
  result.poses.resize(count);
  result.coarse.resize(count);
  for (int i = 0; i < count; ++i) {
    result.poses[i] = gauge(pose[i], pose[0]);
    result.coarse[i] = gauge(coarse[i], coarse[0]);
  }
  // ... and the refined points with it (the same gauge as the poses, z scaled alike: floor at -h).
  // Each point tied to the middle of the keyframes that saw it (the plan refinement moves it with that pose).
  // (The observations sorted by point, then pose, in place: the problem is not needed any more, and lists
  // per point would cost a hundred bytes for each of a long capture's millions of points.)
  std::vector<BundleObservation>& obs = problem.observations;
  std::sort(obs.begin(), obs.end(), [](const BundleObservation& a, const BundleObservation& b) {
    return a.point != b.point ? a.point < b.point : a.pose < b.pose;
  });
  result.tracked_points.reserve(problem.points.size());
  for (std::size_t k = 0; k < obs.size();) {
    std::size_t e = k + 1;
    while (e < obs.size() && obs[e].point == obs[k].point) ++e;
    const Eigen::Vector3d& q = problem.points[static_cast<std::size_t>(obs[k].point)];
    PathPoint p;
    p.position =
        rotate_z(Eigen::Vector3d(q.x() - pose[0].x(), q.y() - pose[0].y(), q.z()), -pose[0].z()) * scale;
    p.observations = static_cast<int>(e - k);
    p.frame = frames[keyframes[obs[k + (e - k) / 2].pose]].index;
    result.tracked_points.push_back(p);
    k = e;
  }
  report("resection", 1.0);
  return result;
}

}  // namespace plenopath::egomotion_steps
