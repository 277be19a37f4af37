#pragma once
// Comparing two equirectangular frames: turn one to the other's heading (a column shift, wrapping across
// the seam), then PSNR and SSIM.
#include <opencv2/core.hpp>

namespace plenopath {

// The panorama `image` (taken with heading `from_heading`, radians) as it would look with heading
// `to_heading` from the same place: column u of the result is column u + (from - to) * w / 2pi of the input
// (rig/spherical.h: the centre column is the heading, azimuth grows clockwise). Whole-pixel shifts are
// exact copies; fractional ones interpolate linearly between neighbouring columns.
cv::Mat rotate_to_heading(const cv::Mat& image, double from_heading, double to_heading);

// Peak signal-to-noise ratio in dB of two images of the same size and type (8-bit, any channels):
// 10 log10(255^2 / MSE) over all samples; +infinity when they are identical. Throws Error on a mismatch.
double psnr_db(const cv::Mat& a, const cv::Mat& b);

// Mean structural similarity (Wang et al. 2004: 11x11 Gaussian window, sigma 1.5, K1 0.01, K2 0.03) of the
// grey-level versions of two 8-bit images of the same size; 1 when identical. Throws Error on a mismatch.
double ssim(const cv::Mat& a, const cv::Mat& b);

}  // namespace plenopath
