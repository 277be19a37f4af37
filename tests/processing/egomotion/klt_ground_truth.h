#pragma once
// Errors of KLT observations against the synthetic camera's ground truth (shared by tests and bench_klt).
// For every track whose first window lies on one smooth surface (depth within 15 % over the window: no
// occlusion edge inside), the 3-D point is placed from the first observation's ray and the rendered depth
// there; each later observation is compared with where that point projects (in working pixels).
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "model/camera_path.h"
#include "processing/egomotion/klt_tracks.h"

namespace plenopath::test {

struct KltTruthErrors {
  std::map<int, std::vector<double>> error_px;           // by track age (frames since the first observation)
  std::map<int, std::vector<double>> signed_azimuth_px;  // azimuth error times cos(elevation), same order
  int smooth_tracks = 0;
};

inline double bilinear_depth(const cv::Mat& m, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= m.cols || y0 + 1 >= m.rows) return 0.0;
  const double fx = x - x0, fy = y - y0;
  return (1 - fx) * (1 - fy) * m.at<float>(y0, x0) + fx * (1 - fy) * m.at<float>(y0, x0 + 1) +
         (1 - fx) * fy * m.at<float>(y0 + 1, x0) + fx * fy * m.at<float>(y0 + 1, x0 + 1);
}

// depths: the rendered depth of each frame (CV_32F, metres along the ray), any size 2:1.
inline KltTruthErrors klt_truth_errors(const KltTracker& klt, int window_px,
                                       const std::vector<cv::Mat>& depths, const CameraPath& truth,
                                       double camera_height) {
  KltTruthErrors out;
  const int half = window_px / 2;
  const double pixel = 2 * M_PI / klt.width();
  auto centre = [&](int f) { return Eigen::Vector3d(truth.frames[f].x, truth.frames[f].y, camera_height); };
  for (const FeatureTrack& t : klt.tracks()) {
    if (t.observations.size() < 2) continue;
    const TrackObservation& o0 = t.observations.front();
    cv::Mat depth = depths[o0.frame];
    if (depth.cols != klt.width())
      cv::resize(depth, depth, cv::Size(klt.width(), klt.height()), 0, 0, cv::INTER_NEAREST);
    const int u = static_cast<int>(std::lround(o0.x)), v = static_cast<int>(std::lround(o0.y));
    if (u < half || v < half || u + half >= depth.cols || v + half >= depth.rows) continue;
    double lo = 0, hi = 0;
    cv::minMaxLoc(depth(cv::Rect(u - half, v - half, window_px, window_px)), &lo, &hi);
    if (lo <= 0 || hi > 1.15 * lo) continue;
    ++out.smooth_tracks;
    const double c0 = std::cos(truth.frames[o0.frame].heading), s0 = std::sin(truth.frames[o0.frame].heading);
    const Eigen::Vector3d b0 = klt.bearing(o0);
    const Eigen::Vector3d point =
        centre(o0.frame) + bilinear_depth(depth, o0.x, o0.y) *
                               Eigen::Vector3d(c0 * b0.x() - s0 * b0.y(), s0 * b0.x() + c0 * b0.y(), b0.z());
    for (std::size_t k = 1; k < t.observations.size(); ++k) {
      const TrackObservation& o = t.observations[k];
      const Eigen::Vector3d w = point - centre(o.frame);
      const double c = std::cos(truth.frames[o.frame].heading), s = std::sin(truth.frames[o.frame].heading);
      const Eigen::Vector3d predicted =
          Eigen::Vector3d(c * w.x() + s * w.y(), -s * w.x() + c * w.y(), w.z()).normalized();
      const Eigen::Vector3d observed = klt.bearing(o);
      const int age = o.frame - o0.frame;
      out.error_px[age].push_back(std::atan2(predicted.cross(observed).norm(), predicted.dot(observed)) /
                                  pixel);
      const double azimuth_error = std::remainder(
          std::atan2(observed.y(), observed.x()) - std::atan2(predicted.y(), predicted.x()), 2 * M_PI);
      out.signed_azimuth_px[age].push_back(azimuth_error / pixel *
                                           std::sqrt(1 - observed.z() * observed.z()));
    }
  }
  return out;
}

}  // namespace plenopath::test
