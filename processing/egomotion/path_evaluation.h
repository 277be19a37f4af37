#pragma once
// Scores an estimated camera path against ground truth: frames matched by capture index, a 2-D similarity
// (rotation, uniform scale, translation; never a reflection, so a mirrored path scores as wrong) aligns the
// estimate to the truth by least squares (Umeyama), then absolute trajectory and heading errors.
#include <Eigen/Core>
#include <string>

#include "model/camera_path.h"

namespace plenopath {

struct Similarity2 {
  double scale = 1.0;
  double rotation = 0.0;  // radians, counter-clockwise
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();
  Eigen::Vector2d apply(const Eigen::Vector2d& p) const;
};

// Least-squares similarity taking `from` onto `to` (same size >= 2), proper rotation only.
// With fix_scale the scale stays 1 (a rigid alignment, for paths whose metric scale is to be judged).
Similarity2 align_similarity(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& to,
                             bool fix_scale = false);

struct PathErrors {
  int frames_matched = 0;
  double rot_rms_deg = 0.0;  // heading error after removing the aligning rotation
  double rot_max_deg = 0.0;
  double ate_rms_m = 0.0;  // position error after the similarity alignment, in the truth's metres
  double ate_max_m = 0.0;
  double ate_pct = 0.0;  // ate_rms_m as a percentage of the truth's path length
  double truth_length_m = 0.0;
  double scale = 1.0;            // the aligning scale: 1 + the estimate's relative scale error
  double scale_error_pct = 0.0;  // |1/scale - 1| * 100: how far the estimate's own metres are off
};

// Throws Error when fewer than two frames match.
PathErrors evaluate_path(const CameraPath& estimate, const CameraPath& truth);

}  // namespace plenopath
