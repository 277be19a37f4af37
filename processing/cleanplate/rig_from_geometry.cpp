#include "processing/cleanplate/rig_from_geometry.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/cleanplate/colour_difference.h"
#include "processing/cleanplate/exposure_gain.h"
#include "processing/cleanplate/warp_geometry.h"
#include "processing/util/parallel_for.h"
#include "rig/spherical.h"

namespace plenopath {

void RigFromGeometryOptions::check() const {
  const std::string s = "RigFromGeometryOptions.";
  require_option(keyframes >= 1 && keyframes <= 100, s + "keyframes", "must be in [1, 100]", keyframes);
  require_option(neighbours >= 1 && neighbours <= 32, s + "neighbours", "must be in [1, 32]", neighbours);
  require_option(min_baseline_m >= 0, s + "min_baseline_m", "must be >= 0", min_baseline_m);
  require_option(max_baseline_m > min_baseline_m, s + "max_baseline_m", "must be > min_baseline_m",
                 max_baseline_m);
  require_option(min_stay_share > 0 && min_stay_share <= 1, s + "min_stay_share", "must be in (0, 1]",
                 min_stay_share);
  require_option(max_agree_share >= 0 && max_agree_share < 1, s + "max_agree_share", "must be in [0, 1)",
                 max_agree_share);
  require_option(min_samples >= 1, s + "min_samples", "must be >= 1", min_samples);
  require_option(iterations >= 1 && iterations <= 20, s + "iterations", "must be in [1, 20]", iterations);
  require_option(min_moved_px >= 0, s + "min_moved_px", "must be >= 0", min_moved_px);
  require_option(occlusion_tolerance > 0, s + "occlusion_tolerance", "must be > 0", occlusion_tolerance);
  require_option(min_region >= 0 && min_region < 1, s + "min_region", "must be in [0, 1)", min_region);
}

namespace {

// One keyframe compared with one other frame: per keyframe pixel (row-major), the other frame's pixel its
// scene point lands on (-1: hidden there, not moved enough, or no depth) and whether the colours agree.
struct Comparison {
  std::vector<int> landing;
  std::vector<std::uint8_t> agrees;
};

Comparison compare(const PathFrame& key, const cv::Mat& key_image, const cv::Mat& key_depth,
                   const std::vector<Eigen::Vector3f>& rays, const PathFrame& other, const cv::Mat& image,
                   const cv::Mat& depth, int tolerance, const RigFromGeometryOptions& options) {
  const int w = key_image.cols, h = key_image.rows;
  Comparison out;
  out.landing.assign(static_cast<std::size_t>(w) * h, -1);
  out.agrees.assign(static_cast<std::size_t>(w) * h, 0);
  cv::Mat warped = cv::Mat::zeros(h, w, CV_8UC3), valid = cv::Mat::zeros(h, w, CV_8U);
  const Eigen::Matrix3d other_from_world = world_from_camera_rotation(other.heading).transpose();
  const Eigen::Vector3d offset(key.x - other.x, key.y - other.y, 0.0);
  parallel_for_each(h, 0, [&](int v) {
    for (int u = 0; u < w; ++u) {
      const float d = key_depth.at<float>(v, u);
      if (!(d > 0)) continue;
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      const Eigen::Vector3d world = rays[i].cast<double>() * d + offset;
      const double distance = world.norm();
      if (distance < 1e-6) continue;
      const Eigen::Vector2d p = bearing_to_equirect(other_from_world * world, w, h);
      const double moved_u = std::remainder(p.x() - (u + 0.5), double(w)), moved_v = p.y() - (v + 0.5);
      if (std::hypot(moved_u, moved_v) < options.min_moved_px) continue;
      const int x = ((static_cast<int>(std::floor(p.x())) % w) + w) % w;
      const int y = std::clamp(static_cast<int>(p.y()), 0, h - 1);
      if (!depth.empty()) {
        const float seen = depth.at<float>(y, x);
        if (seen > 0 && seen < distance * (1 - options.occlusion_tolerance)) continue;  // hidden from it
      }
      out.landing[i] = y * w + x;
      warped.at<cv::Vec3b>(v, u) = image.at<cv::Vec3b>(y, x);
      valid.at<std::uint8_t>(v, u) = 255;
    }
  });
  const cv::Scalar gain = exposure_gain(key_image, warped, valid, {});
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      if (out.landing[i] < 0) continue;
      out.agrees[i] = max_channel_difference(key_image.at<cv::Vec3b>(v, u), warped.at<cv::Vec3b>(v, u),
                                             gain) <= tolerance;
    }
  return out;
}

}  // namespace

cv::Mat rig_from_geometry(const CameraPath& path, const std::function<cv::Mat(int position)>& frame,
                          const std::function<cv::Mat(int position)>& static_depth, const cv::Mat& rig_mask,
                          const CaptureStillness& stillness, const RigFromGeometryOptions& options,
                          Progress& progress) {
  options.check();
  const int count = static_cast<int>(path.size());
  if (stillness.empty() || count < 3) return rig_mask.empty() ? cv::Mat() : cv::Mat(rig_mask != 0);
  const int w = stillness.median.cols, h = stillness.median.rows;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  cv::Size frame_size;
  auto colour_frame = [&](int position) {
    const cv::Mat image = frame(position);
    if (image.empty() || image.type() != CV_8UC3)
      throw Error("rig from geometry: frame " + std::to_string(path.frames[position].index) +
                  " is not a colour image");
    if (frame_size.empty()) frame_size = image.size();
    return image;
  };
  auto small_image = [&](const cv::Mat& image) {
    cv::Mat small;
    cv::resize(image, small, {w, h}, 0, 0, cv::INTER_AREA);
    return small;
  };
  auto small_depth = [&](int position) {
    const cv::Mat depth = static_depth(position);
    if (depth.empty() || depth.type() != CV_32F) return cv::Mat();
    cv::Mat small;
    cv::resize(depth, small, {w, h}, 0, 0, cv::INTER_NEAREST);
    return small;
  };

  // The comparisons, made once; and per pixel the keyframes where it shows what the capture shows there.
  std::vector<Comparison> comparisons;
  std::vector<int> stays(pixels, 0);
  int keyframes = 0;
  for (int k = 0; k < options.keyframes; ++k) {
    progress.checkpoint(0.9 * k / options.keyframes, "finding the rig by the geometry");
    const int position = std::clamp(static_cast<int>((k + 0.5) * count / options.keyframes), 0, count - 1);
    const cv::Mat key_depth = small_depth(position);
    if (key_depth.empty()) continue;
    const cv::Mat key_frame = colour_frame(position), key_image = small_image(key_frame);
    const cv::Mat key_stays = stays_in_place(key_frame, stillness, options.min_stay_share);
    for (std::size_t i = 0; i < pixels; ++i) stays[i] += key_stays.data[i] != 0;
    ++keyframes;
    const PathFrame& key = path.frames[static_cast<std::size_t>(position)];
    const std::vector<Eigen::Vector3f> rays = plan_rays(key.heading, w, h);
    for (int j : neighbours_within(path, position, options.min_baseline_m, options.max_baseline_m,
                                   options.neighbours))
      comparisons.push_back(compare(key, key_image, key_depth, rays, path.frames[static_cast<std::size_t>(j)],
                                    small_image(colour_frame(j)), small_depth(j), stillness.tolerance,
                                    options));
  }
  cv::Mat known = cv::Mat::zeros(h, w, CV_8U);
  if (!rig_mask.empty()) cv::resize(rig_mask != 0, known, {w, h}, 0, 0, cv::INTER_AREA);
  known = known > 0;
  if (keyframes == 0) return rig_mask.empty() ? cv::Mat() : cv::Mat(rig_mask != 0);

  // The rig grows from its edges inwards: samples landing in it say nothing of the scene.
  cv::Mat rig = known.clone();
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    cv::Mat next = known.clone();
    const std::uint8_t* in_rig = rig.ptr<std::uint8_t>(0);
    for (std::size_t i = 0; i < pixels; ++i) {
      if (2 * stays[i] < keyframes) continue;
      int samples = 0, agree = 0;
      for (const Comparison& c : comparisons) {
        const int landing = c.landing[i];
        if (landing < 0 || in_rig[landing]) continue;
        ++samples;
        agree += c.agrees[i];
      }
      if (samples >= options.min_samples && agree <= options.max_agree_share * samples) next.data[i] = 255;
    }
    const bool changed = cv::countNonZero(next != rig) > 0;
    rig = next;
    if (!changed) break;
  }
  // Small holes closed. What moves with the camera stands on the floor with it (a trolley, an operator's
  // feet, a tripod's legs): regions that reach neither the rig given nor the bottom rows (the nadir) are
  // dropped, and small ones (a strip of wall the plan gets wrong that stays in view along a corridor).
  cv::morphologyEx(rig, rig, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
  cv::Mat labels, stats, centres;
  const int regions = cv::connectedComponentsWithStats(rig, labels, stats, centres, 8, CV_32S);
  std::vector<std::uint8_t> grounded(static_cast<std::size_t>(regions), 0);
  const int nadir_rows = std::max(1, h / 20);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = labels.at<int>(v, u);
      if (l > 0 && (v >= h - nadir_rows || known.at<std::uint8_t>(v, u)))
        grounded[static_cast<std::size_t>(l)] = 1;
    }
  // (the seam: a region on one edge is grounded when the one it continues on the other edge is)
  for (int pass = 0; pass < 2; ++pass)
    for (int v = 0; v < h; ++v) {
      const int a = labels.at<int>(v, 0), b = labels.at<int>(v, w - 1);
      if (a > 0 && b > 0 && (grounded[static_cast<std::size_t>(a)] || grounded[static_cast<std::size_t>(b)]))
        grounded[static_cast<std::size_t>(a)] = grounded[static_cast<std::size_t>(b)] = 1;
    }
  const double min_area = options.min_region * w * h;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = labels.at<int>(v, u);
      if (l > 0 && (stats.at<int>(l, cv::CC_STAT_AREA) < min_area || !grounded[static_cast<std::size_t>(l)]))
        rig.at<std::uint8_t>(v, u) = 0;
    }
  cv::Mat out;
  cv::resize(rig, out, frame_size, 0, 0, cv::INTER_NEAREST);
  cv::dilate(out, out, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(3, 3)), cv::Point(-1, -1),
             std::max(1, frame_size.width / 512));
  if (!rig_mask.empty()) out |= (rig_mask != 0);
  progress.report(1.0);
  return cv::countNonZero(out) > 0 ? out : cv::Mat();
}

}  // namespace plenopath
