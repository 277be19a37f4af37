#include "processing/cleanplate/clean_plate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/util/parallel_for.h"
#include "rig/spherical.h"

namespace plenopath {

void CleanPlateOptions::check() const {
  const std::string s = "CleanPlateOptions.";
  require_option(neighbours >= 1 && neighbours <= 64, s + "neighbours", "must be in [1, 64]", neighbours);
  require_option(min_baseline_m >= 0, s + "min_baseline_m", "must be >= 0", min_baseline_m);
  require_option(max_baseline_m > min_baseline_m, s + "max_baseline_m", "must be > min_baseline_m",
                 max_baseline_m);
  require_option(occlusion_tolerance > 0, s + "occlusion_tolerance", "must be > 0", occlusion_tolerance);
  require_option(disagreement > 0, s + "disagreement", "must be > 0", disagreement);
  require_option(weak_disagreement > 0 && weak_disagreement <= disagreement, s + "weak_disagreement",
                 "must be in (0, disagreement]", weak_disagreement);
  require_option(depth_edge > 0, s + "depth_edge", "must be > 0", depth_edge);
  require_option(min_region_px >= 1, s + "min_region_px", "must be >= 1", min_region_px);
  require_option(mask_closing_px >= 0, s + "mask_closing_px", "must be >= 0", mask_closing_px);
  require_option(mask_dilation_px >= 0, s + "mask_dilation_px", "must be >= 0", mask_dilation_px);
  require_option(min_support >= 1, s + "min_support", "must be >= 1", min_support);
}

namespace {

struct Warped {
  cv::Mat image;  // CV_8UC3 in the keyframe's pixels
  cv::Mat valid;  // CV_8U
};

// Neighbour `n` warped onto the keyframe through the keyframe's static depth.
Warped warp_onto_keyframe(const PathFrame& key, const PathFrame& n, const cv::Mat& key_depth,
                          const cv::Mat& image, const cv::Mat& depth,
                          const std::vector<Eigen::Vector3f>& rays, double occlusion_tolerance) {
  const int w = key_depth.cols, h = key_depth.rows;
  cv::Mat map_x(h, w, CV_32F), map_y(h, w, CV_32F);
  Warped out;
  out.valid = cv::Mat::zeros(h, w, CV_8U);
  const Eigen::Matrix3d n_from_world = world_from_camera_rotation(n.heading).transpose();
  const Eigen::Vector3d offset(key.x - n.x, key.y - n.y, 0.0);  // the keyframe's centre seen from n
  parallel_for_each(h, 0, [&](int v) {
    for (int u = 0; u < w; ++u) {
      const float d = key_depth.at<float>(v, u);
      float* mx = &map_x.at<float>(v, u);
      float* my = &map_y.at<float>(v, u);
      *mx = *my = -1.0f;
      if (!(d > 0)) continue;
      const Eigen::Vector3d world = rays[static_cast<std::size_t>(v) * w + u].cast<double>() * d + offset;
      const double distance = world.norm();
      if (distance < 1e-6) continue;
      const Eigen::Vector2d p = bearing_to_equirect(n_from_world * world, w, h);
      if (!depth.empty()) {
        const int du = std::clamp(static_cast<int>(p.x()), 0, w - 1);
        const int dv = std::clamp(static_cast<int>(p.y()), 0, h - 1);
        const float seen = depth.at<float>(dv, du);
        if (seen > 0 && seen < distance * (1.0 - occlusion_tolerance)) continue;  // hidden from n
      }
      *mx = static_cast<float>(p.x() - 0.5);
      *my = static_cast<float>(std::clamp(p.y() - 0.5, 0.0, h - 1.0));
      out.valid.at<std::uint8_t>(v, u) = 255;
    }
  });
  cv::remap(image, out.image, map_x, map_y, cv::INTER_CUBIC, cv::BORDER_WRAP);
  return out;
}

}  // namespace

CleanPlate clean_plate(const CameraPath& path, int keyframe_position,
                       const std::function<cv::Mat(int position)>& frame,
                       const std::function<cv::Mat(int position)>& static_depth,
                       const CleanPlateOptions& options, Progress& progress) {
  options.check();
  const int count = static_cast<int>(path.size());
  if (keyframe_position < 0 || keyframe_position >= count)
    throw Error("clean plate: keyframe position " + std::to_string(keyframe_position) +
                " is outside the path (" + std::to_string(count) + " frames)");
  const PathFrame& key = path.frames[static_cast<std::size_t>(keyframe_position)];
  const cv::Mat key_image = frame(keyframe_position);
  const cv::Mat key_depth = static_depth(keyframe_position);
  if (key_image.empty() || key_image.type() != CV_8UC3)
    throw Error("clean plate: frame " + std::to_string(key.index) + " is not a colour image");
  if (key_depth.empty() || key_depth.type() != CV_32F || key_depth.size() != key_image.size())
    throw Error("clean plate: frame " + std::to_string(key.index) +
                " has no static depth of its size (a depth map, or the plan's walls rendered as depth)");
  const int w = key_image.cols, h = key_image.rows;

  // The keyframe's rays in the plan frame, once.
  std::vector<Eigen::Vector3f> rays(static_cast<std::size_t>(w) * h);
  const Eigen::Matrix3d world_from_key = world_from_camera_rotation(key.heading);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      rays[static_cast<std::size_t>(v) * w + u] =
          (world_from_key * equirect_to_bearing({u + 0.5, v + 0.5}, w, h)).cast<float>();

  // Neighbours on both sides within the baselines (same piece: one frame), spread evenly over them: frames
  // further apart in time see a walking person further away.
  CleanPlate out;
  std::vector<Warped> warped;
  std::vector<int> within;
  for (int side : {-1, 1})
    for (int j = keyframe_position + side; j >= 0 && j < count; j += side) {
      const PathFrame& n = path.frames[static_cast<std::size_t>(j)];
      if (n.piece != key.piece) break;
      const double baseline = std::hypot(n.x - key.x, n.y - key.y);
      if (baseline > options.max_baseline_m) break;
      if (baseline >= options.min_baseline_m) within.push_back(j);
    }
  std::sort(within.begin(), within.end());
  std::vector<int> candidates;
  const std::size_t wanted = static_cast<std::size_t>(2 * options.neighbours);
  if (within.size() <= wanted) {
    candidates = within;
  } else {
    for (std::size_t i = 0; i < wanted; ++i)
      candidates.push_back(within[(i * (within.size() - 1)) / (wanted - 1)]);
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const int j = candidates[c];
    progress.checkpoint(double(c) / (candidates.size() + 1),
                        "warping frame " + std::to_string(path.frames[static_cast<std::size_t>(j)].index));
    const cv::Mat image = frame(j);
    if (image.size() != key_image.size() || image.type() != CV_8UC3)
      throw Error("clean plate: frame " + std::to_string(path.frames[static_cast<std::size_t>(j)].index) +
                  " differs in size or type from the keyframe");
    cv::Mat depth = static_depth(j);
    if (!depth.empty() && (depth.type() != CV_32F || depth.size() != key_image.size())) depth = cv::Mat();
    warped.push_back(warp_onto_keyframe(key, path.frames[static_cast<std::size_t>(j)], key_depth, image,
                                        depth, rays, options.occlusion_tolerance));
    out.neighbours_used.push_back(j);
  }
  progress.checkpoint(double(candidates.size()) / (candidates.size() + 1), "consensus");

  // Where the static depth jumps (an edge of a pillar, a door frame), a small pose or depth error moves the
  // warped edge: disagreement there is not a mover.
  cv::Mat log_depth, grad_x, grad_y, depth_edges;
  cv::log(cv::max(key_depth, 0.05), log_depth);
  cv::Sobel(log_depth, grad_x, CV_32F, 1, 0, 3);
  cv::Sobel(log_depth, grad_y, CV_32F, 0, 1, 3);
  cv::magnitude(grad_x, grad_y, depth_edges);
  depth_edges = depth_edges > options.depth_edge;
  cv::dilate(depth_edges, depth_edges, cv::Mat(), cv::Point(-1, -1), 2);

  // Median of the other frames per pixel and channel; the keyframe's disagreement with it.
  cv::Mat consensus = key_image.clone();
  cv::Mat disagree = cv::Mat::zeros(h, w, CV_8U), weak = cv::Mat::zeros(h, w, CV_8U);
  cv::Mat has_consensus = cv::Mat::zeros(h, w, CV_8U);
  out.support = cv::Mat::zeros(h, w, CV_8U);
  parallel_for_each(h, 0, [&](int v) {
    std::array<std::vector<std::uint8_t>, 3> samples;
    for (int u = 0; u < w; ++u) {
      for (auto& s : samples) s.clear();
      for (const Warped& wp : warped) {
        if (!wp.valid.at<std::uint8_t>(v, u)) continue;
        const cv::Vec3b& c = wp.image.at<cv::Vec3b>(v, u);
        for (int ch = 0; ch < 3; ++ch) samples[ch].push_back(c[ch]);
      }
      const int n = static_cast<int>(samples[0].size());
      out.support.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(std::min(n, 255));
      if (n < options.min_support) continue;
      cv::Vec3b median;
      for (int ch = 0; ch < 3; ++ch) {
        auto mid = samples[ch].begin() + n / 2;
        std::nth_element(samples[ch].begin(), mid, samples[ch].end());
        median[ch] = *mid;
      }
      consensus.at<cv::Vec3b>(v, u) = median;
      has_consensus.at<std::uint8_t>(v, u) = 255;
    }
  });
  // The keyframe disagrees where no consensus pixel within one pixel matches it: a sharp texture edge warped
  // half a pixel off is not a mover.
  parallel_for_each(h, 0, [&](int v) {
    for (int u = 0; u < w; ++u) {
      if (!has_consensus.at<std::uint8_t>(v, u)) continue;
      const cv::Vec3b& k = key_image.at<cv::Vec3b>(v, u);
      int best = 255;
      for (int dv = -1; dv <= 1 && best > options.disagreement; ++dv)
        for (int du = -1; du <= 1; ++du) {
          const int y = std::clamp(v + dv, 0, h - 1), x = (u + du + w) % w;
          if (!has_consensus.at<std::uint8_t>(y, x)) continue;
          const cv::Vec3b& c = consensus.at<cv::Vec3b>(y, x);
          int difference = 0;
          for (int ch = 0; ch < 3; ++ch) difference = std::max(difference, std::abs(int(k[ch]) - int(c[ch])));
          best = std::min(best, difference);
        }
      if (best > options.disagreement && !depth_edges.at<std::uint8_t>(v, u))
        disagree.at<std::uint8_t>(v, u) = 255;
      if (best > options.weak_disagreement) weak.at<std::uint8_t>(v, u) = 255;
    }
  });

  // Blobs large enough to be a mover, grown (hysteresis) over the weakly disagreeing pixels connected to
  // them, then replaced where the neighbours saw the scene.
  cv::Mat labels, stats, centroids;
  const int blobs = cv::connectedComponentsWithStats(disagree, labels, stats, centroids, 8, CV_32S);
  cv::Mat seeds = cv::Mat::zeros(h, w, CV_8U);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = labels.at<int>(v, u);
      if (l > 0 && l < blobs && stats.at<int>(l, cv::CC_STAT_AREA) >= options.min_region_px)
        seeds.at<std::uint8_t>(v, u) = 255;
    }
  cv::Mat weak_labels;
  const int weak_blobs = cv::connectedComponents(weak | seeds, weak_labels, 8, CV_32S);
  std::vector<std::uint8_t> seeded(static_cast<std::size_t>(weak_blobs), 0);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      if (seeds.at<std::uint8_t>(v, u)) seeded[static_cast<std::size_t>(weak_labels.at<int>(v, u))] = 1;
  cv::Mat moving = cv::Mat::zeros(h, w, CV_8U);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = weak_labels.at<int>(v, u);
      if (l > 0 && seeded[static_cast<std::size_t>(l)]) moving.at<std::uint8_t>(v, u) = 255;
    }
  // Holes inside a mover (a patch of clothing the colour of the wall behind it) are the mover too.
  if (options.mask_closing_px > 0)
    cv::morphologyEx(moving, moving, cv::MORPH_CLOSE,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * options.mask_closing_px + 1,
                                                                           2 * options.mask_closing_px + 1)));
  if (options.mask_dilation_px > 0)
    cv::dilate(moving, moving,
               cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * options.mask_dilation_px + 1,
                                                                     2 * options.mask_dilation_px + 1)));
  out.image = key_image.clone();
  out.moving_mask = cv::Mat::zeros(h, w, CV_8U);
  long moving_px = 0, unsupported = 0;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      if (!moving.at<std::uint8_t>(v, u)) continue;
      ++moving_px;
      if (out.support.at<std::uint8_t>(v, u) < options.min_support) {
        ++unsupported;
        continue;
      }
      out.image.at<cv::Vec3b>(v, u) = consensus.at<cv::Vec3b>(v, u);
      out.moving_mask.at<std::uint8_t>(v, u) = 255;
    }
  out.consensus = consensus;
  out.moving_share = double(moving_px) / (double(w) * h);
  out.unsupported_share = moving_px ? double(unsupported) / moving_px : 0.0;
  progress.report(1.0);
  return out;
}

}  // namespace plenopath
