#include "processing/egomotion/loop_closure.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/features2d.hpp>
#include <sstream>

#include "model/option_check.h"
#include "processing/egomotion/descriptor_store.h"
#include "processing/util/statistics.h"

namespace plenopath {
namespace {

double azimuth(const Eigen::Vector3d& b) { return std::atan2(b.y(), b.x()); }

}  // namespace

std::vector<std::pair<int, int>> match_descriptors(const cv::Mat& a, const cv::Mat& b, double ratio) {
  std::vector<std::pair<int, int>> out;
  if (a.rows < 2 || b.rows < 2) return out;
  cv::BFMatcher matcher(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> ab, ba;
  matcher.knnMatch(a, b, ab, 2);
  matcher.knnMatch(b, a, ba, 2);
  std::vector<int> best_in_a(b.rows, -1);
  for (const auto& m : ba)
    if (m.size() == 2 && m[0].distance < ratio * m[1].distance) best_in_a[m[0].queryIdx] = m[0].trainIdx;
  for (const auto& m : ab)
    if (m.size() == 2 && m[0].distance < ratio * m[1].distance && best_in_a[m[0].trainIdx] == m[0].queryIdx)
      out.emplace_back(m[0].queryIdx, m[0].trainIdx);
  return out;
}

void LoopClosureOptions::check() const {
  const std::string s = "LoopClosureOptions.";
  require_option(descriptor_stride >= 1, s + "descriptor_stride", "must be >= 1", descriptor_stride);
  require_option(max_distance_steps > 0, s + "max_distance_steps", "must be > 0", max_distance_steps);
  require_option(min_travel_steps > max_distance_steps, s + "min_travel_steps",
                 "must exceed max_distance_steps", min_travel_steps);
  require_option(max_turn_disagreement_deg > 0, s + "max_turn_disagreement_deg", "must be > 0",
                 max_turn_disagreement_deg);
  require_option(min_inliers >= 8, s + "min_inliers", "must be >= 8", min_inliers);
  require_option(ratio > 0 && ratio <= 1, s + "ratio", "must be in (0, 1]", ratio);
  require_option(spacing_frames >= 0, s + "spacing_frames", "must be >= 0", spacing_frames);
}

FrameDescriptors describe_frame(const cv::Mat& gray, int frame, const std::vector<int>& tracks,
                                const std::vector<cv::Point2f>& positions) {
  FrameDescriptors out;
  out.frame = frame;
  std::vector<cv::KeyPoint> keypoints;
  keypoints.reserve(tracks.size());
  for (std::size_t k = 0; k < tracks.size(); ++k)
    keypoints.emplace_back(positions[k], 31.f, 0.f, 0.f, 0,
                           static_cast<int>(k));  // upright: turns are shifts
  // One pyramid level: the tracks' corners are at the working image's scale.
  thread_local cv::Ptr<cv::ORB> orb = cv::ORB::create(1000, 1.2f, 1, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, 20);
  orb->compute(gray, keypoints, out.descriptors);  // drops keypoints too near the border
  for (const cv::KeyPoint& k : keypoints) out.tracks.push_back(tracks[static_cast<std::size_t>(k.class_id)]);
  return out;
}

bool verify_frame_match(const FrameDescriptors& fa, const FrameDescriptors& fb,
                        const std::function<Eigen::Vector3d(int, int)>& bearing, double turn_guess,
                        double max_turn_error, int min_inliers, double ratio,
                        const PlanarTwoViewOptions& two_view, std::mt19937& rng, LoopMatch* match,
                        double* direction) {
  if (direction) *direction = std::numeric_limits<double>::quiet_NaN();
  if (fa.descriptors.empty() || fb.descriptors.empty()) return false;
  const std::vector<std::pair<int, int>> matches = match_descriptors(fa.descriptors, fb.descriptors, ratio);
  if (static_cast<int>(matches.size()) < min_inliers) return false;
  std::vector<Eigen::Vector3d> ba, bb;
  std::vector<double> azimuth_change;
  for (const auto& [ia, ib] : matches) {
    ba.push_back(bearing(fa.tracks[static_cast<std::size_t>(ia)], fa.frame));
    bb.push_back(bearing(fb.tracks[static_cast<std::size_t>(ib)], fb.frame));
    azimuth_change.push_back(std::remainder(azimuth(ba.back()) - azimuth(bb.back()), 2 * M_PI));
  }
  if (!std::isfinite(turn_guess)) turn_guess = median(azimuth_change);  // no prior: the matches' own
  PlanarRelativePose rel = estimate_planar_relative_pose(ba, bb, turn_guess, two_view, rng);
  std::vector<bool> inlier = rel.inlier;
  double turn = rel.turn;
  if (!rel.valid) {
    // Back on the very spot: no parallax to verify a direction with, but a pure turn must explain the
    // matches (each bearing rotated by the median azimuth change lands on its match).
    turn = median(azimuth_change);
    inlier.assign(ba.size(), false);
    int count = 0;
    for (std::size_t k = 0; k < ba.size(); ++k) {
      const double c = std::cos(-turn), s = std::sin(-turn);
      const Eigen::Vector3d r(c * ba[k].x() - s * ba[k].y(), s * ba[k].x() + c * ba[k].y(), ba[k].z());
      inlier[k] = std::atan2(r.cross(bb[k]).norm(), r.dot(bb[k])) < 3 * two_view.threshold;
      count += inlier[k];
    }
    if (count < min_inliers || count < static_cast<int>(ba.size()) / 2) return false;
  } else if (rel.inliers < min_inliers) {
    return false;
  }
  if (std::abs(std::remainder(turn - turn_guess, 2 * M_PI)) > max_turn_error) return false;
  match->frame_a = fa.frame;
  match->frame_b = fb.frame;
  match->turn = turn;
  match->track_pairs.clear();
  for (std::size_t k = 0; k < matches.size(); ++k)
    if (inlier[k])
      match->track_pairs.emplace_back(fa.tracks[static_cast<std::size_t>(matches[k].first)],
                                      fb.tracks[static_cast<std::size_t>(matches[k].second)]);
  if (direction && rel.valid) *direction = rel.direction;
  return true;
}

std::vector<LoopMatch> find_loop_closures(const DescriptorStore& store, int first_frame, int last_frame,
                                          const std::function<Eigen::Vector3d(int)>& pose,
                                          const std::function<double(int)>& travelled,
                                          const std::function<Eigen::Vector3d(int, int)>& bearing,
                                          double typical_step, const PlanarTwoViewOptions& two_view,
                                          const LoopClosureOptions& options, std::mt19937& rng) {
  std::vector<LoopMatch> out;
  // The store's entries in range (their descriptors stay on disk until a candidate pair is verified).
  std::vector<int> entries;
  for (int i = 0; i < store.size(); ++i)
    if (store.frame(i) >= first_frame && store.frame(i) <= last_frame) entries.push_back(i);
  if (!options.enabled || !(typical_step > 0) || entries.size() < 2) return out;
  const double max_distance = options.max_distance_steps * typical_step;
  const double min_travel = options.min_travel_steps * typical_step;
  const double max_turn_error = options.max_turn_disagreement_deg * M_PI / 180.0;
  std::vector<Eigen::Vector3d> poses;
  std::vector<double> along;
  for (int i : entries) {
    poses.push_back(pose(store.frame(i)));
    along.push_back(travelled(store.frame(i)));
  }
  int next_allowed = 0;
  for (std::size_t b = 1; b < entries.size(); ++b) {
    if (store.frame(entries[b]) < next_allowed || !store.has_descriptors(entries[b])) continue;
    // The nearest earlier place, far enough back along the path.
    int best = -1;
    double best_distance = max_distance;
    for (std::size_t a = 0; a < b; ++a) {
      if (along[b] - along[a] < min_travel) break;  // `along` grows: the rest are nearer along the path
      const double d = (poses[a].head<2>() - poses[b].head<2>()).norm();
      if (d < best_distance) {
        best_distance = d;
        best = static_cast<int>(a);
      }
    }
    if (best < 0) continue;
    const FrameDescriptors fa = store.load(entries[static_cast<std::size_t>(best)]);
    const FrameDescriptors fb = store.load(entries[b]);
    const double turn_guess =
        std::remainder(poses[b].z() - poses[static_cast<std::size_t>(best)].z(), 2 * M_PI);
    LoopMatch m;
    if (!verify_frame_match(fa, fb, bearing, turn_guess, max_turn_error, options.min_inliers, options.ratio,
                            two_view, rng, &m))
      continue;
    out.push_back(std::move(m));
    next_allowed = fb.frame + options.spacing_frames;
  }
  return out;
}

}  // namespace plenopath
