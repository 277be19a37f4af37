#include "processing/egomotion/affine_patch.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "model/option_check.h"

namespace plenopath {
namespace {

// Gaussian weight over the window: the centre matters most (and a depth edge near the rim matters less).
std::vector<float> window_weights(int n) {
  const int h = n / 2;
  const double sigma = n / 4.0;
  std::vector<float> w(static_cast<std::size_t>(n) * n);
  for (int y = -h; y <= h; ++y)
    for (int x = -h; x <= h; ++x)
      w[(y + h) * n + (x + h)] = static_cast<float>(std::exp(-(x * x + y * y) / (2 * sigma * sigma)));
  return w;
}

const std::vector<float>& cached_weights(int n) {
  thread_local int cached_n = -1;
  thread_local std::vector<float> cached;
  if (cached_n != n) {
    cached = window_weights(n);
    cached_n = n;
  }
  return cached;
}

// Samples the warped window from an 8-bit image into `out` (bilinear). False when any sample leaves the
// image.
bool sample_warped(const cv::Mat& image, const AffineWarp& warp, int n, float* out) {
  const int h = n / 2;
  const double a = warp.linear(0, 0), b = warp.linear(0, 1), c = warp.linear(1, 0), d = warp.linear(1, 1);
  // The window's corners bound every sample (the warp is affine).
  for (int sy : {-h, h})
    for (int sx : {-h, h}) {
      const double x = warp.centre.x + a * sx + b * sy, y = warp.centre.y + c * sx + d * sy;
      // A margin: the samples between the corners are stepped to incrementally and may round past them.
      if (!(x >= 1e-6 && y >= 1e-6 && x < image.cols - 1 - 1e-6 && y < image.rows - 1 - 1e-6)) return false;
    }
  const std::size_t step = image.step[0];
  for (int y = -h; y <= h; ++y) {
    double px = warp.centre.x - a * h + b * y, py = warp.centre.y - c * h + d * y;
    for (int x = -h; x <= h; ++x, px += a, py += c) {
      const int ix = static_cast<int>(px), iy = static_cast<int>(py);
      const float fx = static_cast<float>(px - ix), fy = static_cast<float>(py - iy);
      const uchar* p = image.data + iy * step + ix;
      const float top = p[0] + fx * (p[1] - p[0]);
      const float bottom = p[step] + fx * (p[step + 1] - p[step]);
      *out++ = top + fy * (bottom - top);
    }
  }
  return true;
}

// Weighted normalisation to zero mean and unit variance; returns the standard deviation before (0 = flat).
double normalise(float* v, const std::vector<float>& w) {
  double sw = 0, s = 0, s2 = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    sw += w[k];
    s += w[k] * v[k];
    s2 += w[k] * double(v[k]) * v[k];
  }
  const double mean = s / sw;
  const double var = std::max(0.0, s2 / sw - mean * mean);
  const double sd = std::sqrt(var);
  if (sd < 1e-6) return 0.0;
  const float inv = static_cast<float>(1.0 / sd), m = static_cast<float>(mean);
  for (std::size_t k = 0; k < w.size(); ++k) v[k] = (v[k] - m) * inv;
  return sd;
}

}  // namespace

LinearStretch linear_stretch(const cv::Matx22d& a) {
  // a = rotation(q part) + reflection-like (r part); the singular values are q + r and |q - r|.
  const double e = 0.5 * (a(0, 0) + a(1, 1)), f = 0.5 * (a(0, 0) - a(1, 1));
  const double g = 0.5 * (a(1, 0) + a(0, 1)), k = 0.5 * (a(1, 0) - a(0, 1));
  const double q = std::hypot(e, k), r = std::hypot(f, g);
  return {std::abs(q - r), q + r, std::atan2(k, e)};
}

void AffinePatchOptions::check() const {
  const std::string s = "AffinePatchOptions.";
  require_option(window_px >= 5 && window_px % 2 == 1, s + "window_px", "must be odd and >= 5", window_px);
  require_option(max_iterations >= 1, s + "max_iterations", "must be >= 1", max_iterations);
  require_option(converged_px > 0, s + "converged_px", "must be > 0", converged_px);
  require_option(max_residual > 0, s + "max_residual", "must be > 0", max_residual);
  require_option(min_scale > 0 && min_scale < 1, s + "min_scale", "must be in (0, 1)", min_scale);
  require_option(max_scale > 1, s + "max_scale", "must be > 1", max_scale);
}

AffinePatch make_affine_patch(const cv::Mat& image, cv::Point2d centre, const AffinePatchOptions& options) {
  AffinePatch patch;
  const int n = options.window_px, h = n / 2;
  if (!(centre.x - h - 2 >= 0 && centre.y - h - 2 >= 0 && centre.x + h + 2 < image.cols &&
        centre.y + h + 2 < image.rows))
    return patch;
  cv::Mat around;  // the window plus a one-pixel margin, for central differences
  cv::getRectSubPix(image, cv::Size(n + 2, n + 2),
                    cv::Point2f(static_cast<float>(centre.x), static_cast<float>(centre.y)), around, CV_32F);
  const std::vector<float>& w = cached_weights(n);
  patch.values.create(n, n, CV_32F);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) patch.values.at<float>(y, x) = around.at<float>(y + 1, x + 1);
  const double sd = normalise(patch.values.ptr<float>(), w);
  if (sd < 1.0) return patch;  // flat: under one grey level of contrast
  const float inv = static_cast<float>(1.0 / sd);
  patch.steepest.create(n * n, 6, CV_32F);
  cv::Matx66d hessian = cv::Matx66d::zeros();
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float gx = 0.5f * inv * (around.at<float>(y + 1, x + 2) - around.at<float>(y + 1, x));
      const float gy = 0.5f * inv * (around.at<float>(y + 2, x + 1) - around.at<float>(y, x + 1));
      const float dx = static_cast<float>(x - h), dy = static_cast<float>(y - h);
      float* sd_row = patch.steepest.ptr<float>(y * n + x);
      const float row[6] = {gx * dx, gy * dx, gx * dy, gy * dy, gx, gy};
      const double wk = w[y * n + x];
      for (int i = 0; i < 6; ++i) {
        sd_row[i] = row[i];
        for (int j = 0; j < 6; ++j) hessian(i, j) += wk * row[i] * row[j];
      }
    }
  // Too little structure in some direction (an edge, not a corner) cannot be aligned: the translation
  // block's smaller eigenvalue, per unit weight, must not vanish.
  const double txx = hessian(4, 4), tyy = hessian(5, 5), txy = hessian(4, 5);
  const double min_eig = 0.5 * (txx + tyy) - std::sqrt(0.25 * (txx - tyy) * (txx - tyy) + txy * txy);
  double weight_sum = 0;
  for (float v : w) weight_sum += v;
  if (min_eig / weight_sum < 1e-3) return patch;
  // A little damping on the deformation terms keeps weakly textured patches from trading shear for shift.
  for (int i = 0; i < 4; ++i) hessian(i, i) *= 1.0 + 1e-3;
  bool ok = false;
  patch.hessian_inverse = hessian.inv(cv::DECOMP_CHOLESKY, &ok);
  patch.valid = ok;
  return patch;
}

bool align_affine_patch(const AffinePatch& patch, const cv::Mat& image, AffineWarp* warp,
                        const AffinePatchOptions& options, double* residual) {
  if (!patch.valid || image.type() != CV_8UC1) return false;
  const int n = patch.values.rows, h = n / 2;
  const std::vector<float>& w = cached_weights(n);
  thread_local std::vector<float> sampled;
  sampled.resize(static_cast<std::size_t>(n) * n);
  const float* t = patch.values.ptr<float>();
  double last_move = 1e9;
  for (int it = 0; it < options.max_iterations; ++it) {
    if (!sample_warped(image, *warp, n, sampled.data())) return false;
    if (normalise(sampled.data(), w) < 1.0) return false;
    cv::Vec6d b(0, 0, 0, 0, 0, 0);
    for (int k = 0; k < n * n; ++k) {
      const double e = w[k] * (sampled[k] - t[k]);
      const float* sd = patch.steepest.ptr<float>(k);
      for (int i = 0; i < 6; ++i) b[i] += sd[i] * e;
    }
    const cv::Vec6d dp = patch.hessian_inverse * b;
    if (!std::isfinite(dp[4]) || !std::isfinite(dp[5])) return false;
    // W <- W o W(dp)^-1 (inverse compositional update).
    const cv::Matx33d delta(1 + dp[0], dp[2], dp[4], dp[1], 1 + dp[3], dp[5], 0, 0, 1);
    const cv::Matx33d current(warp->linear(0, 0), warp->linear(0, 1), warp->centre.x, warp->linear(1, 0),
                              warp->linear(1, 1), warp->centre.y, 0, 0, 1);
    bool invertible = false;
    const cv::Matx33d updated = current * delta.inv(cv::DECOMP_LU, &invertible);
    if (!invertible) return false;
    warp->linear = cv::Matx22d(updated(0, 0), updated(0, 1), updated(1, 0), updated(1, 1));
    warp->centre = cv::Point2d(updated(0, 2), updated(1, 2));
    // How far the update moved the window's corners (in template pixels).
    last_move = 0;
    for (int sy : {-h, h})
      for (int sx : {-h, h})
        last_move =
            std::max(last_move, std::hypot(dp[0] * sx + dp[2] * sy + dp[4], dp[1] * sx + dp[3] * sy + dp[5]));
    if (last_move < options.converged_px) break;
  }
  if (last_move > 30 * options.converged_px) return false;  // still moving: no stable match
  const LinearStretch stretch = linear_stretch(warp->linear);
  if (stretch.smallest < options.min_scale || stretch.largest > options.max_scale) return false;
  if (!sample_warped(image, *warp, n, sampled.data()) || normalise(sampled.data(), w) < 1.0) return false;
  double sw = 0, se = 0;
  for (int j = 0; j < n * n; ++j) {
    sw += w[j];
    se += w[j] * double(sampled[j] - t[j]) * (sampled[j] - t[j]);
  }
  const double rms = std::sqrt(se / sw);
  if (residual) *residual = rms;
  return rms <= options.max_residual;
}

}  // namespace plenopath
