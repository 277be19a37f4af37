#pragma once
// Two-view geometry of still panoramas shot from a tripod at one fixed height (issue 20): both cameras are
// level and at the same height, so B differs from A by a turn psi about the vertical and a horizontal
// translation whose length two views cannot see. Two unknowns, so two correspondences fix them: the minimal
// solver below, run in RANSAC, then refined on the inliers.
//
// Conventions (rig/spherical.h): camera frame +x forward, +y left, +z up. A sits at the origin with heading
// 0; B sits at t = (cos phi, sin phi, 0) (times an unknown length) and has heading psi, so B's bearing b
// points along Rz(psi) b in A's frame. Epipolar constraint: a . (t x Rz(psi) b) = 0.
#include <Eigen/Core>
#include <random>
#include <vector>

namespace plenopath {

struct PlanarMotion {
  double turn = 0.0;       // psi: heading of B minus heading of A, radians, (-pi, pi]
  double direction = 0.0;  // phi: angle of B's position seen from A, in A's frame (CCW from A's forward)
};

// The planar motions (up to four) that satisfy a[k] . (t x Rz(psi) b[k]) = 0 for k = 0, 1 and put both
// points in front of both cameras (a[k] ~ +lambda, b[k] ~ +mu with lambda, mu > 0). The turn solves a
// quartic in tan(psi / 2) (psi = pi handled on its own); the direction is then the null vector of a 2 x 2
// system. Points at the cameras' own height carry no information (their epipolar plane is the horizon
// for every motion): such a pair gives no solution.
std::vector<PlanarMotion> solve_planar_two_point(const Eigen::Vector3d& a0, const Eigen::Vector3d& b0,
                                                 const Eigen::Vector3d& a1, const Eigen::Vector3d& b1);

// Angular distance (radians) of a correspondence from the epipolar plane through the baseline: the mean
// of a's angle from the plane (t, Rz(psi) b) and Rz(psi) b's angle from the plane (t, a).
double planar_epipolar_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const PlanarMotion& motion);

// True when the rays a (from A) and Rz(psi) b (from B at t) meet in front of both cameras. Rays nearly
// parallel to each other count as in front (far points cannot tell).
bool in_front_of_both(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const PlanarMotion& motion);

struct PlanarRansacOptions {
  double threshold_deg = 0.25;     // inlier threshold on planar_epipolar_angle
  int max_iterations = 2000;       // pairs of correspondences drawn at most
  double confidence = 0.9999;      // stop once a better hypothesis is this unlikely to exist
  int min_inliers = 30;            // fewer: no pose
  double min_elevation_deg = 3.0;  // correspondences this close to the horizon in both views are not drawn
  void check() const;              // throws Error naming the bad field
};

struct PlanarPoseEstimate {
  bool valid = false;
  PlanarMotion motion;
  int inliers = 0;
  std::vector<bool> inlier;          // per correspondence
  double rms_error_deg = 0.0;        // planar_epipolar_angle over the inliers
  double median_parallax_deg = 0.0;  // median angle between a and Rz(psi) b over the inliers
};

// RANSAC over solve_planar_two_point, then Gauss-Newton on (psi, phi) over the inliers (inliers chosen
// again after each pass).
PlanarPoseEstimate estimate_planar_pose(const std::vector<Eigen::Vector3d>& a,
                                        const std::vector<Eigen::Vector3d>& b,
                                        const PlanarRansacOptions& options, std::mt19937& rng);

}  // namespace plenopath
