#pragma once
// Pitch and roll of an equirectangular frame from its vertical edges (issue 18: a trolley on an uneven floor
// rocks by 1-2 deg, and the planar motion model takes every bearing as level). A vertical world line is
// seen on a great circle through the zenith, so the normal n of the plane through the camera and the edge
// is horizontal: n . up = 0, with `up` the world's up direction in the camera frame. Every edge pixel gives
// such a normal (its bearing crossed with the edge's tangent on the sphere, from the image gradient); up is
// the direction most nearly orthogonal to the inliers' normals (smallest eigenvector of sum w n n^T, Cauchy
// reweighted). Lines in any vertical plane through the camera (a ceiling joint straight above the path)
// agree with the vertical ones; every other line is an outlier. The estimate is absolute per frame: no drift.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>

namespace plenopath {

struct TiltOptions {
  double max_abs_elevation_deg = 60.0;  // edges nearer the poles are not used (stretched, few lines)
  double min_gradient = 40.0;           // Canny's low threshold (3x3 Sobel, L2); the high one is 3 times it
  double robust_scale_deg = 0.3;        // Cauchy scale of the residual (angle between n and the horizontal)
  double max_tilt_deg = 10.0;           // an estimate beyond this is refused
  int min_chain_pixels = 12;            // a steep edge chain must be this long (pixels and rows)
  int min_edges = 8;                    // fewer inlier chains: no estimate
  void check() const;                   // throws Error naming the bad field
};

struct TiltEstimate {
  bool valid = false;
  double pitch = 0.0;  // radians; > 0: the camera's forward direction points up (rig/synthetic_camera.h)
  double roll = 0.0;   // radians; > 0: the camera's left side is up
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  // the world's up direction in the camera frame
  int edges = 0;                                  // inlier edge chains
};

// `gray`: CV_8U equirectangular frame; `mask` (optional, CV_8U, same size): 0 = do not use (the trolley's
// mast is vertical in the camera frame, not in the world).
TiltEstimate estimate_tilt(const cv::Mat& gray, const TiltOptions& options, const cv::Mat& mask = cv::Mat());

// The rotation taking camera-frame bearings to the level camera frame (same heading): Ry(-pitch) Rx(roll).
Eigen::Matrix3d level_from_camera(const TiltEstimate& tilt);

}  // namespace plenopath
