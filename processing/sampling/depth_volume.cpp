#include "processing/sampling/depth_volume.h"

#include <cmath>

#include "model/error.h"
#include "rig/spherical.h"

namespace plenopath {

DepthVolume depth_volume(const cv::Mat& depth) {
  if (depth.empty()) throw Error("depth volume: the depth panorama is empty");
  if (depth.channels() != 1 || (depth.depth() != CV_32F && depth.depth() != CV_16U))
    throw Error(
        "depth volume: expected a one-channel CV_32F (metres) or CV_16U (millimetres) depth panorama");
  DepthVolume out;
  const int w = depth.cols, h = depth.rows;
  double sum_d = 0.0, sum_d3 = 0.0;
  for (int row = 0; row < h; ++row) {
    const double a = equirect_pixel_solid_angle(row, w, h);
    double row_d = 0.0, row_d3 = 0.0;
    int row_valid = 0;
    for (int col = 0; col < w; ++col) {
      double d = 0.0;
      if (depth.depth() == CV_32F)
        d = depth.at<float>(row, col);
      else
        d = depth.at<std::uint16_t>(row, col) * 0.001;
      if (!(d > 0.0) || !std::isfinite(d)) continue;
      row_d += d;
      row_d3 += d * d * d;
      ++row_valid;
    }
    sum_d += a * row_d;
    sum_d3 += a * row_d3;
    out.covered_solid_angle += a * row_valid;
    out.valid_pixels += row_valid;
  }
  out.mean_range = sum_d / (4.0 * M_PI);
  out.star_volume = sum_d3 / 3.0;
  return out;
}

void VolumeChangeOptions::check() const {
  if (!(log_ratio_threshold > 0.0))
    throw Error("volume change options: log_ratio_threshold must be positive");
  if (!(min_coverage >= 0.0 && min_coverage <= 1.0))
    throw Error("volume change options: min_coverage must be in [0, 1]");
}

std::vector<int> detect_volume_changes(const std::vector<DepthVolume>& volumes,
                                       const VolumeChangeOptions& options) {
  options.check();
  std::vector<int> changes;
  double reference = 0.0;
  bool have_reference = false;
  for (int k = 0; k < static_cast<int>(volumes.size()); ++k) {
    const DepthVolume& v = volumes[k];
    const double value = options.use_mean_range ? v.mean_range : v.star_volume;
    if (v.covered_solid_angle < options.min_coverage * 4.0 * M_PI || !(value > 0.0)) continue;
    if (!have_reference) {
      reference = value;
      have_reference = true;
      continue;
    }
    if (std::abs(std::log(value / reference)) > options.log_ratio_threshold) {
      changes.push_back(k);
      reference = value;
    }
  }
  return changes;
}

}  // namespace plenopath
