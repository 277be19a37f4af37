#include "processing/anchors/anchor_refinement.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "model/error.h"
#include "processing/anchors/pose_graph_costs.h"

namespace plenopath {
namespace {
using namespace pose_graph;

std::size_t position_of(const CameraPath& path, int frame) {
  auto it = std::lower_bound(path.frames.begin(), path.frames.end(), frame,
                             [](const PathFrame& f, int i) { return f.index < i; });
  if (it == path.frames.end() || it->index != frame)
    throw Error("anchor on frame " + std::to_string(frame) + ", which the path does not have");
  return static_cast<std::size_t>(it - path.frames.begin());
}

void apply(const Similarity2& s, PathFrame* f) {
  const Eigen::Vector2d p = s.apply(f->position());
  f->x = p.x();
  f->y = p.y();
  f->heading = wrap_angle(f->heading + s.rotation);
}

}  // namespace

Similarity2 similarity_to_anchors(const CameraPath& path, const Anchors& anchors) {
  if (anchors.empty()) throw Error("aligning a path needs at least one anchor");
  std::vector<Eigen::Vector2d> from, to;
  for (const Anchor& a : anchors) {
    from.push_back(path.frames[position_of(path, a.frame)].position());
    to.push_back(a.position);
  }
  if (anchors.size() == 1) {
    // One anchor: a translation, or with the anchor's heading also the rotation about it.
    Similarity2 s;
    if (anchors[0].heading)
      s.rotation = wrap_angle(*anchors[0].heading - path.frames[position_of(path, anchors[0].frame)].heading);
    const double c = std::cos(s.rotation), sn = std::sin(s.rotation);
    s.translation =
        to[0] - Eigen::Vector2d(c * from[0].x() - sn * from[0].y(), sn * from[0].x() + c * from[0].y());
    return s;
  }
  return align_similarity(from, to);
}

static CameraPath align_one_piece(const CameraPath& path, const Anchors& anchors) {
  const Similarity2 s = similarity_to_anchors(path, anchors);
  CameraPath out = path;
  for (PathFrame& f : out.frames) apply(s, &f);
  return out;
}

static CameraPath preview_one_piece(const CameraPath& path, const Anchors& anchors) {
  if (anchors.empty()) return path;
  if (anchors.size() == 1) return align_one_piece(path, anchors);
  // Anchors in path order, each with its position along the path.
  std::vector<std::pair<std::size_t, const Anchor*>> ordered;
  for (const Anchor& a : anchors) ordered.emplace_back(position_of(path, a.frame), &a);
  std::sort(ordered.begin(), ordered.end(), [](const auto& l, const auto& r) { return l.first < r.first; });
  const std::vector<double> s = path.arc_lengths();
  // One exact similarity per consecutive pair (identical frames anchored twice: a translation).
  std::vector<Similarity2> pieces;
  for (std::size_t k = 0; k + 1 < ordered.size(); ++k) {
    const Anchor& a = *ordered[k].second;
    const Anchor& b = *ordered[k + 1].second;
    const Eigen::Vector2d pa = path.frames[ordered[k].first].position();
    const Eigen::Vector2d pb = path.frames[ordered[k + 1].first].position();
    if ((pb - pa).norm() < 1e-9 || (b.position - a.position).norm() < 1e-9) {
      Similarity2 t;
      t.translation = a.position - pa;
      pieces.push_back(t);
    } else {
      pieces.push_back(align_similarity({pa, pb}, {a.position, b.position}));
    }
  }
  // Positions: the piece between the frame's two anchors (pieces agree at the anchors, so the path stays
  // connected). Headings: the pieces' rotations averaged at each anchor and interpolated by arc length, so
  // headings do not jump at an anchor either.
  std::vector<double> rotation_at_anchor(ordered.size());
  for (std::size_t k = 0; k < ordered.size(); ++k) {
    const double left = pieces[k == 0 ? 0 : k - 1].rotation;
    const double right = pieces[std::min(k, pieces.size() - 1)].rotation;
    rotation_at_anchor[k] = left + 0.5 * std::remainder(right - left, 2 * M_PI);
  }
  CameraPath out = path;
  std::size_t piece = 0;
  for (std::size_t i = 0; i < out.frames.size(); ++i) {
    while (piece + 1 < pieces.size() && i > ordered[piece + 1].first) ++piece;
    const std::size_t begin = ordered[piece].first, end = ordered[piece + 1].first;
    const double span = s[end] - s[begin];
    const double t = std::clamp(span > 0 ? (s[i] - s[begin]) / span : 0.0, 0.0, 1.0);
    const double r0 = rotation_at_anchor[piece], r1 = rotation_at_anchor[piece + 1];
    const Eigen::Vector2d p = pieces[piece].apply(path.frames[i].position());
    out.frames[i].x = p.x();
    out.frames[i].y = p.y();
    out.frames[i].heading = wrap_angle(path.frames[i].heading + r0 + t * std::remainder(r1 - r0, 2 * M_PI));
  }
  return out;
}

void AnchorRefinementOptions::check() const {
  if (!(step_sigma_fraction > 0)) throw Error("anchor refinement: step_sigma_fraction must be > 0");
  if (!(step_sigma_min_m > 0)) throw Error("anchor refinement: step_sigma_min_m must be > 0");
  if (!(turn_sigma_rad > 0)) throw Error("anchor refinement: turn_sigma_rad must be > 0");
  if (!(anchor_sigma_m > 0)) throw Error("anchor refinement: anchor_sigma_m must be > 0");
  if (!(anchor_heading_sigma_rad > 0)) throw Error("anchor refinement: anchor_heading_sigma_rad must be > 0");
  if (max_iterations < 1) throw Error("anchor refinement: max_iterations must be >= 1");
  if (!(drift_scale_sigma > 0) || !(drift_bias_sigma_rad > 0))
    throw Error("anchor refinement: drift sigmas must be > 0");
}

static CameraPath refine_one_piece(const CameraPath& path, const Anchors& anchors,
                                   const AnchorRefinementOptions& options, AnchorRefinementReport* report,
                                   Progress& progress, const std::vector<GpsPrior>& gps) {
  if (path.empty()) throw Error("anchor refinement: the path is empty");
  // GPS fixes on frames the path has; they align the path like anchors when there are no anchors.
  std::vector<GpsPrior> fixes;
  for (const GpsPrior& g : gps)
    if (path.find_frame(g.frame) && g.sigma_m > 0) fixes.push_back(g);
  if (anchors.empty() && fixes.size() < 2)
    throw Error("anchor refinement: place at least one anchor (or give GPS fixes on two frames or more)");
  for (const Anchor& a : anchors) position_of(path, a.frame);  // validates every anchor first

  // Start from the similarity alignment, so the solver only has to bend, not to turn the whole path.
  Anchors alignment = anchors;
  if (anchors.empty())
    for (const GpsPrior& g : fixes) alignment.push_back({g.frame, g.plan_xy, std::nullopt});
  const CameraPath start = align_one_piece(path, alignment);
  std::vector<std::array<double, 3>> poses(start.frames.size());
  for (std::size_t i = 0; i < poses.size(); ++i)
    poses[i] = {start.frames[i].x, start.frames[i].y, start.frames[i].heading};

  // The tracker's drift {scale, turn bias per step}, one for the whole path. Per-stretch drift would leave
  // each stretch one unknown more than its anchor pins down (its start heading, scale and bias against two
  // coordinates); one global drift is determined by three anchors and over-determined by more.
  std::set<int> anchored_frames;
  for (const Anchor& a : alignment) anchored_frames.insert(a.frame);
  std::array<double, 2> drift = {1.0, 0.0};

  ceres::Problem problem;
  problem.AddParameterBlock(drift.data(), 2);
  problem.AddResidualBlock(DriftPrior::Create(options.drift_scale_sigma, options.drift_bias_sigma_rad),
                           nullptr, drift.data());
  if (anchored_frames.size() < 2)
    problem.SetParameterBlockConstant(drift.data());  // one anchor cannot see drift
  for (std::size_t i = 0; i + 1 < start.frames.size(); ++i) {
    const PathFrame& a = start.frames[i];
    const PathFrame& b = start.frames[i + 1];
    const Eigen::Vector2d d = b.position() - a.position();
    const double c = std::cos(a.heading), s = std::sin(a.heading);
    const Eigen::Vector2d local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
    const double sigma_t = std::max(options.step_sigma_min_m, options.step_sigma_fraction * d.norm());
    problem.AddResidualBlock(StepResidual::Create(local, std::remainder(b.heading - a.heading, 2 * M_PI),
                                                  sigma_t, options.turn_sigma_rad),
                             nullptr, poses[i].data(), poses[i + 1].data(), drift.data());
  }
  for (const Anchor& anchor : anchors) {
    double* pose = poses[position_of(start, anchor.frame)].data();
    problem.AddResidualBlock(AnchorPrior::Create(anchor.position, options.anchor_sigma_m), nullptr, pose);
    if (anchor.heading)
      problem.AddResidualBlock(HeadingPrior::Create(*anchor.heading, options.anchor_heading_sigma_rad),
                               nullptr, pose);
  }
  for (const GpsPrior& g : fixes)
    problem.AddResidualBlock(AnchorPrior::Create(g.plan_xy, g.sigma_m), new ceres::CauchyLoss(1.0),
                             poses[position_of(start, g.frame)].data());
  // A single anchor without heading leaves the rotation about it free: hold that frame's heading.
  if (anchors.size() == 1 && !anchors[0].heading && fixes.size() < 2)
    problem.AddResidualBlock(HeadingPrior::Create(poses[position_of(start, anchors[0].frame)][2], 1e-3),
                             nullptr, poses[position_of(start, anchors[0].frame)].data());

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;  // a chain: banded, sparse
  solver.max_num_iterations = options.max_iterations;
  // One thread: with more, Ceres sums in whatever order its threads finish and the last bits differ from
  // run to run, and `plenopath refine` would not repeat itself.
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ProgressCallback callback(progress, options.max_iterations);
  solver.callbacks.push_back(&callback);
  solver.update_state_every_iteration = false;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  progress.throw_if_cancelled();  // the path and the report stay as they were

  AnchorRefinementReport local_report;
  AnchorRefinementReport& r = report ? *report : local_report;
  r.iterations = static_cast<int>(summary.iterations.size());
  r.initial_cost = summary.initial_cost;
  r.final_cost = summary.final_cost;
  r.message = summary.BriefReport();
  r.residuals.clear();

  CameraPath out = start;
  for (std::size_t i = 0; i < out.frames.size(); ++i) {
    out.frames[i].x = poses[i][0];
    out.frames[i].y = poses[i][1];
    out.frames[i].heading = wrap_angle(poses[i][2]);
  }
  for (const Anchor& anchor : anchors) {
    const PathFrame& f = out.frames[position_of(out, anchor.frame)];
    AnchorResidual res;
    res.frame = anchor.frame;
    res.distance_m = (f.position() - anchor.position).norm();
    if (anchor.heading) res.heading_error_deg = std::abs(degrees(wrap_angle(f.heading - *anchor.heading)));
    r.residuals.push_back(res);
  }
  return out;
}

namespace {
using namespace pose_graph;

// Writes the frames of piece k, placed on their own, back into the whole path and marks the piece placed.
void put_piece_back(const CameraPath& placed, int k, CameraPath* out) {
  for (const PathFrame& f : placed.frames) {
    PathFrame& target = out->frames[position_of(*out, f.index)];
    target.x = f.x;
    target.y = f.y;
    target.heading = f.heading;
  }
  out->pieces[static_cast<std::size_t>(k)].placed = true;
}

// Runs `place` on each piece of `path` that has anchors (a path without pieces is one piece) and writes the
// placed frames back; a piece placed so is marked placed. Pieces without anchors stay as they are.
template <class Place>
CameraPath place_pieces(const CameraPath& path, const Anchors& anchors, Place&& place) {
  for (const Anchor& a : anchors) position_of(path, a.frame);  // validates every anchor first
  if (path.piece_count() == 1) return place(path, anchors);
  CameraPath out = path;
  for (int k = 0; k < path.piece_count(); ++k) {
    CameraPath piece = path.piece_path(k);
    Anchors own;
    for (const Anchor& a : anchors)
      if (piece.find_frame(a.frame)) own.push_back(a);
    if (own.empty()) continue;
    const CameraPath placed = place(piece, own);
    put_piece_back(placed, k, &out);
  }
  return out;
}

}  // namespace

CameraPath align_path_to_anchors(const CameraPath& path, const Anchors& anchors) {
  if (anchors.empty()) throw Error("aligning a path needs at least one anchor");
  return place_pieces(path, anchors,
                      [](const CameraPath& p, const Anchors& a) { return align_one_piece(p, a); });
}

CameraPath preview_path_with_anchors(const CameraPath& path, const Anchors& anchors) {
  if (anchors.empty()) return path;
  return place_pieces(path, anchors,
                      [](const CameraPath& p, const Anchors& a) { return preview_one_piece(p, a); });
}

CameraPath refine_path_with_anchors(const CameraPath& path, const Anchors& anchors,
                                    const AnchorRefinementOptions& options, AnchorRefinementReport* report,
                                    Progress& progress, const std::vector<GpsPrior>& gps) {
  options.check();
  if (path.piece_count() == 1) return refine_one_piece(path, anchors, options, report, progress, gps);
  // In pieces: each piece with anchors (or two GPS fixes) is refined on its own; the others stay unplaced.
  if (path.empty()) throw Error("anchor refinement: the path is empty");
  for (const Anchor& a : anchors) position_of(path, a.frame);
  AnchorRefinementReport total;
  CameraPath out = path;
  bool any = false;
  for (int k = 0; k < path.piece_count(); ++k) {
    const CameraPath piece = path.piece_path(k);
    Anchors own;
    for (const Anchor& a : anchors)
      if (piece.find_frame(a.frame)) own.push_back(a);
    std::vector<GpsPrior> own_gps;
    for (const GpsPrior& g : gps)
      if (piece.find_frame(g.frame) && g.sigma_m > 0) own_gps.push_back(g);
    if (own.empty() && own_gps.size() < 2) continue;
    any = true;
    AnchorRefinementReport r;
    SubProgress piece_progress(progress, double(k) / path.piece_count(), double(k + 1) / path.piece_count(),
                               "piece " + std::to_string(k));
    const CameraPath placed = refine_one_piece(piece, own, options, &r, piece_progress, own_gps);
    total.iterations += r.iterations;
    total.initial_cost += r.initial_cost;
    total.final_cost += r.final_cost;
    total.message += (total.message.empty() ? "" : "; ") + ("piece " + std::to_string(k) + ": " + r.message);
    total.residuals.insert(total.residuals.end(), r.residuals.begin(), r.residuals.end());
    put_piece_back(placed, k, &out);
  }
  if (!any)
    throw Error(
        "anchor refinement: place at least one anchor on a piece (or give GPS fixes on two frames or more)");
  if (report) *report = total;
  return out;
}

std::vector<GpsPrior> gps_priors_for_path(const Project& project) {
  if (project.capture.gps_track.empty() || !project.geo.valid || project.path.empty() ||
      !(project.capture.frame_rate > 0))
    return {};
  std::vector<double> times;
  // A frame's own time (variable-rate video), not its index over the rate.
  for (const PathFrame& f : project.path.frames) times.push_back(project.capture.time_at_index_s(f.index));
  GpsMatchOptions match;
  match.time_offset_s = project.capture.gps_time_offset_s;
  std::vector<GpsPrior> gps = gps_priors(project.capture.gps_track, times, project.geo, match);
  for (GpsPrior& g : gps) g.frame = project.path.frames[static_cast<std::size_t>(g.frame)].index;
  return gps;
}

}  // namespace plenopath
