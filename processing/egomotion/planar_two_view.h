#pragma once
// Planar two-view geometry on unit bearings: a trolley turns only about the vertical and moves in the
// horizontal plane, so the relative pose of two panoramas has three unknowns (turn, direction of travel,
// and an unknown length). With the turn known (from the ring headings), one correspondence fixes the
// direction: RANSAC on single correspondences, then Gauss-Newton on (turn, direction) over the inliers.
#include <Eigen/Core>
#include <random>
#include <vector>

namespace plenopath {

struct PlanarRelativePose {
  bool valid = false;
  double turn = 0.0;       // heading of B minus heading of A, radians
  double direction = 0.0;  // angle of B's position seen from A, in A's frame (CCW from A's forward)
  int inliers = 0;
  std::vector<bool> inlier;
  double median_parallax = 0.0;  // median angle (radians) between rotated-aligned bearings: how much B moved
  double rms_error = 0.0;        // epipolar residual over inliers, radians
};

struct PlanarTwoViewOptions {
  double threshold = 0.004;  // epipolar inlier threshold, radians (about 0.7 px at 1024 wide)
  int iterations = 64;       // RANSAC hypotheses
  int min_inliers = 12;
  double min_parallax = 0.002;  // radians; below this the direction is not observable
  int turn_scan_deg = 25;  // when the turn guess explains under half the matches, turns within this are tried
  // ... and one of them replaces the guess only when it explains this many times as many matches.
  double turn_scan_margin = 1.0;
};

// a[k] seen by camera A, b[k] by camera B (camera frames, unit). A sits at the origin with heading 0.
PlanarRelativePose estimate_planar_relative_pose(const std::vector<Eigen::Vector3d>& a,
                                                 const std::vector<Eigen::Vector3d>& b, double turn_guess,
                                                 const PlanarTwoViewOptions& options, std::mt19937& rng);

// Epipolar residual (sine of the angle between b's ray and the epipolar plane) of one correspondence.
double planar_epipolar_error(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double turn,
                             double direction);

// Midpoint triangulation from rays (centres and unit world directions). Returns false when the rays are
// nearly parallel (max pairwise angle below min_angle), the centres subtend less than min_angle seen from
// the point, or the point is behind a camera.
bool triangulate_rays(const std::vector<Eigen::Vector3d>& centres,
                      const std::vector<Eigen::Vector3d>& directions, double min_angle,
                      Eigen::Vector3d* point);

}  // namespace plenopath
