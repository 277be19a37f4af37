#pragma once
// Step 3: global refinement of planar poses (x, y, heading) and 3-D points with Ceres (bundle adjustment on
// bearings). Angular residuals (bearing_cost.h), a robust loss, the gauge fixed (first pose held, the scale
// held by a soft prior), sparse Schur. Long captures are refined in overlapping windows of keyframes first
// (each window's leading poses held from the previous window), then in one global pass: a bundle, or for
// captures too long for one (tens of thousands of frames), a pose graph on the keyframes.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "processing/util/progress.h"

namespace plenopath {

struct BundleObservation {
  int pose = 0;
  int point = 0;
  // Unit, camera frame, kept in single precision (1e-7 rad, far below a pixel's 6e-3 at 1024 wide): 20 bytes
  // an observation instead of 32, and a 100 000-frame walk makes over 20 million of them.
  Eigen::Vector3f bearing_f = Eigen::Vector3f::UnitX();
  BundleObservation() = default;
  BundleObservation(int pose_index, int point_index, const Eigen::Vector3d& unit_bearing)
      : pose(pose_index), point(point_index), bearing_f(unit_bearing.cast<float>()) {}
  Eigen::Vector3d bearing() const { return bearing_f.cast<double>(); }
};

struct BundleProblem {
  std::vector<Eigen::Vector3d> poses;   // (x, y, heading) per keyframe
  std::vector<Eigen::Vector3d> points;  // plan frame; the camera centres are at z = 0
  std::vector<BundleObservation> observations;
  // (pitch, roll) per pose, radians, when the refinement estimates them (RefinementOptions::tilt_prior_deg);
  // empty = level cameras (the planar model).
  std::vector<Eigen::Vector2d> tilts;
  // Points on the floor (indices into points; floor_points.h finds them), held to one level below the
  // camera centres by RefinementOptions::floor_sigma. Empty = no floor prior.
  std::vector<int> floor_points;
};

struct RefinementOptions {
  double loss_scale = 0.003;  // Cauchy loss scale, radians (about half a pixel at 1024 wide)
  int window_keyframes = 80;  // keyframes per window in the windowed pass (0 = no windowed pass)
  int window_overlap = 20;    // keyframes shared by consecutive windows (held in the later one)
  int window_max_iterations = 15;
  int global_max_iterations = 20;  // 0 = skip the global pass (the windowed pass has done most of the work)
  // Memory: Ceres keeps about a kilobyte per observation. Above this many, the global pass sees each point
  // through a few of its observations (first, last, evenly between), and windows with both ends held then
  // refine every pose against all observations (0 = always all). 10 000 frames make about 2.3 million.
  // When even three observations a point are more than this, the global pass is a pose graph on the
  // keyframes instead (pose_graph.h), the revisited places measured by local bundles.
  int global_max_observations = 600000;
  // After the global pass, observations farther off than this (radians) are dropped and the global pass is
  // repeated (0 = keep all).
  double outlier_threshold = 0.012;
  // With the observations, whole points whose residual RMS exceeds this many times the median point's are
  // dropped (0 = none): "corners" where an edge crosses a farther surface slide as the camera moves and
  // fit a little badly everywhere. 1.5 on the 400-frame walks: scale error 1.19 -> 0.24 % with noise and
  // people, ATE 0.043 -> 0.042 % (1024) and 0.043 -> 0.037 % (2048).
  double point_outlier_factor = 1.5;
  // Ceres threads. 1 keeps the result bit-for-bit reproducible: with more, Ceres sums costs and gradients
  // per thread in whatever order the threads finish, the last bits differ run to run, and those differences
  // grow through the outlier pass and the resection's inlier decisions (0.19 deg vs 1.42 deg seen).
  int threads = 1;
  // > 0: each pose's pitch and roll are estimated too, held near level by a prior of this spread (degrees):
  // a trolley rocking on an uneven floor, a hand-held pole. 0 = level cameras. bench_nuisances (150 frames,
  // 512 wide; heading deg / ATE % / scale %), 0 -> 2: clean 0.045/0.015/0.30 -> 0.047/0.018/0.35;
  // 1 deg wobble + 1.5 deg bumps 0.32/0.47/2.1 -> 0.18/0.40/0.33; all nuisances 0.22/0.32/1.7 ->
  // 0.066/0.078/0.07. About 30 % more time in the refinement.
  double tilt_prior_deg = 2.0;
  // > 0: after the first global pass, the prior's spread for the second (after the outliers go) is this
  // many times the RMS of the tilts the first found, within [tilt_prior_min_deg, tilt_prior_deg]: as wide
  // as the camera's real wobble. Where tilt is weakly observed (a corridor whose points are mostly on the
  // floor), a wide prior lets the tilts take up errors that turn the headings. POV-Ray trolley walk
  // `people` (level camera; heading deg / ATE % / scale %): tilts found 0.32 deg RMS, 0.125 / 0.022 /
  // 0.053 -> 0.067 / 0.018 / 0.029; bench_nuisances' rocking renders find 1.2 deg and are unchanged.
  double tilt_prior_from_data = 1.0;
  double tilt_prior_min_deg = 0.1;
  // With tilt_prior_from_data (else ignored): when the tilts the second pass found call for a prior narrower
  // by more than 30 %, one more global pass with it (the first pass's tilts, under the wide prior, are partly
  // noise). `people`: 0.067 / 0.018 / 0.029 -> 0.055 / 0.015 / 0.011; the other POV-Ray scenes and
  // bench_nuisances do not narrow that much and are unchanged.
  bool tilt_prior_refit = true;
  // > 0: BundleProblem::floor_points are held to one common level (a free parameter of each solve) with
  // this spread, a share of the level's depth, under a Cauchy loss: the camera rides at one height over a
  // flat floor (a trolley, a tripod, a rendered walk), so the scale cannot drift along the walk. 0 = off
  // (a camera carried at a varying height).
  double floor_sigma = 0.01;
  // > 0 (with floor_sigma): the global passes hold the floor points with this many times the robust spread
  // (1.4826 x the median absolute deviation) of their levels, within [floor_sigma_min, floor_sigma]: as
  // wide as the floor and the camera's height really vary. It is measured once, under floor_sigma: on the
  // points the windows refined, or after the first global pass (then one more pass runs). A trolley's or
  // a render's floor points agree to 0.12-0.20 % of their depth (POV-Ray corpus), and 1 % let the scale
  // wander between them. A camera carried by hand shows a wider spread and keeps a wider prior.
  double floor_sigma_from_data = 1.0;
  double floor_sigma_min = 0.001;
  void check() const;  // throws Error naming the bad field
};

struct RefinementReport {
  double initial_rms = 0.0;  // angular residual RMS before, radians (all observations)
  double final_rms = 0.0;
  int windows = 0;
  int iterations = 0;        // summed over all solves
  int outliers_removed = 0;  // observations dropped as outliers
  int revisits = 0;          // revisited places the pose-graph pass tied together (0: no pose graph)
  // The tilt prior's spread in the last global pass (0: no tilts; EgomotionResult: the widest of its pieces).
  double tilt_prior_used_deg = 0.0;
  // The floor prior's spread in the last global pass, a share of the floor's depth (0: no floor prior;
  // EgomotionResult: the widest of its pieces).
  double floor_sigma_used = 0.0;
};

// Reports per Ceres iteration; a cancel stops the solver and ends with Cancelled (`problem` is then partly
// refined: a caller that cancels drops it).
RefinementReport refine_bundle(BundleProblem& problem, const RefinementOptions& options,
                               Progress& progress = null_progress());

// Angular residual (radians) of one observation, and of each, under the problem's current values.
double observation_error(const BundleProblem& problem, const BundleObservation& observation);
std::vector<double> observation_errors(const BundleProblem& problem);

}  // namespace plenopath
