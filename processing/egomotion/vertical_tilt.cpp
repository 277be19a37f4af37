#include "processing/egomotion/vertical_tilt.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "model/error.h"
#include "model/option_check.h"

namespace plenopath {

void TiltOptions::check() const {
  const std::string s = "TiltOptions.";
  require_option(max_abs_elevation_deg > 5 && max_abs_elevation_deg < 89, s + "max_abs_elevation_deg",
                 "must be in (5, 89)", max_abs_elevation_deg);
  require_option(min_gradient > 0, s + "min_gradient", "must be > 0", min_gradient);
  require_option(robust_scale_deg > 0 && robust_scale_deg < 30, s + "robust_scale_deg", "must be in (0, 30)",
                 robust_scale_deg);
  require_option(max_tilt_deg > 0 && max_tilt_deg < 45, s + "max_tilt_deg", "must be in (0, 45)",
                 max_tilt_deg);
  require_option(min_edges >= 3, s + "min_edges", "must be >= 3", min_edges);
  require_option(min_chain_pixels >= 3, s + "min_chain_pixels", "must be >= 3", min_chain_pixels);
}

TiltEstimate estimate_tilt(const cv::Mat& gray, const TiltOptions& options, const cv::Mat& mask) {
  if (gray.type() != CV_8U || gray.empty()) throw Error("tilt: the frame must be 8-bit grey");
  if (!mask.empty() && (mask.type() != CV_8U || mask.size() != gray.size()))
    throw Error("tilt: the mask must be 8-bit and the frame's size");
  const int w = gray.cols, h = gray.rows;
  // Edge pixels (Canny) whose gradient is within 30 deg of horizontal: steep edges. Pixel by pixel, the
  // orientation of an edge is quantised (a slanted edge rendered or sampled without blur is a staircase of
  // vertical runs), so each connected chain of such pixels is fitted with one great circle (the plane
  // through the camera and all its pixels' bearings), which averages the staircase out.
  cv::Mat edges, gx, gy;
  cv::Canny(gray, edges, options.min_gradient, 3 * options.min_gradient, 3, true);
  cv::Sobel(gray, gx, CV_32F, 1, 0, 3);
  cv::Sobel(gray, gy, CV_32F, 0, 1, 3);
  const double max_e = options.max_abs_elevation_deg * M_PI / 180.0;
  const int v0 = std::max(1, static_cast<int>(std::ceil((M_PI / 2 - max_e) / M_PI * h - 0.5)));
  const int v1 = std::min(h - 2, static_cast<int>(std::floor((M_PI / 2 + max_e) / M_PI * h - 0.5)));
  cv::Mat steep(h, w, CV_8U, cv::Scalar(0));
  const float tan30 = 0.577f;
  for (int v = v0; v <= v1; ++v) {
    const uchar* e = edges.ptr<uchar>(v);
    const float* px = gx.ptr<float>(v);
    const float* py = gy.ptr<float>(v);
    const uchar* m = mask.empty() ? nullptr : mask.ptr<uchar>(v);
    uchar* out = steep.ptr<uchar>(v);
    for (int u = 0; u < w; ++u)
      out[u] = e[u] && (!m || m[u]) && std::abs(py[u]) <= tan30 * std::abs(px[u]) ? 255 : 0;
  }
  cv::Mat labels;
  const int count = cv::connectedComponents(steep, labels, 8, CV_32S);
  std::vector<Eigen::Matrix3d> scatter(count, Eigen::Matrix3d::Zero());
  std::vector<int> pixels(count, 0), top(count, h), bottom(count, -1);
  for (int v = v0; v <= v1; ++v) {
    const int* l = labels.ptr<int>(v);
    const double e = M_PI / 2 - (v + 0.5) / h * M_PI;
    const double ce = std::cos(e), se = std::sin(e);
    const float* px = gx.ptr<float>(v);
    for (int u = 0; u < w; ++u) {
      if (l[u] <= 0) continue;
      // Sub-pixel position across the edge: the peak of |d/dx| along the row (parabola through three).
      double x = u + 0.5;
      if (u > 0 && u + 1 < w) {
        const double m0 = std::abs(px[u - 1]), m1 = std::abs(px[u]), m2 = std::abs(px[u + 1]);
        const double denom = m0 - 2 * m1 + m2;
        if (denom < 0) x += std::clamp(0.5 * (m0 - m2) / denom, -0.5, 0.5);
      }
      const double a = x / w * 2.0 * M_PI - M_PI;
      const Eigen::Vector3d b(ce * std::cos(a), -ce * std::sin(a), se);
      scatter[l[u]] += b * b.transpose();
      ++pixels[l[u]];
      top[l[u]] = std::min(top[l[u]], v);
      bottom[l[u]] = std::max(bottom[l[u]], v);
    }
  }
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> strength;
  const double pixel = 2.0 * M_PI / w;
  for (int c = 1; c < count; ++c) {
    if (pixels[c] < options.min_chain_pixels || bottom[c] - top[c] + 1 < options.min_chain_pixels) continue;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter[c]);
    // Residual: rms angle of the pixels off the fitted great circle. A curve (a blob's outline) is refused.
    if (std::sqrt(std::max(0.0, solver.eigenvalues()(0)) / pixels[c]) > 0.5 * pixel) continue;
    normals.push_back(solver.eigenvectors().col(0));
    strength.push_back(pixels[c]);
  }
  TiltEstimate out;
  if (static_cast<int>(normals.size()) < options.min_edges) return out;
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  // Cauchy IRLS, the scale shrinking to the final one (a wide start finds the consensus).
  const double final_scale = std::sin(options.robust_scale_deg * M_PI / 180.0);
  const double scales[] = {8 * final_scale, 4 * final_scale, 2 * final_scale,
                           final_scale,     final_scale,     final_scale};
  for (double scale : scales) {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    const double inv = 1.0 / (scale * scale);
    for (size_t i = 0; i < normals.size(); ++i) {
      const double r = normals[i].dot(up);
      m += strength[i] / (1.0 + r * r * inv) * normals[i] * normals[i].transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(m);
    Eigen::Vector3d next = solver.eigenvectors().col(0);
    if (next.dot(up) < 0) next = -next;
    up = next.normalized();
  }
  int inliers = 0;
  for (const Eigen::Vector3d& n : normals) inliers += std::abs(n.dot(up)) < 2 * final_scale;
  out.edges = inliers;
  out.up = up;
  out.pitch = std::asin(std::clamp(up.x(), -1.0, 1.0));
  out.roll = std::atan2(up.y(), up.z());
  out.valid = inliers >= options.min_edges &&
              std::acos(std::clamp(up.z(), -1.0, 1.0)) <= options.max_tilt_deg * M_PI / 180.0;
  return out;
}

Eigen::Matrix3d level_from_camera(const TiltEstimate& tilt) {
  const double cp = std::cos(tilt.pitch), sp = std::sin(tilt.pitch);
  const double cr = std::cos(tilt.roll), sr = std::sin(tilt.roll);
  Eigen::Matrix3d ry, rx;
  ry << cp, 0, -sp, 0, 1, 0, sp, 0, cp;
  rx << 1, 0, 0, 0, cr, -sr, 0, sr, cr;
  return ry * rx;
}

}  // namespace plenopath
