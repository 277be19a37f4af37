#include "processing/egomotion/klt_tracks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <sstream>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/util/grey_image.h"
#include "processing/util/statistics.h"
#include "rig/spherical.h"

namespace plenopath {
namespace {
// How far a warp's linear part is from the identity: the largest relative change of a length, or the
// rotation.
double deformation(const cv::Matx22d& a) {
  const LinearStretch s = linear_stretch(a);
  return std::max({std::abs(s.largest - 1.0), std::abs(s.smallest - 1.0), std::abs(s.rotation)});
}
}  // namespace

void KltOptions::check() const {
  const std::string s = "KltOptions.";
  require_option(work_width == 0 || work_width >= 64, s + "work_width", "must be 0 or >= 64", work_width);
  require_option(max_features >= 20, s + "max_features", "must be >= 20", max_features);
  require_option(min_features >= 0 && min_features <= max_features, s + "min_features",
                 "must be in [0, max_features]", min_features);
  require_option(quality_level > 0 && quality_level < 1, s + "quality_level", "must be in (0, 1)",
                 quality_level);
  require_option(exposure_jump > 0, s + "exposure_jump", "must be > 0", exposure_jump);
  require_option(min_distance_px >= 1, s + "min_distance_px", "must be >= 1", min_distance_px);
  require_option(window_px >= 5 && window_px % 2 == 1, s + "window_px", "must be odd and >= 5", window_px);
  require_option(retry_share >= 0 && retry_share <= 1, s + "retry_share", "must be in [0, 1]", retry_share);
  require_option(pyramid_levels >= 0 && pyramid_levels <= 6, s + "pyramid_levels", "must be in [0, 6]",
                 pyramid_levels);
  require_option(min_parallax_flow_px >= 0, s + "min_parallax_flow_px", "must be >= 0", min_parallax_flow_px);
  require_option(max_track_frames == 0 || max_track_frames >= 2, s + "max_track_frames", "must be 0 or >= 2",
                 max_track_frames);
  if (affine_refinement) affine.check();
  require_option(max_affine_correction_px > 0, s + "max_affine_correction_px", "must be > 0",
                 max_affine_correction_px);
  require_option(affine_refresh_deformation > 0, s + "affine_refresh_deformation", "must be > 0",
                 affine_refresh_deformation);
  require_option(max_abs_elevation_deg > 10 && max_abs_elevation_deg <= 90, s + "max_abs_elevation_deg",
                 "must be in (10, 90]", max_abs_elevation_deg);
  require_option(auto_level_frames >= 2, s + "auto_level_frames", "must be >= 2", auto_level_frames);
  require_option(auto_level_spread_deg > 0, s + "auto_level_spread_deg", "must be > 0",
                 auto_level_spread_deg);
  if (level_bearings || auto_level) tilt.check();
}

KltTracker::KltTracker(const KltOptions& options) : options_(options) {
  options.check();
  levelling_ = options_.level_bearings ? Levelling::kOn
               : options_.auto_level   ? Levelling::kDeciding
                                       : Levelling::kOff;
}

void KltTracker::decide_levelling() {
  std::vector<double> pitch, roll;
  for (const TiltEstimate& t : tilts_)
    if (t.valid) {
      pitch.push_back(t.pitch);
      roll.push_back(t.roll);
    }
  // Too few frames with vertical edges to judge: not levelled (nor could most frames be).
  if (pitch.size() * 2 < tilts_.size()) {
    levelling_ = Levelling::kOff;
    return;
  }
  // A robust spread (1.4826 x the median absolute deviation: the standard deviation for Gaussian
  // scatter), so that a few frames whose estimate a passer-by or a fast turn threw off do not level a
  // level camera (the POV-Ray people walk every third frame: RMS 0.287 deg).
  auto robust_sigma = [](const std::vector<double>& v) {
    return 1.4826 * median_absolute_deviation(v, median(v));
  };
  tilt_spread_deg_ = std::hypot(robust_sigma(pitch), robust_sigma(roll)) * 180.0 / M_PI;
  const double threshold = options_.auto_level_spread_deg * 1024.0 / std::max(1, width_);
  levelling_ = tilt_spread_deg_ > threshold ? Levelling::kOn : Levelling::kOff;
}

KltTracker::Packed KltTracker::pack(float x, float y) const {
  auto unit = [&](float v) {
    return static_cast<std::uint16_t>(std::clamp(std::lround(v / quantum_), 0L, 65535L));
  };
  return {unit(x), unit(y)};
}

int KltTracker::start_track(int frame, float x, float y) {
  StoredTrack s;
  s.first_frame = frame;
  s.length = 1;
  if (free_open_.empty()) {
    s.open = static_cast<int>(open_.size());
    open_.emplace_back();
  } else {
    s.open = free_open_.back();
    free_open_.pop_back();
  }
  open_[static_cast<std::size_t>(s.open)].assign(1, pack(x, y));
  stored_.push_back(s);
  moved_frames_.push_back(0);
  return static_cast<int>(stored_.size()) - 1;
}

void KltTracker::extend_track(int track, float x, float y) {
  StoredTrack& s = stored_[static_cast<std::size_t>(track)];
  open_[static_cast<std::size_t>(s.open)].push_back(pack(x, y));
  ++s.length;
}

void KltTracker::close_track(int track) {
  StoredTrack& s = stored_[static_cast<std::size_t>(track)];
  if (s.open < 0) return;
  std::vector<Packed>& o = open_[static_cast<std::size_t>(s.open)];
  s.offset = static_cast<std::int64_t>(closed_.size());
  closed_.insert(closed_.end(), o.begin(), o.end());
  o.clear();
  free_open_.push_back(s.open);
  s.open = -1;
}

TrackObservation KltTracker::observation(int track, int frame) const {
  const StoredTrack& s = stored_[static_cast<std::size_t>(track)];
  const int k = frame - s.first_frame;
  const Packed& p = s.open >= 0 ? open_[static_cast<std::size_t>(s.open)][static_cast<std::size_t>(k)]
                                : closed_[static_cast<std::size_t>(s.offset + k)];
  return {frame, static_cast<float>(p[0] * quantum_), static_cast<float>(p[1] * quantum_)};
}

TrackObservation KltTracker::last_observation(int track) const {
  return observation(track, last_frame(track));
}

std::vector<FeatureTrack> KltTracker::tracks() const {
  std::vector<FeatureTrack> out(stored_.size());
  for (int t = 0; t < track_count(); ++t)
    for (int f = first_frame(t); f <= last_frame(t); ++f)
      out[static_cast<std::size_t>(t)].observations.push_back(observation(t, f));
  return out;
}

TrackMemory KltTracker::memory() const {
  TrackMemory m;
  m.tracks = stored_.size();
  m.observations = closed_.size();
  m.bytes = closed_.size() * sizeof(Packed) + stored_.capacity() * sizeof(StoredTrack) +
            moved_frames_.capacity() * sizeof(int);
  for (const auto& o : open_) {
    m.observations += o.size();
    m.bytes += o.capacity() * sizeof(Packed) + sizeof(o);
  }
  return m;
}

Eigen::Vector3d KltTracker::bearing(const TrackObservation& o) const {
  // OpenCV puts pixel centres on integers; rig/spherical.h puts them at u + 0.5.
  const Eigen::Vector3d b = equirect_to_bearing({o.x + 0.5, o.y + 0.5}, width_, height_);
  if (levelling_ != Levelling::kOn || o.frame < 0 || o.frame >= static_cast<int>(level_from_camera_.size()))
    return b;
  return level_from_camera_[static_cast<std::size_t>(o.frame)] * b;
}

void KltTracker::set_mask(const cv::Mat& mask) {
  if (!mask.empty() && mask.type() != CV_8U) throw Error("KLT: the mask must be 8-bit (CV_8U)");
  mask_ = mask.clone();
  if (!mask_.empty() && width_ > 0 && mask_.size() != cv::Size(width_, height_))
    cv::resize(mask_, mask_, cv::Size(width_, height_), 0, 0, cv::INTER_NEAREST);
}

cv::Mat KltTracker::prepare(const cv::Mat& frame) {
  cv::Mat gray = equirect_at_width(grey_image_8u(frame, "KLT"), options_.work_width);
  if (width_ == 0) {
    width_ = gray.cols;
    height_ = gray.rows;
    quantum_ = width_ / 65536.0;
    pad_ = (options_.window_px / 2 + 2) << options_.pyramid_levels;
    pad_ = std::min(pad_, width_ / 2);
  } else if (gray.cols != width_ || gray.rows != height_) {
    throw Error("KLT: frame size changed within the capture");
  }
  if (options_.normalise_exposure) {
    // Lucas-Kanade assumes constant brightness: an auto-exposure jump of 20-30 % between two frames loses
    // most tracks, and the capture breaks in pieces. The jump is the median brightness ratio of coarse
    // blocks against the frame before (a crowd crossing part of the view changes its blocks only); beyond
    // exposure_jump, this frame and every later one are scaled back by it (the gain accumulates). Slow drift
    // is left alone.
    cv::Mat blocks;
    cv::resize(gray, blocks, cv::Size(64, 32), 0, 0, cv::INTER_AREA);
    if (!previous_blocks_.empty()) {
      std::vector<double> ratios;
      for (int y = 0; y < blocks.rows; ++y)
        for (int x = 0; x < blocks.cols; ++x) {
          const int now = blocks.at<uchar>(y, x), before = previous_blocks_.at<uchar>(y, x);
          if (now > 8 && before > 8 && now < 250 && before < 250) ratios.push_back(double(before) / now);
        }
      const double jump = ratios.size() > blocks.total() / 4 ? median(ratios) : 1.0;
      if (std::abs(jump - 1.0) > options_.exposure_jump)
        exposure_gain_ = std::clamp(exposure_gain_ * jump, 1.0 / 3.0, 3.0);
    }
    previous_blocks_ = blocks;
    if (exposure_gain_ != 1.0) gray.convertTo(gray, CV_8U, exposure_gain_);
  }
  return gray;
}

// The live tracks followed from the previous frame into this one (padded coordinates).
struct KltTracker::LiveFlow {
  std::vector<cv::Point2f> from, to;
  std::vector<char> continued;    // per live track: found, checked back, inside the band and the mask
  std::vector<double> flow;       // flow lengths of the continued tracks
  double turn_flow = 0.0;         // their median sideways flow (a turn), working pixels
  bool moved = false;             // the camera moved (parallax beyond a turn), so tracks age
  std::vector<AffineWarp> warps;  // per live track: its affine refinement (affine_refinement)
  std::vector<char> aligned;      // ... and whether it was accepted
};

bool KltTracker::unmasked(double x, double y) const {
  if (mask_.empty()) return true;
  int mx = static_cast<int>(std::floor(x)) % width_;
  if (mx < 0) mx += width_;
  const int my = std::clamp(static_cast<int>(std::floor(y)), 0, height_ - 1);
  return mask_.at<uchar>(my, mx) != 0;
}

void KltTracker::measure_tilt(const cv::Mat& gray) {
  const TiltEstimate tilt = estimate_tilt(gray, options_.tilt, mask_);
  tilts_.push_back(tilt);
  // A frame without enough vertical edges keeps the last good estimate (the floor changes slowly).
  level_from_camera_.push_back(
      tilt.valid ? level_from_camera(tilt)
                 : (level_from_camera_.empty() ? Eigen::Matrix3d::Identity() : level_from_camera_.back()));
}

KltTracker::LiveFlow KltTracker::follow_live_tracks(const std::vector<cv::Mat>& pyramid,
                                                    double predicted_shift_px, double y_min,
                                                    double y_max) const {
  LiveFlow f;
  const cv::Size window(options_.window_px, options_.window_px);
  for (const cv::Point2f& o : live_positions_) f.from.emplace_back(o.x + pad_, o.y + pad_);
  std::vector<unsigned char> status, status_back;
  std::vector<float> error;
  std::vector<cv::Point2f> back;
  const cv::TermCriteria term(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
  f.to = f.from;
  for (cv::Point2f& p : f.to) p.x += static_cast<float>(predicted_shift_px);
  cv::calcOpticalFlowPyrLK(previous_pyramid_, pyramid, f.from, f.to, status, error, window,
                           options_.pyramid_levels, term, cv::OPTFLOW_USE_INITIAL_FLOW);
  const bool check_back = options_.forward_backward_px > 0;
  if (check_back) {
    back = f.from;
    cv::calcOpticalFlowPyrLK(pyramid, previous_pyramid_, f.to, back, status_back, error, window,
                             options_.pyramid_levels, term, cv::OPTFLOW_USE_INITIAL_FLOW);
  }
  // Which tracks continue, and whether the camera moved: a turn about the vertical shifts the whole
  // panorama sideways by one amount, so what is left after removing the median sideways flow is the
  // translation's parallax.
  f.continued.assign(live_.size(), 0);
  std::vector<double> sideways;
  for (size_t k = 0; k < live_.size(); ++k) {
    bool ok = status[k] != 0;
    if (ok && check_back) {
      const float dx = back[k].x - f.from[k].x, dy = back[k].y - f.from[k].y;
      ok = status_back[k] != 0 &&
           dx * dx + dy * dy <= options_.forward_backward_px * options_.forward_backward_px;
    }
    const float y = f.to[k].y - pad_;
    if (ok && (y < y_min || y > y_max)) ok = false;
    if (ok) ok = unmasked(f.to[k].x - pad_, y);  // entering a masked region ends the track
    f.continued[k] = ok;
    if (!ok) continue;
    f.flow.push_back(std::hypot(f.to[k].x - f.from[k].x, f.to[k].y - f.from[k].y));
    sideways.push_back(f.to[k].x - f.from[k].x);
  }
  f.turn_flow = median(sideways);
  std::vector<double> parallax;
  for (size_t k = 0; k < live_.size(); ++k)
    if (f.continued[k])
      parallax.push_back(std::hypot(f.to[k].x - f.from[k].x - f.turn_flow, f.to[k].y - f.from[k].y));
  f.moved = median(parallax) > options_.min_parallax_flow_px;
  return f;
}

void KltTracker::refine_affine(const cv::Mat& padded, LiveFlow* f) const {
  // One refinement per continued track, each independent: run them on all cores (each result depends only
  // on its track, so the outcome does not depend on the thread count).
  f->warps.assign(live_.size(), AffineWarp());
  f->aligned.assign(live_.size(), 0);
  cv::parallel_for_(cv::Range(0, static_cast<int>(live_.size())), [&](const cv::Range& range) {
    for (int k = range.start; k < range.end; ++k) {
      if (!f->continued[k]) continue;
      AffineWarp& warp = f->warps[k];
      warp.centre = cv::Point2d(f->to[k].x, f->to[k].y);
      warp.linear = live_patches_[k].linear;
      f->aligned[k] = align_affine_patch(live_patches_[k].patch, padded, &warp, options_.affine) &&
                      std::hypot(warp.centre.x - f->to[k].x, warp.centre.y - f->to[k].y) <=
                          options_.max_affine_correction_px;
    }
  });
}

void KltTracker::carry_live_tracks(const cv::Mat& padded, LiveFlow& f, int frame_index,
                                   FrameTrackStats* stats) {
  const bool affine = options_.affine_refinement;
  std::vector<int> still_live;
  std::vector<cv::Point2f> still_positions;
  std::vector<LivePatch> still_patches;
  // Every track ends here but those extended below (a cut track ends too: its continuation is a new one).
  std::vector<char> extended(live_.size(), 0);
  for (size_t k = 0; k < live_.size(); ++k) {
    if (!f.continued[k]) {
      ++stats->lost;
      continue;
    }
    cv::Point2d at(f.to[k].x, f.to[k].y);  // padded coordinates
    bool refined = true;
    cv::Matx22d linear = cv::Matx22d::eye();
    if (affine) {
      refined = f.aligned[k];
      if (refined) {
        at = f.warps[k].centre;
        linear = f.warps[k].linear;
      } else {
        ++affine_failures_;
      }
    }
    if (!unmasked(at.x - pad_, at.y - pad_)) {  // the refinement may have moved it into a masked region
      ++stats->lost;
      continue;
    }
    if (!refined) {
      // Lucas-Kanade's step into this frame is all there is, and it is the biased kind: the track ends at
      // the previous frame, and a new one starts here (sharing no observation with it).
      LivePatch fresh;
      fresh.patch = make_affine_patch(padded, at, options_.affine);
      ++stats->lost;
      if (!fresh.patch.valid) continue;
      float fx = std::fmod(static_cast<float>(at.x) - pad_, static_cast<float>(width_));
      if (fx < 0) fx += width_;
      if (fx >= width_) fx -= width_;
      const float fy = static_cast<float>(at.y) - pad_;
      still_live.push_back(start_track(frame_index, fx, fy));
      still_positions.emplace_back(fx, fy);
      still_patches.push_back(std::move(fresh));
      continue;
    }
    float x = static_cast<float>(at.x) - pad_;
    const float y = static_cast<float>(at.y) - pad_;
    x = std::fmod(x, static_cast<float>(width_));
    if (x < 0) x += width_;
    if (x >= width_) x -= width_;
    int& age = moved_frames_[live_[k]];
    if (f.moved) ++age;
    // Each track's own limit, between half and all of max_track_frames: tracks born together (all of
    // frame 0's) must not be cut together, or the points before and after that frame would share no
    // track, and the two halves of the map would each keep their own scale. Only frames in which the
    // camera moved count: a turn on the spot does not change how a feature looks, and cutting every
    // track during one would leave no point seen both before and after it (the scale would be lost).
    const int limit = options_.max_track_frames -
                      static_cast<int>((static_cast<std::uint64_t>(live_[k]) * 2654435761u) %
                                       static_cast<std::uint64_t>(options_.max_track_frames / 2 + 1));
    if (options_.max_track_frames > 0 && age >= limit) {
      // Continue as a new point from here (see KltOptions::max_track_frames), with a new patch when
      // refining. The new track starts one frame back: its first pair of frames is then measured by the
      // same track.
      LivePatch next_patch;
      if (affine) {
        next_patch.patch = make_affine_patch(padded, at, options_.affine);
        if (!next_patch.patch.valid) {
          ++stats->lost;
          continue;
        }
      }
      const int next = start_track(frame_index - 1, live_positions_[k].x, live_positions_[k].y);
      extend_track(next, x, y);
      moved_frames_[static_cast<std::size_t>(next)] = 1;
      still_live.push_back(next);
      still_positions.emplace_back(x, y);
      if (affine) still_patches.push_back(std::move(next_patch));
    } else {
      extend_track(live_[k], x, y);
      extended[k] = 1;
      still_live.push_back(live_[k]);
      still_positions.emplace_back(x, y);
      if (affine) {
        still_patches.push_back(std::move(live_patches_[k]));
        still_patches.back().linear = linear;
        // Deformed this much, the patch as first seen is a poor template: cut a new one here (the point
        // stays the same; its observations so far and from now on are each aligned, not chained).
        if (deformation(linear) > options_.affine_refresh_deformation) {
          LivePatch fresh;
          fresh.patch = make_affine_patch(padded, at, options_.affine);
          if (fresh.patch.valid) still_patches.back() = std::move(fresh);
        }
      }
    }
  }
  for (size_t k = 0; k < live_.size(); ++k)
    if (!extended[k]) close_track(live_[k]);
  stats->tracked = static_cast<int>(still_live.size());
  stats->median_flow_px = median(f.flow);
  live_ = std::move(still_live);
  live_positions_ = std::move(still_positions);
  live_patches_ = std::move(still_patches);
}

void KltTracker::detect_new_tracks(const cv::Mat& gray, const cv::Mat& padded, int frame_index, double y_min,
                                   double y_max, FrameTrackStats* stats) {
  cv::Mat mask(gray.size(), CV_8U, cv::Scalar(0));
  mask.rowRange(static_cast<int>(std::ceil(y_min)), static_cast<int>(std::floor(y_max))).setTo(255);
  if (!mask_.empty()) cv::bitwise_and(mask, mask_, mask);
  for (const cv::Point2f& o : live_positions_)
    cv::circle(mask, cv::Point(cvRound(o.x), cvRound(o.y)), options_.min_distance_px, cv::Scalar(0), -1);
  std::vector<cv::Point2f> corners;
  const int wanted = options_.max_features - static_cast<int>(live_.size());
  cv::goodFeaturesToTrack(gray, corners, wanted, options_.quality_level, options_.min_distance_px, mask, 5);
  stats->corners_available = static_cast<int>(corners.size());
  if (!corners.empty()) {
    cv::cornerSubPix(gray, corners, cv::Size(3, 3), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 10, 0.02));
  }
  for (const cv::Point2f& c : corners) {
    if (!unmasked(c.x, c.y)) continue;  // the sub-pixel refinement may have moved it into a masked region
    if (options_.affine_refinement) {
      LivePatch lp;
      lp.patch = make_affine_patch(padded, cv::Point2d(c.x + pad_, c.y + pad_), options_.affine);
      if (!lp.patch.valid) continue;  // too little structure to refine: not worth a track
      live_patches_.push_back(std::move(lp));
    }
    live_.push_back(start_track(frame_index, c.x, c.y));
    live_positions_.push_back(c);
    ++stats->detected;
  }
}

FrameTrackStats KltTracker::add_frame(const cv::Mat& frame, double predicted_shift_px) {
  const cv::Mat gray = prepare(frame);
  const int frame_index = frame_count_++;
  if (!mask_.empty() && mask_.size() != gray.size())
    cv::resize(mask_, mask_, gray.size(), 0, 0, cv::INTER_NEAREST);
  if (levelling_ != Levelling::kOff) measure_tilt(gray);
  if (levelling_ == Levelling::kDeciding && frame_count_ >= options_.auto_level_frames) decide_levelling();
  // Wrap horizontally (the seam), replicate vertically (the poles are not tracked anyway).
  cv::Mat padded;
  cv::copyMakeBorder(gray, padded, 0, 0, pad_, pad_, cv::BORDER_WRAP);
  cv::copyMakeBorder(padded, padded, pad_, pad_, 0, 0, cv::BORDER_REPLICATE);
  std::vector<cv::Mat> pyramid;
  cv::buildOpticalFlowPyramid(padded, pyramid, cv::Size(options_.window_px, options_.window_px),
                              options_.pyramid_levels, true);
  const double max_elev = options_.max_abs_elevation_deg * M_PI / 180.0;
  const double y_min = (M_PI / 2 - max_elev) / M_PI * height_, y_max = height_ - y_min;

  FrameTrackStats stats;
  if (!live_.empty() && !previous_pyramid_.empty()) {
    LiveFlow flow = follow_live_tracks(pyramid, predicted_shift_px, y_min, y_max);
    // Guesses closer than this reach the same minimum: the pyramid's coarsest level covers the difference.
    const double same_guess_px = 0.25 * options_.window_px;
    if (options_.retry_share > 0 && flow.flow.size() < options_.retry_share * live_.size() &&
        std::abs(last_turn_px_ - predicted_shift_px) > same_guess_px) {
      LiveFlow retried = follow_live_tracks(pyramid, last_turn_px_, y_min, y_max);
      if (retried.flow.size() > flow.flow.size()) flow = std::move(retried);
    }
    if (!flow.flow.empty()) last_turn_px_ = flow.turn_flow;
    if (options_.affine_refinement) refine_affine(padded, &flow);
    carry_live_tracks(padded, flow, frame_index, &stats);
  } else {
    for (int t : live_) close_track(t);  // no previous frame to track from (cannot happen after the first)
    live_.clear();
    live_positions_.clear();
    live_patches_.clear();
  }
  if (static_cast<int>(live_.size()) < options_.min_features)
    detect_new_tracks(gray, padded, frame_index, y_min, y_max, &stats);
  else
    stats.corners_available = static_cast<int>(live_.size());
  previous_pyramid_ = std::move(pyramid);
  return stats;
}

}  // namespace plenopath
