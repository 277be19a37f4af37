#include "processing/egomotion/egomotion.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <opencv2/imgproc.hpp>
#include <random>
#include <sstream>

#include "model/error.h"
#include "processing/egomotion/bearing_cost.h"
#include "processing/util/grey_image.h"
#include "processing/util/statistics.h"

namespace plenopath {
namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

Eigen::Vector3d rotate_z(const Eigen::Vector3d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}

void add_flag(PathFrame& f, FrameFlag flag, const std::string& why) {
  if (f.flags & flag) return;
  f.flags |= flag;
  f.reason += (f.reason.empty() ? "" : "; ") + why;
}

// Angle between a world ray and the direction from a centre to a point.
double ray_error(const Eigen::Vector3d& pose, const Eigen::Vector3d& point, const Eigen::Vector3d& bearing) {
  const Eigen::Vector3d d = rotate_z(bearing, pose.z());
  const Eigen::Vector3d v = point - Eigen::Vector3d(pose.x(), pose.y(), 0.0);
  return std::atan2(d.cross(v).norm(), d.dot(v));
}

// Pose-only Gauss-Newton (x, y, heading) on angular residuals with a Huber weight. Returns the inlier count.
int resect_pose(Eigen::Vector3d* pose, const std::vector<Eigen::Vector3d>& points,
                const std::vector<Eigen::Vector3d>& bearings, double huber, double inlier_threshold) {
  std::vector<PlanarBearingCost> costs;
  costs.reserve(bearings.size());
  for (const auto& b : bearings) costs.emplace_back(b);
  Eigen::Vector3d p = *pose;
  for (int it = 0; it < 10; ++it) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < points.size(); ++k) {
      double r[3];
      costs[k](p.data(), points[k].data(), r);
      Eigen::Matrix<double, 3, 3> j;
      for (int d = 0; d < 3; ++d) {
        Eigen::Vector3d q = p;
        const double h = 1e-7;
        q[d] += h;
        double rq[3];
        costs[k](q.data(), points[k].data(), rq);
        for (int e = 0; e < 3; ++e) j(e, d) = (rq[e] - r[e]) / h;
      }
      const Eigen::Vector3d rv(r[0], r[1], r[2]);
      const double n = rv.norm();
      const double w = n <= huber ? 1.0 : huber / n;
      jtj += w * j.transpose() * j;
      jtr += w * j.transpose() * rv;
    }
    const Eigen::Vector3d step = -(jtj + 1e-9 * Eigen::Matrix3d::Identity()).ldlt().solve(jtr);
    if (!step.allFinite()) break;
    p += step;
    if (step.norm() < 1e-9) break;
  }
  int inliers = 0;
  for (size_t k = 0; k < points.size(); ++k)
    inliers += ray_error(p, points[k], bearings[k]) < inlier_threshold;
  *pose = p;
  return inliers;
}

// Merges the points of each verified loop pair (union-find; the earlier visit's point stays), rewrites the
// observations and the track-to-point map, and drops a keyframe's second observation of one merged point.
// Returns how many points were merged away.
int merge_loop_points(const std::vector<LoopMatch>& loops, BundleProblem* problem,
                      std::vector<int>* point_of_track) {
  std::vector<int> parent(problem->points.size());
  for (std::size_t q = 0; q < parent.size(); ++q) parent[q] = static_cast<int>(q);
  auto root = [&](int q) {
    while (parent[q] != q) q = parent[q] = parent[parent[q]];
    return q;
  };
  int merged = 0;
  for (const LoopMatch& m : loops)
    for (const auto& [ta, tb] : m.track_pairs) {
      const int pa = (*point_of_track)[ta], pb = (*point_of_track)[tb];
      if (pa < 0 || pb < 0) continue;
      const int ra = root(pa), rb = root(pb);
      if (ra == rb) continue;
      parent[std::max(ra, rb)] = std::min(ra, rb);
      ++merged;
    }
  if (merged == 0) return 0;
  std::vector<BundleObservation>& obs = problem->observations;
  for (BundleObservation& o : obs) o.point = root(o.point);
  std::sort(obs.begin(), obs.end(), [](const BundleObservation& a, const BundleObservation& b) {
    return a.point != b.point ? a.point < b.point : a.pose < b.pose;
  });
  obs.erase(std::unique(obs.begin(), obs.end(),
                        [](const BundleObservation& a, const BundleObservation& b) {
                          return a.point == b.point && a.pose == b.pose;
                        }),
            obs.end());
  for (int& q : *point_of_track)
    if (q >= 0) q = root(q);
  return merged;
}

}  // namespace

std::string EgomotionOptions::check() const {
  std::ostringstream o;
  const std::string r = ring.check(), k = klt.check(), f = refinement.check(), l = loop.check();
  if (!l.empty()) o << "loop: " << l;
  if (!r.empty()) o << "ring: " << r;
  if (!k.empty()) o << "klt: " << k;
  if (!f.empty()) o << "refinement: " << f;
  if (!(keyframe_parallax_deg > 0)) o << "keyframe_parallax_deg must be > 0; ";
  if (!(keyframe_max_turn_deg > 0)) o << "keyframe_max_turn_deg must be > 0; ";
  if (!(keyframe_min_shared > 0 && keyframe_min_shared < 1)) o << "keyframe_min_shared must be in (0, 1); ";
  if (!(max_step_ratio > 1)) o << "max_step_ratio must be > 1; ";
  if (!(max_step_turn_disagreement_deg > 0)) o << "max_step_turn_disagreement_deg must be > 0; ";
  if (!(min_triangulation_deg > 0)) o << "min_triangulation_deg must be > 0; ";
  if (!(max_initial_error_deg > 0)) o << "max_initial_error_deg must be > 0; ";
  if (min_point_keyframes < 2) o << "min_point_keyframes must be >= 2; ";
  if (resection_min_points < 3) o << "resection_min_points must be >= 3; ";
  if (camera_height_m < 0) o << "camera_height_m must be >= 0 (0 = unknown); ";
  if (scale_distance_m < 0) o << "scale_distance_m must be >= 0; ";
  if (scale_distance_m > 0 && (scale_frame_a < 0 || scale_frame_b < 0 || scale_frame_a == scale_frame_b))
    o << "scale_distance_m needs two different frames scale_frame_a and scale_frame_b; ";
  if (!(jump_factor > 1)) o << "jump_factor must be > 1; ";
  if (!(moving_outlier_fraction > 0 && moving_outlier_fraction <= 1))
    o << "moving_outlier_fraction must be in (0, 1]; ";
  return o.str();
}

struct EgomotionTracker::State {
  explicit State(const EgomotionOptions& o) : options(o), klt(o.klt) {}
  EgomotionOptions options;
  KltTracker klt;
  std::vector<std::vector<double>> rings;
  std::vector<FrameTrackStats> stats;
  std::vector<int> live_after;              // live tracks after each frame (texture measure)
  std::vector<double> window;               // ring column weights
  std::vector<FrameDescriptors> described;  // for loop closure
  double seconds_frames = 0.0;
};

EgomotionTracker::EgomotionTracker(const EgomotionOptions& options) {
  const std::string bad = options.check();
  if (!bad.empty()) throw Error("egomotion options: " + bad);
  state_ = std::make_unique<State>(options);
}
EgomotionTracker::~EgomotionTracker() = default;
int EgomotionTracker::frame_count() const { return static_cast<int>(state_->rings.size()); }

void EgomotionTracker::add_frame(const cv::Mat& bgr) {
  const auto t0 = Clock::now();
  State& s = *state_;
  if (bgr.empty()) throw Error("egomotion: frame " + std::to_string(s.rings.size()) + " is empty");
  if (bgr.cols != 2 * bgr.rows)
    throw Error("egomotion: frame " + std::to_string(s.rings.size()) + " is not equirectangular 2:1");
  const cv::Mat gray = equirect_at_width(grey_image(bgr, "egomotion"), s.options.klt.work_width);
  s.rings.push_back(make_ring_image(gray, s.options.ring));
  // The turn since the previous frame, from the rings, starts the KLT search (fast turns).
  double predicted_shift = 0.0;
  if (s.rings.size() >= 2) {
    const std::vector<double>& previous = s.rings[s.rings.size() - 2];
    const double max_px = s.options.ring.max_turn_deg_per_frame / 360.0 * gray.cols;
    if (s.window.size() != previous.size()) s.window = axis_window(gray.cols, s.options.ring.axis_floor);
    const RingShift shift = circular_phase_correlation(previous, s.rings.back(), 0.0, max_px, &s.window,
                                                       s.options.ring.max_frequency_fraction);
    if (shift.valid && shift.peak >= s.options.ring.min_peak) predicted_shift = shift.shift_px;
  }
  const FrameTrackStats st = s.klt.add_frame(gray, predicted_shift);
  s.stats.push_back(st);
  const int index = static_cast<int>(s.rings.size()) - 1;
  if (s.options.loop.enabled && index % s.options.loop.descriptor_stride == 0) {
    std::vector<cv::Point2f> positions;
    for (int t : s.klt.live_tracks()) {
      const TrackObservation& o = s.klt.tracks()[static_cast<std::size_t>(t)].observations.back();
      positions.emplace_back(o.x, o.y);
    }
    s.described.push_back(describe_frame(gray, index, s.klt.live_tracks(), positions));
  }
  s.live_after.push_back(st.tracked + st.detected);
  s.seconds_frames += seconds_since(t0);
}

EgomotionResult EgomotionTracker::finish(const EgomotionCallback& callback) {
  const auto t_start = Clock::now();
  State& s = *state_;
  const EgomotionOptions& opt = s.options;
  EgomotionResult result;
  result.seconds_per_frame_stage = s.seconds_frames;
  const int n = static_cast<int>(s.rings.size());
  if (n == 0) throw Error("egomotion: the capture has no frames");
  bool cancelled = false;
  auto report = [&](const char* stage, double f) {
    if (callback && !cancelled && !callback(stage, f)) cancelled = true;
    return !cancelled;
  };
  auto finish_cancelled = [&]() {
    result.cancelled = true;
    result.seconds_geometry = seconds_since(t_start);
    return result;
  };
  const double deg = M_PI / 180.0;
  const int width = s.klt.width();
  const double pixel_angle = 2.0 * M_PI / std::max(1, width);
  // Angular tolerances are set for a 1024-wide working image; a coarser one measures coarser, and holding
  // it to sub-pixel tolerances leaves RANSAC too few inliers and puts every residual in the robust loss's
  // flat tail.
  const double coarseness = std::max(1.0, 1024.0 / std::max(1, width));
  PlanarTwoViewOptions two_view = opt.two_view;
  two_view.threshold *= coarseness;
  RefinementOptions refinement = opt.refinement;
  refinement.loss_scale *= coarseness;
  refinement.outlier_threshold *= coarseness;

  // ---- 1. coarse headings
  report("headings", 0.0);
  const RingHeadings rh = solve_ring_headings(s.rings, opt.ring);
  result.ring_headings = rh.headings;
  if (!report("headings", 1.0)) return finish_cancelled();

  // ---- per-frame index of observations
  const std::vector<FeatureTrack>& tracks = s.klt.tracks();
  std::vector<std::vector<int>> frame_tracks(n);
  for (int t = 0; t < static_cast<int>(tracks.size()); ++t)
    for (const TrackObservation& o : tracks[t].observations) frame_tracks[o.frame].push_back(t);
  auto observation = [&](int t, int frame) -> const TrackObservation* {
    const auto& obs = tracks[t].observations;
    const int k = frame - obs.front().frame;
    if (k < 0 || k >= static_cast<int>(obs.size())) return nullptr;
    return &obs[k];
  };
  auto bearing = [&](int t, int frame) { return s.klt.bearing(*observation(t, frame)); };

  std::mt19937 rng(opt.seed);
  std::vector<PathFrame> frames(n);
  for (int i = 0; i < n; ++i) frames[i].index = i;
  std::vector<bool> textureless(n, false);
  for (int i = 0; i < n; ++i) {
    if (s.live_after[i] < opt.textureless_corners) {
      textureless[i] = true;
      add_flag(frames[i], kFrameTextureless,
               "textureless: " + std::to_string(s.live_after[i]) + " trackable corners");
    }
    if (i > 0 && s.stats[i].tracked > 0 && s.stats[i].median_flow_px < opt.duplicate_flow_px)
      add_flag(frames[i], kFrameDuplicate, "duplicate: no motion since the previous frame (stopped)");
    if (i > 0 && rh.step_peak[i] < opt.ring.min_peak)
      add_flag(frames[i], kFrameJump, "jump: the ring image does not register with the previous frame");
  }

  // ---- 1b. frame-to-frame turns from the KLT tracks. The rings are coarse indoors (parallax of near walls
  // biases them by degrees, and they drift); the tracks between consecutive frames give each turn to a few
  // hundredths of a degree: the median azimuth change (exact for a turn on the spot), refined by planar
  // two-view geometry when the frames moved enough. Frames without enough tracks keep the ring's turn.
  std::vector<double> heading(n, 0.0);
  // Per frame: the share of the tracks continued from the previous frame that move against the static
  // scene (off the epipolar geometry of the step, or of a pure turn when the step has no parallax); -1 when
  // the step could not be solved. Tracks on people walking by, a passing door or the operator: the
  // refinement rejects them, but a frame where they are many is worth flagging.
  std::vector<double> moving_share(n, -1.0);
  {
    PlanarTwoViewOptions step_options = two_view;
    step_options.turn_scan_deg = 0;
    step_options.iterations = 32;
    const double max_disagreement = opt.max_step_turn_disagreement_deg * deg;
    for (int f = 1; f < n; ++f) {
      const double ring_turn = rh.headings[f] - rh.headings[f - 1];
      std::vector<Eigen::Vector3d> ba, bb;
      std::vector<double> azimuth_change;
      for (int t : frame_tracks[f]) {
        if (!observation(t, f - 1)) continue;
        const Eigen::Vector3d a = bearing(t, f - 1), b = bearing(t, f);
        azimuth_change.push_back(
            std::remainder(std::atan2(a.y(), a.x()) - std::atan2(b.y(), b.x()), 2 * M_PI));
        // A spread subset is plenty for the two-view turn (tracks are in detection order, i.e. spread).
        if (ba.size() < 240 && (azimuth_change.size() % 2 == 1 || frame_tracks[f].size() < 480)) {
          ba.push_back(a);
          bb.push_back(b);
        }
      }
      double turn = ring_turn;
      if (static_cast<int>(azimuth_change.size()) >= two_view.min_inliers) {
        turn = median(azimuth_change);
        const PlanarRelativePose rel = estimate_planar_relative_pose(ba, bb, turn, step_options, rng);
        const bool solved = rel.valid && std::abs(rel.turn - turn) < max_disagreement;
        if (solved) turn = rel.turn;
        if (solved || rel.median_parallax < two_view.min_parallax) {
          int moving = 0, total = 0;
          for (int t : frame_tracks[f]) {
            if (!observation(t, f - 1)) continue;
            const Eigen::Vector3d a = bearing(t, f - 1), b = bearing(t, f);
            const Eigen::Vector3d turned = rotate_z(a, -turn);
            const double error = solved ? std::abs(planar_epipolar_error(a, b, rel.turn, rel.direction))
                                        : std::atan2(turned.cross(b).norm(), turned.dot(b));
            moving += error > 3.0 * two_view.threshold;
            ++total;
          }
          moving_share[f] = double(moving) / total;
        }
      }
      heading[f] = heading[f - 1] + turn;
    }
  }
  result.tracked_headings = heading;

  // ---- 2a. keyframes (chunk cuts)
  std::vector<int> keyframes = {0};
  for (int f = 1; f < n; ++f) {
    if (textureless[f]) continue;
    const int kf = keyframes.back();
    std::vector<double> parallax;
    for (int t : frame_tracks[kf]) {
      if (!observation(t, f)) continue;
      const Eigen::Vector3d a = rotate_z(bearing(t, kf), heading[kf]);
      const Eigen::Vector3d b = rotate_z(bearing(t, f), heading[f]);
      parallax.push_back(std::atan2(a.cross(b).norm(), a.dot(b)));
    }
    const double shared = frame_tracks[kf].empty() ? 0.0 : double(parallax.size()) / frame_tracks[kf].size();
    const bool cut = median(parallax) > opt.keyframe_parallax_deg * deg || shared < opt.keyframe_min_shared ||
                     parallax.size() < 60 ||
                     std::abs(heading[f] - heading[kf]) > opt.keyframe_max_turn_deg * deg || f == n - 1;
    if (cut) keyframes.push_back(f);
  }
  const int kfn = static_cast<int>(keyframes.size());
  result.keyframes = keyframes;
  std::vector<int> kf_of_frame(n, -1);
  for (int k = 0; k < kfn; ++k) kf_of_frame[keyframes[k]] = k;

  // ---- 2b. chain the chunks: direction by two-view RANSAC, length by resection against known points
  std::vector<Eigen::Vector3d> kf_pose(kfn, Eigen::Vector3d::Zero());
  kf_pose[0].z() = heading[keyframes[0]];
  std::vector<Eigen::Vector3d> point(tracks.size(), Eigen::Vector3d::Zero());
  std::vector<char> point_valid(tracks.size(), 0);
  std::vector<bool> kf_bridged(kfn, false);
  // Speeds (length per frame) rather than keyframe steps: keyframes are a varying number of frames apart,
  // and a gap bridged with the last step's length instead of the last speed shrinks (or stretches) the scale
  // of everything after it (seen: a 9-frame gap bridged with a 2-frame step left the rest of a 2 600-frame
  // walk at 0.3 of its scale).
  std::vector<double> recent_speeds;  // the last measured keyframe steps per frame
  double last_speed = 0.0, last_direction = kf_pose[0].z();
  auto triangulate_track = [&](int t, int up_to_kf) {
    const auto& obs = tracks[t].observations;
    std::vector<Eigen::Vector3d> centres, dirs;
    const auto first =
        std::lower_bound(keyframes.begin(), keyframes.begin() + up_to_kf + 1, obs.front().frame);
    for (auto it = first; it != keyframes.begin() + up_to_kf + 1 && *it <= obs.back().frame; ++it) {
      const int k = static_cast<int>(it - keyframes.begin());
      centres.emplace_back(kf_pose[k].x(), kf_pose[k].y(), 0.0);
      dirs.push_back(rotate_z(bearing(t, *it), kf_pose[k].z()));
    }
    Eigen::Vector3d p;
    if (triangulate_rays(centres, dirs, opt.min_triangulation_deg * coarseness * deg, &p)) {
      point[t] = p;
      point_valid[t] = 1;
    }
  };
  for (int k = 1; k < kfn; ++k) {
    const int a = keyframes[k - 1], b = keyframes[k];
    std::vector<Eigen::Vector3d> ba, bb;
    std::vector<int> shared;
    for (int t : frame_tracks[a]) {
      if (!observation(t, b)) continue;
      ba.push_back(bearing(t, a));
      bb.push_back(bearing(t, b));
      shared.push_back(t);
    }
    const double turn_guess = heading[b] - heading[a];
    const int gap = b - a;
    const double bridge_length = (last_speed > 0 ? last_speed : 1.0 / gap) * gap;  // frame 0 -> 1: unit
    PlanarRelativePose rel = estimate_planar_relative_pose(ba, bb, turn_guess, two_view, rng);
    // The tracked turn is good to a fraction of a degree: a two-view turn far from it is a wrong solution.
    if (rel.valid && std::abs(rel.turn - turn_guess) > opt.max_step_turn_disagreement_deg * deg)
      rel.valid = false;
    Eigen::Vector3d& pa = kf_pose[k - 1];
    Eigen::Vector3d& pb = kf_pose[k];
    pb.z() = pa.z() + (rel.valid ? rel.turn : turn_guess);
    double direction = last_direction, length = 0.0;
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
        Eigen::Matrix<double, 3, 2> m;
        m.col(0) = t_dir;
        m.col(1) = d;
        const Eigen::Vector3d rhs = point[t] - Eigen::Vector3d(pa.x(), pa.y(), 0.0);
        const Eigen::Vector2d lm = (m.transpose() * m).ldlt().solve(m.transpose() * rhs);
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
      // A step many times longer or shorter than the recent ones is a bad measurement (points near the
      // direction of travel, or too few), not a trolley that suddenly ran or crawled: bridge it. (Keyframes
      // are cut by parallax, so their steps stay alike; a turn on the spot is handled above.) A wrong short
      // step would also shrink every later step, which is measured against the points it placed.
      if (recent_speeds.size() >= 3) {
        const double typical = median(recent_speeds) * gap;
        if (length > opt.max_step_ratio * typical || length < typical / opt.max_step_ratio) {
          length = typical;
          kf_bridged[k] = true;
        }
      }
    } else if (rel.median_parallax < two_view.min_parallax && !ba.empty()) {
      length = 0.0;  // a turn on the spot: no translation to see
    } else {
      length = bridge_length;  // cannot solve this stretch: bridge it at the last speed
      kf_bridged[k] = true;
    }
    pb.x() = pa.x() + length * std::cos(direction);
    pb.y() = pa.y() + length * std::sin(direction);
    if (length > 0) {
      last_speed = length / gap;
      last_direction = direction;
      if (!kf_bridged[k]) {
        recent_speeds.push_back(length / gap);
        if (recent_speeds.size() > 9) recent_speeds.erase(recent_speeds.begin());
      }
    }
    for (int t : frame_tracks[b]) triangulate_track(t, k);
    if (k % 16 == 0 && !report("chaining", double(k) / kfn)) return finish_cancelled();
  }

  // Coarse pose of every frame: keyframes interpolated, headings from the rings.
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
    return p;
  };
  std::vector<Eigen::Vector3d> coarse(n);
  for (int f = 0; f < n; ++f) coarse[f] = interpolate(kf_pose, f);

  // ---- 3. refinement of keyframes and points
  BundleProblem problem;
  problem.poses = kf_pose;
  std::vector<int> point_of_track(tracks.size(), -1);
  for (int t = 0; t < static_cast<int>(tracks.size()); ++t) {
    triangulate_track(t, kfn - 1);
    if (!point_valid[t]) continue;
    std::vector<BundleObservation> obs;
    const auto& to = tracks[t].observations;
    for (auto it = std::lower_bound(keyframes.begin(), keyframes.end(), to.front().frame);
         it != keyframes.end() && *it <= to.back().frame; ++it) {
      const int k = static_cast<int>(it - keyframes.begin());
      const Eigen::Vector3d b = bearing(t, *it);
      if (ray_error(kf_pose[k], point[t], b) > opt.max_initial_error_deg * coarseness * deg) continue;
      obs.push_back({k, static_cast<int>(problem.points.size()), b});
    }
    if (static_cast<int>(obs.size()) < opt.min_point_keyframes) continue;
    point_of_track[t] = static_cast<int>(problem.points.size());
    problem.points.push_back(point[t]);
    problem.observations.insert(problem.observations.end(), obs.begin(), obs.end());
  }
  result.points = static_cast<int>(problem.points.size());
  result.observations = static_cast<int>(problem.observations.size());
  if (!report("refinement", 0.0)) return finish_cancelled();
  // Windows first; then the places the walk came back to are tied together, and one global pass removes
  // the drift in between.
  RefinementOptions windowed = refinement, global = refinement;
  windowed.global_max_iterations = 0;
  global.window_keyframes = 0;
  const RefinementReport windows =
      refine_bundle(problem, windowed, [&](double f) { return report("refinement", 0.5 * f); });
  if (windows.cancelled || cancelled) return finish_cancelled();
  {
    std::vector<double> kf_travelled(kfn, 0.0);
    for (int k = 1; k < kfn; ++k)
      kf_travelled[k] =
          kf_travelled[k - 1] + (problem.poses[k].head<2>() - problem.poses[k - 1].head<2>()).norm();
    std::vector<double> steps;
    for (int k = 1; k < kfn; ++k) steps.push_back(kf_travelled[k] - kf_travelled[k - 1]);
    const std::vector<Eigen::Vector3d> kf_now = problem.poses;
    const std::vector<LoopMatch> loops = find_loop_closures(
        s.described, [&](int f) { return interpolate(kf_now, f); },
        [&](int f) {
          const int k1 =
              static_cast<int>(std::upper_bound(keyframes.begin(), keyframes.end(), f) - keyframes.begin());
          if (k1 >= kfn) return kf_travelled.back();
          const int k0 = k1 - 1;
          const double w = double(f - keyframes[k0]) / (keyframes[k1] - keyframes[k0]);
          return (1 - w) * kf_travelled[k0] + w * kf_travelled[k1];
        },
        bearing, median(steps), two_view, opt.loop, rng);
    result.merged_points = merge_loop_points(loops, &problem, &point_of_track);
    result.loop_closures = static_cast<int>(loops.size());
    for (const LoopMatch& m : loops) result.loop_frames.emplace_back(m.frame_a, m.frame_b);
  }
  const RefinementReport global_report =
      refine_bundle(problem, global, [&](double f) { return report("refinement", 0.5 + 0.5 * f); });
  if (global_report.cancelled || cancelled) return finish_cancelled();
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
  std::vector<Eigen::Vector3d> pose(n);
  const double inlier_threshold = std::max(4.0 * refinement.loss_scale, 3.0 * pixel_angle);
  for (int f = 0; f < n; ++f) {
    pose[f] = interpolate(refined_kf, f);
    std::vector<Eigen::Vector3d> pts, brs;
    for (int t : frame_tracks[f]) {
      if (point_of_track[t] < 0) continue;
      if (!point_alive[point_of_track[t]]) continue;
      pts.push_back(problem.points[point_of_track[t]]);
      brs.push_back(bearing(t, f));
    }
    if (kf_of_frame[f] >= 0) {
      pose[f] = refined_kf[kf_of_frame[f]];
    } else if (static_cast<int>(pts.size()) >= opt.resection_min_points) {
      Eigen::Vector3d p = pose[f];
      const int inliers = resect_pose(&p, pts, brs, refinement.loss_scale, inlier_threshold);
      // The frame lies between its keyframes: a resection that lands farther from the interpolated pose
      // than the keyframe step (or turns more than the tracked turn allows) has slipped.
      const int k1 =
          static_cast<int>(std::upper_bound(keyframes.begin(), keyframes.end(), f) - keyframes.begin());
      const int k0 = std::max(0, k1 - 1);
      const double kf_step =
          k1 < kfn ? (refined_kf[k1].head<2>() - refined_kf[k0].head<2>()).norm()
                   : (k0 > 0 ? (refined_kf[k0].head<2>() - refined_kf[k0 - 1].head<2>()).norm() : 0.0);
      const bool slipped =
          (p.head<2>() - pose[f].head<2>()).norm() > std::max(kf_step, 0.5 * typical_kf_step) ||
          std::abs(p.z() - pose[f].z()) > opt.max_step_turn_disagreement_deg * deg;
      if (slipped) {
        add_flag(frames[f], kFrameBridged, "bridged: the frame's points place it away from its keyframes");
      } else if (inliers >= opt.resection_min_points) {
        pose[f] = p;
      } else {
        add_flag(frames[f], kFrameBridged, "bridged: too few consistent points to place the frame");
      }
    } else {
      add_flag(frames[f], kFrameBridged, "bridged: too few tracked points to place the frame");
    }
    if (moving_share[f] >= 0) {
      if (moving_share[f] > opt.moving_outlier_fraction)
        add_flag(frames[f], kFrameMovingObjects,
                 "moving objects: " + std::to_string(int(std::round(100 * moving_share[f]))) +
                     "% of tracks move against the static scene");
      frames[f].confidence = 1.0 - moving_share[f];
    }
    if (f % 64 == 0 && !report("resection", double(f) / n)) return finish_cancelled();
  }
  for (int k = 1; k < kfn; ++k) {
    if (!kf_bridged[k]) continue;
    for (int f = keyframes[k - 1] + 1; f <= keyframes[k]; ++f)
      add_flag(frames[f], kFrameBridged, "bridged: the step into this chunk could not be measured");
  }

  // ---- 4. metric scale
  double scale = 1.0;
  result.scale_source = "relative";
  if (opt.camera_height_m > 0) {
    // Floor points: seen steeply downwards; the floor is the dominant level among them.
    std::vector<double> steep;
    // Steepness from the observing keyframes: keep points whose first observation looks down > 25 deg.
    std::vector<char> seen(problem.points.size(), 0);
    for (const BundleObservation& o : problem.observations) {
      if (seen[o.point]) continue;
      seen[o.point] = 1;
      const Eigen::Vector3d& p = problem.points[o.point];
      const Eigen::Vector3d& c = problem.poses[o.pose];
      const double horizontal = std::hypot(p.x() - c.x(), p.y() - c.y());
      if (p.z() < 0 && std::atan2(-p.z(), horizontal) > 25 * deg) steep.push_back(-p.z());
    }
    if (steep.size() >= 20) {
      // Mode of log depth (bins of 2 %), then the median within 4 % of it.
      std::map<int, int> bins;
      for (double z : steep) ++bins[static_cast<int>(std::floor(std::log(z) / 0.02))];
      int best_bin = 0, best_count = -1;
      for (const auto& [bin, count] : bins) {
        const int c =
            count + (bins.count(bin - 1) ? bins[bin - 1] : 0) + (bins.count(bin + 1) ? bins[bin + 1] : 0);
        if (c > best_count) {
          best_count = c;
          best_bin = bin;
        }
      }
      const double mode = std::exp((best_bin + 0.5) * 0.02);
      std::vector<double> near;
      for (double z : steep)
        if (std::abs(z / mode - 1.0) < 0.04) near.push_back(z);
      const double floor_depth = median(near);
      if (floor_depth > 0) {
        scale = opt.camera_height_m / floor_depth;
        result.scale_source = "camera_height";
        result.floor_points = static_cast<int>(near.size());
      }
    }
  }
  if (result.scale_source == "relative" && opt.scale_distance_m > 0 && opt.scale_frame_a < n &&
      opt.scale_frame_b < n) {
    const double d = (pose[opt.scale_frame_a].head<2>() - pose[opt.scale_frame_b].head<2>()).norm();
    if (d > 0) {
      scale = opt.scale_distance_m / d;
      result.scale_source = "distance";
    }
  }
  if (result.scale_source == "relative") {
    // Unit: the first keyframe step.
    const double d = kfn > 1 ? (refined_kf[1].head<2>() - refined_kf[0].head<2>()).norm() : 0.0;
    if (d > 0) scale = 1.0 / d;
  }
  result.scale_factor = scale;

  // ---- jumps: a step far longer than its neighbours'
  std::vector<double> steps(n, 0.0);
  for (int f = 1; f < n; ++f) steps[f] = (pose[f].head<2>() - pose[f - 1].head<2>()).norm();
  const double typical_step = median(std::vector<double>(steps.begin() + std::min(1, n - 1), steps.end()));
  for (int f = 1; f < n; ++f) {
    std::vector<double> local;
    for (int g = std::max(1, f - 10); g <= std::min(n - 1, f + 10); ++g)
      if (g != f) local.push_back(steps[g]);
    const double m = std::max(median(local), 0.25 * typical_step);  // a turn on the spot: steps near 0
    if (m > 0 && steps[f] > opt.jump_factor * m)
      add_flag(frames[f], kFrameJump, "jump: the step is much longer than its neighbours'");
  }

  // ---- output: frame 0 at the origin with heading 0
  const Eigen::Vector3d origin = pose[0];
  auto to_output = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d(p.x() - origin.x(), p.y() - origin.y(), 0.0);
    const Eigen::Vector3d r = rotate_z(d, -origin.z()) * scale;
    return Eigen::Vector3d(r.x(), r.y(), p.z() - origin.z());
  };
  result.path.scale_source = result.scale_source;
  const Eigen::Vector3d coarse_origin = coarse[0];
  result.coarse_poses.resize(n);
  for (int f = 0; f < n; ++f) {
    const Eigen::Vector3d p = to_output(pose[f]);
    frames[f].x = p.x();
    frames[f].y = p.y();
    frames[f].heading = wrap_angle(p.z());
    const Eigen::Vector3d d(coarse[f].x() - coarse_origin.x(), coarse[f].y() - coarse_origin.y(), 0.0);
    const Eigen::Vector3d r = rotate_z(d, -coarse_origin.z()) * scale;
    result.coarse_poses[f] = {r.x(), r.y(), wrap_angle(coarse[f].z() - coarse_origin.z())};
    if (frames[f].flags != kFrameOk) ++result.flagged_frames;
  }
  result.path.frames = std::move(frames);
  report("resection", 1.0);
  result.seconds_geometry = seconds_since(t_start);
  return result;
}

EgomotionResult EgomotionTracker::run(int frame_count, const std::function<cv::Mat(int)>& read,
                                      const EgomotionOptions& options, const EgomotionCallback& callback) {
  EgomotionTracker tracker(options);
  for (int i = 0; i < frame_count; ++i) {
    const cv::Mat frame = read(i);
    tracker.add_frame(frame);
    if (callback && (i % 8 == 0 || i == frame_count - 1) &&
        !callback("frames", double(i + 1) / frame_count)) {
      EgomotionResult r;
      r.cancelled = true;
      return r;
    }
  }
  return tracker.finish(callback);
}

}  // namespace plenopath
