#pragma once
// Bilinear sampling of equirectangular images that wraps across the seam (azimuth +-180 deg) and clamps
// at the poles.
#include <opencv2/core.hpp>

namespace plenopath {

// Samples `image` (CV_8U or CV_32F, 1..4 channels) at continuous pixel coordinates (x, y) where pixel
// (u, v) has its centre at (u + 0.5, v + 0.5). Writes image.channels() values to `out`.
void sample_equirect_bilinear(const cv::Mat& image, double x, double y, float* out);

// Convenience for 3-channel 8-bit images.
cv::Vec3f sample_equirect_bilinear_bgr(const cv::Mat& image, double x, double y);

}  // namespace plenopath
