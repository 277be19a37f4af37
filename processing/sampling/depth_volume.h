#pragma once
// Volume from a depth panorama, no plan needed. With d_ij the range along pixel (i, j)'s ray and a_ij its
// exact solid angle (rig/spherical.h equirect_pixel_solid_angle):
//   the seed's estimate      v = (1 / 4pi) * sum a_ij d_ij          (mean range, metres)
//   the star-shaped volume   V = (1 / 3)   * sum a_ij d_ij^3        (m^3 of the region seen from the centre)
// Pixels with no hit (0) are left out of both sums; `covered_solid_angle` says how much of the sphere hit.
#include <opencv2/core.hpp>
#include <vector>

namespace plenopath {

struct DepthVolume {
  double mean_range = 0.0;           // v, metres
  double star_volume = 0.0;          // V, m^3
  double covered_solid_angle = 0.0;  // steradians with a valid depth (4pi = full sphere)
  int valid_pixels = 0;
};

// depth: equirectangular, CV_32F in metres or CV_16U in millimetres, 0 = no hit. Negative, NaN or infinite
// values count as no hit. Throws plenopath::Error for another type or an empty image.
DepthVolume depth_volume(const cv::Mat& depth);

struct VolumeChangeOptions {
  // A change is significant when |log(V_k / V_ref)| exceeds this (0.25 = about 28 %).
  double log_ratio_threshold = 0.25;
  // Which quantity to compare: false = star volume V, true = mean range v.
  bool use_mean_range = false;
  // Frames with less covered solid angle than this fraction of 4pi are skipped (unreliable depth).
  double min_coverage = 0.5;

  void check() const;  // throws plenopath::Error saying which field is wrong
};

// Positions k in `volumes` where the volume has changed significantly since the last detected change (the
// reference starts at the first usable frame). The first usable frame is not reported.
std::vector<int> detect_volume_changes(const std::vector<DepthVolume>& volumes,
                                       const VolumeChangeOptions& options = {});

}  // namespace plenopath
