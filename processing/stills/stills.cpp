#include "processing/stills/stills.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <opencv2/flann.hpp>
#include <random>
#include <sstream>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/stills/edge_lengths.h"
#include "processing/stills/floor_scale.h"
#include "processing/util/parallel_for.h"

namespace plenopath {

void StillsOptions::check() const {
  features.check();
  two_view.check();
  headings.check();
  refinement.check();
  const std::string s = "StillsOptions.";
  require_option(match_ratio > 0 && match_ratio <= 1, s + "match_ratio", "must be in (0, 1]", match_ratio);
  require_option(min_pair_inliers >= two_view.min_inliers, s + "min_pair_inliers",
                 "must be >= two_view.min_inliers", min_pair_inliers);
  require_option(min_pair_coverage_deg >= 0 && min_pair_coverage_deg <= 360, s + "min_pair_coverage_deg",
                 "must be in [0, 360]", min_pair_coverage_deg);
  require_option(consecutive_min_inliers >= two_view.min_inliers, s + "consecutive_min_inliers",
                 "must be >= two_view.min_inliers", consecutive_min_inliers);
  require_option(consecutive_min_coverage_deg >= 0 && consecutive_min_coverage_deg <= 360,
                 s + "consecutive_min_coverage_deg", "must be in [0, 360]", consecutive_min_coverage_deg);
  require_option(min_direction_parallax_deg >= 0, s + "min_direction_parallax_deg", "must be >= 0",
                 min_direction_parallax_deg);
  require_option(max_direction_residual_deg > 0, s + "max_direction_residual_deg", "must be > 0",
                 max_direction_residual_deg);
  require_option(max_length_residual > 0, s + "max_length_residual", "must be > 0", max_length_residual);
  require_option(camera_height_m > 0, s + "camera_height_m", "must be > 0", camera_height_m);
  require_option(min_floor_points >= 3, s + "min_floor_points", "must be >= 3", min_floor_points);
}

namespace {

constexpr double kDeg = M_PI / 180.0;
using Clock = std::chrono::steady_clock;

// For each row of `query`: the nearest row of the indexed set when it passes the ratio test, else -1.
std::vector<int> nearest_passing_ratio(cv::flann::Index& index, const cv::Mat& query, double ratio) {
  std::vector<int> out(static_cast<std::size_t>(query.rows), -1);
  if (query.rows == 0) return out;
  cv::Mat indices, distances;
  index.knnSearch(query, indices, distances, 2, cv::flann::SearchParams(64));
  const float r2 = static_cast<float>(ratio * ratio);  // squared L2 distances
  for (int i = 0; i < query.rows; ++i)
    if (distances.at<float>(i, 0) < r2 * distances.at<float>(i, 1))
      out[static_cast<std::size_t>(i)] = indices.at<int>(i, 0);
  return out;
}

Eigen::Vector3d move_pose(const Eigen::Vector3d& pose, const Eigen::Vector3d& origin) {
  // pose in the frame whose origin is `origin` (x, y, heading).
  const double c = std::cos(origin.z()), s = std::sin(origin.z());
  const double dx = pose.x() - origin.x(), dy = pose.y() - origin.y();
  return {c * dx + s * dy, -s * dx + c * dy, wrap_angle(pose.z() - origin.z())};
}

std::string list_stills(const std::vector<int>& stills) {
  std::ostringstream s;
  for (std::size_t k = 0; k < stills.size(); ++k) {
    if (k == 8) {
      s << ", ...";
      break;
    }
    s << (k ? ", " : "") << stills[k];
  }
  return s.str();
}

struct GroupSolution {
  std::vector<Eigen::Vector3d> poses;  // per still (only the group's are meaningful)
  StillsBundle bundle;
  std::string scale_source = "relative";
  double scale_factor = 1.0;
  int floor_points = 0;
  bool solved = false;
};

}  // namespace

StillsResult solve_stills(int count, const std::function<cv::Mat(int)>& read, const StillsOptions& options,
                          Progress& progress) {
  options.check();
  if (count < 1) throw Error("stills: no stills to solve");
  const Clock::time_point start = Clock::now();
  StillsResult result;

  // 1. Features.
  std::vector<SphereFeatures> features(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    progress.checkpoint(0.3 * i / count,
                        "features: still " + std::to_string(i + 1) + " of " + std::to_string(count));
    const cv::Mat image = read(i);
    try {
      features[static_cast<std::size_t>(i)] = detect_sphere_features(image, options.features);
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      throw Error("stills: still " + std::to_string(i) + ": " + e.what());
    }
    result.features.push_back(static_cast<int>(features[static_cast<std::size_t>(i)].keypoints.size()));
  }
  std::vector<std::unique_ptr<cv::flann::Index>> index(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i)
    if (features[static_cast<std::size_t>(i)].descriptors.rows >= 2)
      index[static_cast<std::size_t>(i)] = std::make_unique<cv::flann::Index>(
          features[static_cast<std::size_t>(i)].descriptors, cv::flann::KDTreeIndexParams(4));

  // 2. Every pair: matches, then planar two-view verification.
  std::vector<std::vector<int>> best(static_cast<std::size_t>(count) * static_cast<std::size_t>(count));
  auto nearest = [&](int from, int to) -> std::vector<int>& {
    return best[static_cast<std::size_t>(from * count + to)];
  };
  for (int a = 0; a < count; ++a) {
    progress.checkpoint(0.3 + 0.2 * a / count,
                        "matching: still " + std::to_string(a + 1) + " of " + std::to_string(count));
    for (int b = 0; b < count; ++b)
      if (a != b && index[static_cast<std::size_t>(b)])
        nearest(a, b) =
            nearest_passing_ratio(*index[static_cast<std::size_t>(b)],
                                  features[static_cast<std::size_t>(a)].descriptors, options.match_ratio);
  }
  struct PairWork {
    StillsPair report;
    std::vector<std::pair<int, int>> inlier_features;
    std::vector<double> depth_a, depth_b;  // unit-baseline depths of the inliers (edge_lengths.h)
  };
  std::vector<std::pair<int, int>> pair_list;
  for (int a = 0; a < count; ++a)
    for (int b = a + 1; b < count; ++b) pair_list.push_back({a, b});
  std::vector<PairWork> work(pair_list.size());
  std::mutex progress_mutex;
  int pairs_done = 0;
  parallel_for_each(static_cast<int>(pair_list.size()), 0, [&](int p) {
    const auto [a, b] = pair_list[static_cast<std::size_t>(p)];
    PairWork& w = work[static_cast<std::size_t>(p)];
    w.report.a = a;
    w.report.b = b;
    const std::vector<int>& ab = nearest(a, b);
    const std::vector<int>& ba = nearest(b, a);
    std::vector<std::pair<int, int>> matches;
    for (std::size_t i = 0; i < ab.size(); ++i) {
      const int j = ab[i];
      // Mutual: b's feature j passes the ratio test too, and its nearest is i.
      if (j >= 0 && static_cast<std::size_t>(j) < ba.size() &&
          ba[static_cast<std::size_t>(j)] == static_cast<int>(i))
        matches.push_back({static_cast<int>(i), j});
    }
    w.report.matches = static_cast<int>(matches.size());
    if (static_cast<int>(matches.size()) >= options.two_view.min_inliers) {
      std::vector<Eigen::Vector3d> ba_bearings, bb_bearings;
      for (const auto& [i, j] : matches) {
        ba_bearings.push_back(features[static_cast<std::size_t>(a)].bearings[static_cast<std::size_t>(i)]);
        bb_bearings.push_back(features[static_cast<std::size_t>(b)].bearings[static_cast<std::size_t>(j)]);
      }
      std::mt19937 rng(options.seed + static_cast<std::uint32_t>(a * count + b));
      const PlanarPoseEstimate e = estimate_planar_pose(ba_bearings, bb_bearings, options.two_view, rng);
      if (e.valid) {
        w.report.inliers = e.inliers;
        w.report.turn_deg = e.motion.turn / kDeg;
        w.report.direction_deg = e.motion.direction / kDeg;
        w.report.rms_error_deg = e.rms_error_deg;
        w.report.median_parallax_deg = e.median_parallax_deg;

        // How much of the horizon the verified matches cover, in each view: 10 deg bins holding at least 3
        // of them (a few stray inliers do not widen a match on one piece of furniture).
        std::vector<int> bins_a(36, 0), bins_b(36, 0);
        auto bin = [](const Eigen::Vector3d& v) {
          const double azimuth = std::atan2(-v.y(), v.x());
          return static_cast<std::size_t>(
              std::clamp(static_cast<int>((azimuth + M_PI) / (2 * M_PI) * 36), 0, 35));
        };
        for (std::size_t k = 0; k < matches.size(); ++k) {
          if (!e.inlier[k]) continue;
          ++bins_a[bin(ba_bearings[k])];
          ++bins_b[bin(bb_bearings[k])];
        }
        auto covered = [](const std::vector<int>& bins) {
          return 10.0 *
                 static_cast<double>(std::count_if(bins.begin(), bins.end(), [](int c) { return c >= 3; }));
        };
        w.report.coverage_deg = std::min(covered(bins_a), covered(bins_b));
        const bool strong =
            e.inliers >= options.min_pair_inliers && w.report.coverage_deg >= options.min_pair_coverage_deg;
        const bool weak = b == a + 1 && e.inliers >= options.consecutive_min_inliers &&
                          w.report.coverage_deg >= options.consecutive_min_coverage_deg &&
                          e.median_parallax_deg >= options.min_direction_parallax_deg;
        w.report.edge = strong || weak;
        std::vector<Eigen::Vector3d> ia, ib;
        for (std::size_t k = 0; k < matches.size(); ++k)
          if (e.inlier[k]) {
            w.inlier_features.push_back(matches[k]);
            ia.push_back(ba_bearings[k]);
            ib.push_back(bb_bearings[k]);
          }
        if (w.report.edge && e.median_parallax_deg >= options.min_direction_parallax_deg)
          triangulate_unit_baseline(ia, ib, e.motion.turn, e.motion.direction, 2.0, &w.depth_a, &w.depth_b);
        if (w.report.edge && e.median_parallax_deg >= options.min_direction_parallax_deg)
          w.report.length_m =
              baseline_from_floor(ia, ib, e.motion.turn, e.motion.direction, options.camera_height_m,
                                  options.min_floor_points, 2.0, &w.report.floor_points);
        // A consecutive pair let in on less evidence must bring its own length (its floor): in a chain of
        // such pairs nothing else would fix how far apart they are, and the group would fail as a whole.
        if (!strong && !(w.report.length_m > 0)) w.report.edge = false;
      }
    }
    std::lock_guard<std::mutex> lock(progress_mutex);
    ++pairs_done;
    progress.report(
        0.5 + 0.2 * pairs_done / static_cast<double>(pair_list.size()),
        "matching: pair " + std::to_string(pairs_done) + " of " + std::to_string(pair_list.size()));
  });
  progress.throw_if_cancelled();

  std::vector<ViewEdge> edges;
  std::vector<std::size_t> edge_pair;  // edge -> work index
  std::vector<PairMatches> pair_matches;
  for (std::size_t p = 0; p < work.size(); ++p) {
    const StillsPair& r = work[p].report;
    if (!r.edge) continue;
    ViewEdge e;
    e.a = r.a;
    e.b = r.b;
    e.turn = r.turn_deg * kDeg;
    e.direction = r.direction_deg * kDeg;
    e.weight = r.inliers;
    e.length = r.length_m;
    e.direction_known = r.median_parallax_deg >= options.min_direction_parallax_deg;
    edges.push_back(e);
    edge_pair.push_back(p);
    pair_matches.push_back({r.a, r.b, work[p].inlier_features});
  }

  // 3. Headings per group; the edges they disagree with are dropped, and the groups found again.
  progress.checkpoint(0.7, "graph");
  std::vector<bool> kept(edges.size(), false);
  for (const std::vector<int>& group : connected_groups(count, edges)) {
    if (group.size() < 2) continue;
    std::vector<bool> kept_here;
    average_headings(count, group, edges, options.headings, &kept_here);
    for (std::size_t e = 0; e < edges.size(); ++e)
      if (kept_here[e]) kept[e] = true;
  }
  std::vector<ViewEdge> kept_edges;
  std::vector<PairMatches> kept_matches;
  std::vector<std::size_t> kept_work;  // kept edge -> work index
  for (std::size_t e = 0; e < edges.size(); ++e) {
    work[edge_pair[e]].report.kept = kept[e];
    if (!kept[e]) continue;
    kept_edges.push_back(edges[e]);
    kept_work.push_back(edge_pair[e]);
    kept_matches.push_back(pair_matches[e]);
  }
  std::vector<std::vector<int>> groups = connected_groups(count, kept_edges);

  // Positions and refinement per group.
  std::vector<int> group_of(static_cast<std::size_t>(count), -1);
  std::vector<GroupSolution> solutions(groups.size());
  std::vector<std::pair<int, int>> dropped_by_positions;
  bool any_refined = false;
  const double steep = std::sin(kFloorSteepnessDeg * kDeg);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::vector<int>& group = groups[g];
    GroupSolution& s = solutions[g];
    s.poses.assign(static_cast<std::size_t>(count), Eigen::Vector3d::Zero());
    if (group.size() < 2) continue;
    std::vector<bool> kept_here;
    const std::vector<double> headings =
        average_headings(count, group, kept_edges, options.headings, &kept_here);
    // Lengths: the floor's, and the ratios of edges that triangulate the same features (edge_lengths.h).
    std::vector<ViewEdge> group_edges = kept_edges;
    std::vector<EdgeDepths> edge_depths;
    std::vector<std::size_t> depth_edge;
    for (std::size_t e = 0; e < kept_edges.size(); ++e) {
      group_edges[e].length = 0.0;
      if (!kept_here[e] || !kept_edges[e].direction_known) continue;
      const PairWork& w = work[kept_work[e]];
      EdgeDepths d;
      d.a = kept_edges[e].a;
      d.b = kept_edges[e].b;
      d.features = w.inlier_features;
      d.depth_a = w.depth_a;
      d.depth_b = w.depth_b;
      d.metric_length = w.report.length_m;
      d.metric_weight = w.report.floor_points;
      edge_depths.push_back(std::move(d));
      depth_edge.push_back(e);
    }
    const EdgeLengths lengths = solve_edge_lengths(count, edge_depths);
    for (std::size_t k = 0; k < depth_edge.size(); ++k) group_edges[depth_edge[k]].length = lengths.length[k];
    std::vector<Eigen::Vector2d> positions;
    bool scale_known = false;
    if (!solve_positions_robust(count, group, group_edges, &kept_here, headings,
                                options.max_direction_residual_deg, options.max_length_residual, &positions,
                                &scale_known))
      continue;
    scale_known = scale_known && lengths.metric;
    for (std::size_t e = 0; e < kept_edges.size(); ++e)
      if (!kept_here[e] && kept_edges[e].a >= 0) {
        const int a = kept_edges[e].a, b = kept_edges[e].b;
        if (std::find(group.begin(), group.end(), a) != group.end() &&
            std::find(group.begin(), group.end(), b) != group.end())
          dropped_by_positions.push_back({a, b});
      }
    for (int i : group)
      s.poses[static_cast<std::size_t>(i)] =
          Eigen::Vector3d(positions[static_cast<std::size_t>(i)].x(),
                          positions[static_cast<std::size_t>(i)].y(), headings[static_cast<std::size_t>(i)]);
    std::vector<std::vector<Eigen::Vector3d>> bearings(static_cast<std::size_t>(count));
    for (int i : group)
      bearings[static_cast<std::size_t>(i)] = features[static_cast<std::size_t>(i)].bearings;
    std::vector<PairMatches> group_matches;
    for (std::size_t e = 0; e < kept_edges.size(); ++e)
      if (kept_here[e]) group_matches.push_back(kept_matches[e]);
    s.bundle = build_stills_bundle(bearings, group_matches, group, s.poses, options.refinement);
    SubProgress refine_progress(progress, 0.7 + 0.3 * g / groups.size(), 0.7 + 0.3 * (g + 1) / groups.size(),
                                "refinement");
    const StillsRefinementReport report =
        refine_stills(&s.bundle, group, options.refinement, refine_progress);
    result.refinement.points += report.points;
    result.refinement.observations += report.observations;
    result.refinement.dropped_observations += report.dropped_observations;
    result.refinement.iterations += report.iterations;
    if (!any_refined) {  // the largest solved group's figures
      any_refined = true;
      result.refinement.initial_rms_deg = report.initial_rms_deg;
      result.refinement.final_rms_deg = report.final_rms_deg;
    }
    s.poses = s.bundle.poses;
    // 4. Scale: the floor among the refined points, seen steeply from the still that saw them first.
    std::vector<int> first_view(s.bundle.points.size(), -1);
    for (const StillObservation& o : s.bundle.observations)
      if (first_view[static_cast<std::size_t>(o.point)] < 0)
        first_view[static_cast<std::size_t>(o.point)] = o.still;
    std::vector<double> depths;
    for (std::size_t q = 0; q < s.bundle.points.size(); ++q) {
      if (first_view[q] < 0) continue;
      const Eigen::Vector3d& c = s.poses[static_cast<std::size_t>(first_view[q])];
      const Eigen::Vector3d d = s.bundle.points[q] - Eigen::Vector3d(c.x(), c.y(), 0.0);
      if (d.z() < -steep * d.norm()) depths.push_back(-s.bundle.points[q].z());
    }
    const FloorLevel floor = floor_level(depths, options.min_floor_points);
    if (floor.depth > 0) {
      s.scale_factor = options.camera_height_m / floor.depth;
      s.scale_source = "camera_height";
      s.floor_points = floor.points;
    } else if (scale_known) {
      s.scale_source = "camera_height";  // the pairs' own floors, carried by the lengths
    }
    for (int i : group) s.poses[static_cast<std::size_t>(i)].head<2>() *= s.scale_factor;
    for (Eigen::Vector3d& p : s.bundle.points) p *= s.scale_factor;
    s.solved = true;
    for (int i : group) group_of[static_cast<std::size_t>(i)] = static_cast<int>(g);
  }
  // Groups whose positions could not be fixed: their stills count as unconnected.
  std::vector<std::vector<int>> final_groups;
  std::vector<int> final_of_group(groups.size(), -1);
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (solutions[g].solved) {
      final_of_group[g] = static_cast<int>(final_groups.size());
      final_groups.push_back(groups[g]);
    }
  for (int i = 0; i < count; ++i)
    if (group_of[static_cast<std::size_t>(i)] < 0) {
      result.unconnected.push_back(i);
      final_groups.push_back({i});
    }
  result.groups = final_groups;

  // 5. The path in pieces: runs of consecutive stills of one group.
  int largest = -1;  // the largest solved group (groups are sorted by size)
  for (std::size_t g = 0; g < solutions.size() && largest < 0; ++g)
    if (solutions[g].solved) largest = static_cast<int>(g);
  auto group_index = [&](int still) { return group_of[static_cast<std::size_t>(still)]; };
  std::vector<int> piece_of(static_cast<std::size_t>(count), 0);
  std::vector<Eigen::Vector3d> piece_origin;
  for (int i = 0; i < count; ++i) {
    const int g = group_index(i);
    const bool starts = i == 0 || g < 0 || g != group_index(i - 1);
    if (starts) {
      PathPiece piece;
      piece.first_index = piece.last_index = i;
      const GroupSolution* s = g >= 0 ? &solutions[static_cast<std::size_t>(g)] : nullptr;
      piece.placed = (g >= 0 && g == largest) || count == 1;
      piece.scale_source = s ? s->scale_source : "none";
      piece.scale_factor = s ? s->scale_factor : 1.0;
      if (g < 0) {
        piece.break_reason = "still " + std::to_string(i) + " connects to no other still";
      } else if (i > 0) {
        const std::vector<int>& members =
            final_groups[static_cast<std::size_t>(final_of_group[static_cast<std::size_t>(g)])];
        piece.break_reason = "still " + std::to_string(i) + " does not connect to still " +
                             std::to_string(i - 1) + "; it is in group " +
                             std::to_string(final_of_group[static_cast<std::size_t>(g)]) + " (stills " +
                             list_stills(members) + ")" + (g == largest ? ", the placed one" : "");
      }
      result.path.pieces.push_back(piece);
      piece_origin.push_back(piece.placed || !s ? Eigen::Vector3d::Zero()
                                                : s->poses[static_cast<std::size_t>(i)]);
    }
    result.path.pieces.back().last_index = i;
    piece_of[static_cast<std::size_t>(i)] = static_cast<int>(result.path.pieces.size()) - 1;
    const int k = piece_of[static_cast<std::size_t>(i)];
    PathFrame f;
    f.index = i;
    f.piece = k;
    if (g >= 0) {
      const Eigen::Vector3d pose =
          move_pose(solutions[static_cast<std::size_t>(g)].poses[static_cast<std::size_t>(i)],
                    piece_origin[static_cast<std::size_t>(k)]);
      f.x = pose.x();
      f.y = pose.y();
      f.heading = pose.z();
    } else {
      f.reason = "connects to no other still";
      f.confidence = 0.0;
    }
    if (starts && i > 0) f.flags |= kFramePieceStart;
    result.path.frames.push_back(f);
  }
  if (result.path.pieces.size() == 1) {
    result.path.scale_source = result.path.pieces[0].scale_source;
    result.path.pieces.clear();  // one placed piece: the plain path
  }
  if (largest >= 0) {
    const GroupSolution& placed = solutions[static_cast<std::size_t>(largest)];
    result.scale_source = placed.scale_source;
    result.scale_factor = placed.scale_factor;
    result.floor_points = placed.floor_points;
  } else {
    result.scale_source = "none";
  }
  if (result.path.scale_source.empty()) result.path.scale_source = result.scale_source;
  // Points: each in the piece of the first still that saw it.
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const GroupSolution& s = solutions[g];
    if (!s.solved) continue;
    std::vector<int> first_view(s.bundle.points.size(), -1), views(s.bundle.points.size(), 0);
    for (const StillObservation& o : s.bundle.observations) {
      int& f = first_view[static_cast<std::size_t>(o.point)];
      if (f < 0 || o.still < f) f = o.still;
      ++views[static_cast<std::size_t>(o.point)];
    }
    for (std::size_t q = 0; q < s.bundle.points.size(); ++q) {
      if (first_view[q] < 0) continue;
      const int k = piece_of[static_cast<std::size_t>(first_view[q])];
      const Eigen::Vector3d& o = piece_origin[static_cast<std::size_t>(k)];
      const Eigen::Vector3d moved =
          move_pose(Eigen::Vector3d(s.bundle.points[q].x(), s.bundle.points[q].y(), 0.0), o);
      PathPoint p;
      p.position = Eigen::Vector3d(moved.x(), moved.y(), s.bundle.points[q].z());
      p.piece = result.path.pieces.empty() ? 0 : k;
      p.observations = views[q];
      p.frame = first_view[q];
      result.points.push_back(p);
    }
  }
  for (PairWork& w : work) {
    for (const auto& [a, b] : dropped_by_positions)
      if (w.report.a == a && w.report.b == b) w.report.kept = false;
    if (w.report.matches > 0) result.pairs.push_back(w.report);
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  progress.report(1.0, "done");
  return result;
}

}  // namespace plenopath
