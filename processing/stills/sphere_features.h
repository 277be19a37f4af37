#pragma once
// Features on an equirectangular panorama, for wide-baseline matching between still panoramas metres apart
// (issue 20). SIFT (scale invariant, so a wall seen from 1 m and from 4 m still matches) is detected twice:
// on the panorama, and on a copy rolled by half its width, so that the seam at azimuth +-180 deg lies in the
// middle of one of the two. Each copy keeps only the features of its central half of the columns, so every
// direction is described once, by the copy in which it is at least a quarter width from the border (no
// descriptor cut by the seam; SIFT's own repeats of a keypoint are removed). Near the poles the
// equirectangular image is stretched beyond what SIFT tolerates, and the nadir holds the tripod: features
// there are dropped. Each kept keypoint becomes a unit bearing in the camera frame (rig/spherical.h).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace plenopath {

struct SphereFeatureOptions {
  int work_width = 2048;                // the panorama is resized to this width (height = width / 2) first
  int max_features = 6000;              // per panorama (split between the two copies), strongest first
  double max_abs_elevation_deg = 60.0;  // features farther from the horizon are dropped (poles, tripod)
  double contrast_threshold = 0.008;    // SIFT's, lower than its default 0.04: plain walls give little
  // Local contrast equalisation (CLAHE, 16 x 8 tiles, this clip limit; 0 = off) before detection: plain
  // paint and dark carpet keep texture that an absolute contrast threshold misses, and the exposure of one
  // shot against the next matters less.
  double equalize_clip = 3.0;
  void check() const;  // throws Error naming the bad field
};

struct SphereFeatures {
  int width = 0, height = 0;              // the working size the keypoints refer to
  std::vector<cv::KeyPoint> keypoints;    // pixel coordinates in the working panorama, x in [0, width)
  std::vector<Eigen::Vector3d> bearings;  // unit, camera frame, one per keypoint
  cv::Mat descriptors;                    // CV_32F, one RootSIFT row per keypoint (unit L2 norm)
};

// image: 8-bit grey or BGR equirectangular panorama (width = 2 x height). Throws Error on an empty image or
// one that is not 2:1.
SphereFeatures detect_sphere_features(const cv::Mat& image, const SphereFeatureOptions& options = {});

}  // namespace plenopath
