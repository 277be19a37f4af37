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
#include "model/option_check.h"
#include "processing/egomotion/descriptor_store.h"
#include "processing/egomotion/egomotion_steps.h"
#include "processing/util/grey_image.h"
#include "processing/util/statistics.h"

namespace plenopath {
using namespace egomotion_steps;
namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

void PieceOptions::check() const {
  const std::string s = "PieceOptions.";
  require_option(min_link_tracks >= 1, s + "min_link_tracks", "must be >= 1", min_link_tracks);
  require_option(min_piece_frames >= 2, s + "min_piece_frames", "must be >= 2", min_piece_frames);
  require_option(join_search_frames >= 0, s + "join_search_frames", "must be >= 0", join_search_frames);
  require_option(join_max_pairs >= 1, s + "join_max_pairs", "must be >= 1", join_max_pairs);
  require_option(join_min_inliers >= 8, s + "join_min_inliers", "must be >= 8", join_min_inliers);
  require_option(join_agreement_deg > 0, s + "join_agreement_deg", "must be > 0", join_agreement_deg);
}

void EgomotionOptions::check() const {
  loop.check();
  static_mask.check();
  pieces.check();
  ring.check();
  klt.check();
  refinement.check();
  const std::string s = "EgomotionOptions.";
  require_option(keyframe_parallax_deg > 0, s + "keyframe_parallax_deg", "must be > 0",
                 keyframe_parallax_deg);
  require_option(keyframe_max_turn_deg > 0, s + "keyframe_max_turn_deg", "must be > 0",
                 keyframe_max_turn_deg);
  require_option(keyframe_min_shared > 0 && keyframe_min_shared < 1, s + "keyframe_min_shared",
                 "must be in (0, 1)", keyframe_min_shared);
  require_option(max_step_ratio > 1, s + "max_step_ratio", "must be > 1", max_step_ratio);
  require_option(max_step_spread >= 0, s + "max_step_spread", "must be >= 0", max_step_spread);
  require_option(step_map_check_factor == 0 || step_map_check_factor >= 1, s + "step_map_check_factor",
                 "must be 0 (no check) or >= 1", step_map_check_factor);
  require_option(floor_step_min_points >= 0, s + "floor_step_min_points", "must be >= 0 (0 = never)",
                 floor_step_min_points);
  require_option(floor_step_max_spread > 0, s + "floor_step_max_spread", "must be > 0",
                 floor_step_max_spread);
  require_option(step_map_check_deg > 0 && step_map_check_deg < 180, s + "step_map_check_deg",
                 "must be in (0, 180)", step_map_check_deg);
  require_option(step_direction_prior_share >= 0 && step_direction_prior_share <= 1,
                 s + "step_direction_prior_share", "must be in [0, 1]", step_direction_prior_share);
  require_option(max_step_turn_disagreement_deg > 0, s + "max_step_turn_disagreement_deg", "must be > 0",
                 max_step_turn_disagreement_deg);
  require_option(min_triangulation_deg > 0, s + "min_triangulation_deg", "must be > 0",
                 min_triangulation_deg);
  require_option(max_initial_error_deg > 0, s + "max_initial_error_deg", "must be > 0",
                 max_initial_error_deg);
  require_option(min_point_keyframes >= 2, s + "min_point_keyframes", "must be >= 2", min_point_keyframes);
  require_option(resection_min_points >= 3, s + "resection_min_points", "must be >= 3", resection_min_points);
  require_option(camera_height_m >= 0, s + "camera_height_m", "must be >= 0 (0 = unknown)", camera_height_m);
  require_option(scale_distance_m >= 0, s + "scale_distance_m", "must be >= 0", scale_distance_m);
  if (scale_distance_m > 0) {
    require_option(scale_frame_a >= 0, s + "scale_frame_a", "must be a frame (>= 0) with scale_distance_m",
                   scale_frame_a);
    require_option(scale_frame_b >= 0 && scale_frame_b != scale_frame_a, s + "scale_frame_b",
                   "must be a frame (>= 0) other than scale_frame_a", scale_frame_b);
  }
  require_option(jump_factor > 1, s + "jump_factor", "must be > 1", jump_factor);
  require_option(moving_outlier_fraction > 0 && moving_outlier_fraction <= 1, s + "moving_outlier_fraction",
                 "must be in (0, 1]", moving_outlier_fraction);
  require_option(mask.empty() || mask.type() == CV_8U, s + "mask", "must be 8-bit (CV_8U)",
                 mask.empty() ? std::string("empty") : std::to_string(mask.type()));
}

struct EgomotionTracker::State {
  explicit State(const EgomotionOptions& o) : options(o), klt(o.klt), auto_mask(o.static_mask) {}
  EgomotionOptions options;
  KltTracker klt;
  // Masking (static_mask.h): frames are held until the mask is decided, then processed.
  StaticMaskEstimator auto_mask;
  std::vector<cv::Mat> held;  // working-size grey frames
  bool mask_decided = false;
  cv::Mat mask;                      // working size, 255 = usable; empty = everything
  std::vector<double> ring_weights;  // per ring column (with a mask)
  void decide_mask(cv::Size size);
  void process(const cv::Mat& gray);
  std::unique_ptr<RingRegistrar> rings;  // created once the mask (and so the column weights) is decided
  int processed = 0;                     // frames through process()
  std::vector<FrameTrackStats> stats;
  std::vector<int> live_after;  // live tracks after each frame (texture measure)
  DescriptorStore described;    // for loop closure and for joining across a stretch without tracks
  // The previous frame's working image and its live tracks, so that the frame before a dropout can be
  // described when the dropout is seen.
  cv::Mat previous_gray;
  std::vector<int> previous_live;
  std::vector<cv::Point2f> previous_positions;
  double seconds_frames = 0.0;
};

EgomotionTracker::EgomotionTracker(const EgomotionOptions& options) {
  options.check();
  state_ = std::make_unique<State>(options);
}
EgomotionTracker::~EgomotionTracker() = default;
int EgomotionTracker::frame_count() const {
  return state_->processed + static_cast<int>(state_->held.size());
}

void EgomotionTracker::add_frame(const cv::Mat& bgr) {
  const auto t0 = Clock::now();
  State& s = *state_;
  const int count = frame_count();
  if (bgr.empty()) throw Error("egomotion: frame " + std::to_string(count) + " is empty");
  if (bgr.cols != 2 * bgr.rows)
    throw Error("egomotion: frame " + std::to_string(count) + " is not equirectangular 2:1");
  const cv::Mat gray = equirect_at_width(grey_image(bgr, "egomotion"), s.options.klt.work_width);
  if (!s.mask_decided) {
    if (s.options.static_mask.frames > 0) {  // hold the frames until the automatic mask is decided
      s.auto_mask.add(gray);
      s.held.push_back(gray);
      if (s.auto_mask.ready()) {
        s.decide_mask(gray.size());
        for (const cv::Mat& g : s.held) s.process(g);
        s.held.clear();
      }
      s.seconds_frames += seconds_since(t0);
      return;
    }
    s.decide_mask(gray.size());
  }
  s.process(gray);
  s.seconds_frames += seconds_since(t0);
}

void EgomotionTracker::State::decide_mask(cv::Size size) {
  mask_decided = true;
  cv::Mat author;
  if (!options.mask.empty()) cv::resize(options.mask, author, size, 0, 0, cv::INTER_NEAREST);
  mask = combine_masks(author, options.static_mask.frames > 0 ? auto_mask.mask(size) : cv::Mat());
  if (!mask.empty()) {
    if (cv::countNonZero(mask) == 0) throw Error("egomotion: the mask leaves no pixel to track");
    klt.set_mask(mask);
    ring_weights = ring_column_weights(mask, options.ring);
  }
  rings = std::make_unique<RingRegistrar>(options.ring, ring_weights.empty() ? nullptr : &ring_weights);
}

void EgomotionTracker::State::process(const cv::Mat& gray) {
  State& s = *this;
  // The turn since the previous frame, from the rings, starts the KLT search (fast turns). The rings search
  // around the turn the tracks made into the frame before (a corner taken at 20-40 deg a frame).
  const double expected_shift =
      s.klt.width() > 0 ? s.klt.last_turn_px() * gray.cols / static_cast<double>(s.klt.width()) : 0.0;
  const RingShift shift = s.rings->add(
      s.mask.empty() ? make_ring_image(gray, s.options.ring) : make_ring_image(gray, s.options.ring, s.mask),
      expected_shift);
  const double predicted_shift = shift.valid && shift.peak >= s.options.ring.min_peak ? shift.shift_px : 0.0;
  const FrameTrackStats st = s.klt.add_frame(gray, predicted_shift);
  s.stats.push_back(st);
  const int index = s.processed++;
  auto described_last = [&](int frame) { return s.described.last_frame() == frame; };
  // Where the tracks stop, both sides are described (capture_pieces.cpp matches them).
  const bool dropout = index > 0 && st.tracked < s.options.pieces.min_link_tracks;
  if (dropout && !described_last(index - 1) && !s.previous_gray.empty())
    s.described.add(describe_frame(s.previous_gray, index - 1, s.previous_live, s.previous_positions));
  std::vector<cv::Point2f> positions = s.klt.live_positions();
  if ((s.options.loop.enabled && index % s.options.loop.descriptor_stride == 0) || dropout)
    s.described.add(describe_frame(gray, index, s.klt.live_tracks(), positions));
  s.previous_gray = gray.clone();
  s.previous_live = s.klt.live_tracks();
  s.previous_positions = std::move(positions);
  s.live_after.push_back(st.tracked + st.detected);
}

EgomotionResult EgomotionTracker::finish(Progress& progress) {
  const auto t_start = Clock::now();
  State& s = *state_;
  if (!s.mask_decided && !s.held.empty()) {  // fewer frames than the static mask waits for
    s.decide_mask(s.held.front().size());
    for (const cv::Mat& g : s.held) s.process(g);
    s.held.clear();
  }
  const EgomotionOptions& opt = s.options;
  EgomotionResult result;
  result.mask = s.mask;
  result.static_mask_fraction =
      s.mask.empty() ? 0.0 : 1.0 - cv::countNonZero(s.mask) / double(s.mask.total());
  result.levelled = s.klt.levelling();
  result.tilt_spread_deg = s.klt.tilt_spread_deg();
  result.seconds_per_frame_stage = s.seconds_frames;
  result.track_memory_mb = s.klt.memory().bytes / 1048576.0;
  const int n = s.processed;
  if (n == 0) throw Error("egomotion: the capture has no frames");
  TrackerMeasurements m;
  m.options = &opt;
  const int width = s.klt.width();
  m.pixel_angle = 2.0 * M_PI / std::max(1, width);
  // Angular tolerances are set for a 1024-wide working image; a coarser one measures coarser, and holding
  // it to sub-pixel tolerances leaves RANSAC too few inliers and puts every residual in the robust loss's
  // flat tail.
  m.coarseness = std::max(1.0, 1024.0 / std::max(1, width));
  m.two_view = opt.two_view;
  m.two_view.threshold *= m.coarseness;
  m.refinement = opt.refinement;
  m.refinement.loss_scale *= m.coarseness;
  m.refinement.outlier_threshold *= m.coarseness;

  // ---- 1. coarse headings
  // Progress: the headings 5 %, the pieces the rest (each by its share of the frames).
  progress.checkpoint(0.0, "headings");
  const RingHeadings rh = s.rings->solve();
  result.ring_headings = rh.headings;
  progress.checkpoint(0.05, "headings");

  const TrackView view(s.klt, n);
  m.view = &view;
  m.described = &s.described;
  std::mt19937 rng(opt.seed);
  std::vector<PathFrame> frames(n);
  for (int i = 0; i < n; ++i) frames[i].index = i;
  m.textureless.assign(n, false);
  for (int i = 0; i < n; ++i) {
    if (s.live_after[i] < opt.textureless_corners) {
      m.textureless[i] = true;
      add_flag(frames[i], kFrameTextureless,
               "textureless: " + std::to_string(s.live_after[i]) + " trackable corners");
    }
    if (i > 0 && s.stats[i].tracked > 0 && s.stats[i].median_flow_px < opt.duplicate_flow_px)
      add_flag(frames[i], kFrameDuplicate, "duplicate: no motion since the previous frame (stopped)");
    if (i > 0 && rh.step_peak[i] < opt.ring.min_peak)
      add_flag(frames[i], kFrameJump, "jump: the ring image does not register with the previous frame");
  }

  // ---- 1b. frame-to-frame turns (frame_turns.cpp)
  measure_frame_turns(rh.headings, rng, &m);
  result.tracked_headings = m.heading;

  // ---- where the images stop connecting (capture_pieces.cpp)
  const CapturePieces pieces = find_capture_pieces(s.stats, m, rng);
  result.joins = static_cast<int>(pieces.joins.size());
  for (const FrameTrackStats& st : s.stats) result.continued_tracks.push_back(st.tracked);

  // ---- 2-5 per piece (piece_solver.cpp)
  const int piece_count = static_cast<int>(pieces.pieces.size());
  result.coarse_poses.resize(n);
  for (int k = 0; k < piece_count; ++k) {
    const PiecePlan& plan = pieces.pieces[k];
    const double share = double(plan.last - plan.first + 1) / n, before = double(plan.first) / n;
    SubProgress piece_progress(progress, 0.05 + 0.95 * before, 0.05 + 0.95 * (before + share),
                               piece_count == 1 ? std::string() : "piece " + std::to_string(k + 1));
    const PieceSolution solved = solve_piece(plan, pieces.joins, m, &frames, rng, piece_progress);
    for (int f = plan.first; f <= plan.last; ++f) {
      const Eigen::Vector3d& p = solved.poses[f - plan.first];
      frames[f].x = p.x();
      frames[f].y = p.y();
      frames[f].heading = wrap_angle(p.z());
      frames[f].piece = k;
      const Eigen::Vector3d& c = solved.coarse[f - plan.first];
      result.coarse_poses[f] = {c.x(), c.y(), wrap_angle(c.z())};
    }
    result.keyframes.insert(result.keyframes.end(), solved.keyframes.begin(), solved.keyframes.end());
    result.points += solved.points;
    for (PathPoint p : solved.tracked_points) {
      p.piece = k;
      result.tracked_points.push_back(p);
    }
    result.observations += solved.observations;
    result.merged_points += solved.merged_points;
    result.steps_from_points += solved.steps_from_points;
    result.steps_on_floor += solved.steps_on_floor;
    result.loop_closures += static_cast<int>(solved.loop_frames.size());
    result.loop_frames.insert(result.loop_frames.end(), solved.loop_frames.begin(), solved.loop_frames.end());
    if (k == 0) {
      result.refinement = solved.refinement;
      result.scale_source = solved.scale_source;
      result.scale_factor = solved.scale_factor;
      result.floor_points = solved.floor_points;
    } else {
      result.refinement.windows += solved.refinement.windows;
      result.refinement.iterations += solved.refinement.iterations;
      result.refinement.tilt_prior_used_deg =
          std::max(result.refinement.tilt_prior_used_deg, solved.refinement.tilt_prior_used_deg);
      result.refinement.floor_sigma_used =
          std::max(result.refinement.floor_sigma_used, solved.refinement.floor_sigma_used);
      add_flag(frames[plan.first], kFramePieceStart, "piece start: " + plan.break_reason);
    }
    if (piece_count > 1) {
      PathPiece piece;
      piece.first_index = plan.first;
      piece.last_index = plan.last;
      piece.placed = k == 0;
      piece.scale_source = solved.scale_source;
      piece.scale_factor = solved.scale_factor;
      piece.break_reason = plan.break_reason;
      result.path.pieces.push_back(std::move(piece));
    }
  }
  result.path.scale_source = result.scale_source;
  for (const PathFrame& f : frames)
    if (f.flags != kFrameOk) ++result.flagged_frames;
  result.path.frames = std::move(frames);
  result.seconds_geometry = seconds_since(t_start);
  return result;
}

EgomotionResult EgomotionTracker::run(int frame_count, const std::function<cv::Mat(int)>& read,
                                      const EgomotionOptions& options, Progress& progress) {
  EgomotionTracker tracker(options);
  // Reading and tracking the frames is about half the work, the geometric steps the rest.
  SubProgress frames_progress(progress, 0.0, 0.5);
  for (int i = 0; i < frame_count; ++i) {
    const cv::Mat frame = read(i);
    tracker.add_frame(frame);
    if (i % 8 == 0 || i == frame_count - 1) frames_progress.checkpoint(double(i + 1) / frame_count, "frames");
  }
  SubProgress finish_progress(progress, 0.5, 1.0);
  return tracker.finish(finish_progress);
}

}  // namespace plenopath
