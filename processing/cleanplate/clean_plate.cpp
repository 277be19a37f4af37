#include "processing/cleanplate/clean_plate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/cleanplate/colour_difference.h"
#include "processing/cleanplate/exposure_gain.h"
#include "processing/cleanplate/warp_geometry.h"
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
  require_option(rig_neighbours >= 1 && rig_neighbours <= 64, s + "rig_neighbours", "must be in [1, 64]",
                 rig_neighbours);
  require_option(rig_min_baseline_m >= 0, s + "rig_min_baseline_m", "must be >= 0", rig_min_baseline_m);
  require_option(rig_max_baseline_m > rig_min_baseline_m, s + "rig_max_baseline_m",
                 "must be > rig_min_baseline_m", rig_max_baseline_m);
  require_option(rig_min_support >= 1, s + "rig_min_support", "must be >= 1", rig_min_support);
  require_option(rig_tolerance >= 1 && rig_tolerance <= 128, s + "rig_tolerance", "must be in [1, 128]",
                 rig_tolerance);
  require_option(min_rig_region > 0 && min_rig_region < 1, s + "min_rig_region", "must be in (0, 1)",
                 min_rig_region);
  require_option(rig_margin_deg >= 0 && rig_margin_deg <= 30, s + "rig_margin_deg", "must be in [0, 30]",
                 rig_margin_deg);
  require_option(max_spread >= 1, s + "max_spread", "must be >= 1", max_spread);
  require_option(max_explained_share > 0 && max_explained_share <= 1, s + "max_explained_share",
                 "must be in (0, 1]", max_explained_share);
  require_option(detection_width >= 64, s + "detection_width", "must be >= 64", detection_width);
  require_option(camera_height_m >= 0, s + "camera_height_m", "must be >= 0 (0 = unknown)", camera_height_m);
}

namespace {

struct Warped {
  cv::Mat image;  // CV_8UC3 in the keyframe's pixels, at the keyframe's exposure
  cv::Mat valid;  // CV_8U
};

// Neighbour `n` warped onto the keyframe through `key_depth`, at the pixels of `where` (all when empty).
// A sample is dropped where the neighbour's own static depth says the point is hidden from it, or where the
// rig covers the neighbour's image.
// bearing_to_equirect (rig/spherical.h) in single precision, for the warps' inner loops: x in [0, w).
inline Eigen::Vector2f bearing_to_equirect_f(const Eigen::Vector3f& b, int w, int h) {
  constexpr float kPi = static_cast<float>(M_PI);
  const float azimuth = std::atan2(-b.y(), b.x());
  const float elevation = std::atan2(b.z(), std::sqrt(b.x() * b.x() + b.y() * b.y()));
  float x = (azimuth + kPi) / (2 * kPi) * w;
  if (x >= w) x -= w;
  if (x < 0) x += w;
  return {x, (kPi / 2 - elevation) / kPi * h};
}

// `moved` (when given): 255 where the sample comes from at least min_moved_px away (the seam wrapped).
// Where `where` is sparse (under a fifth of the image), the samples are taken there alone (bilinear);
// otherwise the whole image is remapped with `interpolation`.
Warped warp_onto_keyframe(const PathFrame& key, const PathFrame& n, const cv::Mat& key_depth,
                          const cv::Mat& image, const cv::Mat& depth, const cv::Mat& rig_mask,
                          const cv::Mat& where, const std::vector<Eigen::Vector3f>& rays,
                          double occlusion_tolerance, cv::Mat* moved = nullptr, double min_moved_px = 0,
                          int interpolation = cv::INTER_CUBIC) {
  const int w = key_depth.cols, h = key_depth.rows;
  const bool sparse = !where.empty() && cv::countNonZero(where) < w * h / 5;
  cv::Mat map_x, map_y;
  Warped out;
  out.valid = cv::Mat::zeros(h, w, CV_8U);
  if (sparse) {
    out.image = cv::Mat::zeros(h, w, CV_8UC3);
  } else {
    map_x.create(h, w, CV_32F);
    map_y.create(h, w, CV_32F);
    map_x.setTo(-1);
    map_y.setTo(-1);
  }
  if (moved) *moved = cv::Mat::zeros(h, w, CV_8U);
  const Eigen::Matrix3f n_from_world = world_from_camera_rotation(n.heading).transpose().cast<float>();
  const Eigen::Vector3f offset(static_cast<float>(key.x - n.x), static_cast<float>(key.y - n.y),
                               0.0f);  // the keyframe's centre seen from n
  const float visible = 1.0f - static_cast<float>(occlusion_tolerance);
  parallel_for_each(h, 0, [&](int v) {
    const std::uint8_t* where_row = where.empty() ? nullptr : where.ptr<std::uint8_t>(v);
    for (int u = 0; u < w; ++u) {
      if (where_row && !where_row[u]) continue;
      const float d = key_depth.at<float>(v, u);
      if (!(d > 0)) continue;
      const Eigen::Vector3f world = rays[static_cast<std::size_t>(v) * w + u] * d + offset;
      const float distance = world.norm();
      if (distance < 1e-6f) continue;
      const Eigen::Vector2f p = bearing_to_equirect_f(n_from_world * world, w, h);
      const int du = std::clamp(static_cast<int>(p.x()), 0, w - 1);
      const int dv = std::clamp(static_cast<int>(p.y()), 0, h - 1);
      if (!rig_mask.empty() && rig_mask.at<std::uint8_t>(dv, du)) continue;
      if (!depth.empty()) {
        const float seen = depth.at<float>(dv, du);
        if (seen > 0 && seen < distance * visible) continue;  // hidden from n
      }
      const float x = p.x() - 0.5f, y = std::clamp(p.y() - 0.5f, 0.0f, h - 1.0f);
      out.valid.at<std::uint8_t>(v, u) = 255;
      if (moved) {
        // (single precision is plenty: a pixel is 1e-3 of the width)
        const float du_wrapped = std::remainder(p.x() - (u + 0.5f), float(w)), dv_moved = p.y() - (v + 0.5f);
        if (du_wrapped * du_wrapped + dv_moved * dv_moved >= min_moved_px * min_moved_px)
          moved->at<std::uint8_t>(v, u) = 255;
      }
      if (!sparse) {
        map_x.at<float>(v, u) = x;
        map_y.at<float>(v, u) = y;
        continue;
      }
      // Sparse: the sample here and now, bilinear, the seam wrapped.
      const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(y);
      const float fx = x - x0, fy = y - y0;
      const int xa = (x0 % w + w) % w, xb = (xa + 1) % w, yb = std::min(y0 + 1, h - 1);
      const cv::Vec3b &a = image.at<cv::Vec3b>(y0, xa), &b = image.at<cv::Vec3b>(y0, xb),
                      &c = image.at<cv::Vec3b>(yb, xa), &e = image.at<cv::Vec3b>(yb, xb);
      cv::Vec3b& o = out.image.at<cv::Vec3b>(v, u);
      for (int ch = 0; ch < 3; ++ch)
        o[ch] = cv::saturate_cast<std::uint8_t>((1 - fy) * ((1 - fx) * a[ch] + fx * b[ch]) +
                                                fy * ((1 - fx) * c[ch] + fx * e[ch]));
    }
  });
  if (!sparse) cv::remap(image, out.image, map_x, map_y, interpolation, cv::BORDER_WRAP);
  return out;
}

// Brings a warped neighbour to the keyframe's exposure (exposure_gain.h) over the pixels of `where` (every
// valid pixel when empty).
cv::Scalar match_exposure(Warped& warped, const cv::Mat& key_image, const cv::Mat& where) {
  const cv::Scalar gain = exposure_gain(key_image, warped.image, warped.valid, where);
  if (gain != cv::Scalar::all(1)) cv::multiply(warped.image, gain, warped.image);
  return gain;
}

// Per pixel and channel, the median of the valid warped samples, where `where` is set (all when empty) and
// at least min_support samples are; `support` counts them; `spread` (when given) is their median absolute
// deviation from it (max over the channels): low where the frames agree among themselves, high where the
// warp is unsure (an object the static depth does not know of lands somewhere else in each frame).
void median_of(const std::vector<Warped>& warped, const cv::Mat& where, int min_support, cv::Mat& consensus,
               cv::Mat& has_consensus, cv::Mat& support, cv::Mat* spread = nullptr) {
  const int h = consensus.rows, w = consensus.cols;
  parallel_for_each(h, 0, [&](int v) {
    std::array<std::array<std::uint8_t, 130>, 3> samples;
    for (int u = 0; u < w; ++u) {
      if (!where.empty() && !where.at<std::uint8_t>(v, u)) continue;
      int n = 0;
      for (const Warped& wp : warped) {
        if (!wp.valid.at<std::uint8_t>(v, u)) continue;
        const cv::Vec3b& c = wp.image.at<cv::Vec3b>(v, u);
        for (int ch = 0; ch < 3; ++ch) samples[ch][n] = c[ch];
        ++n;
      }
      support.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(std::min(n, 255));
      if (n < min_support) continue;
      cv::Vec3b median;
      int deviation = 0;
      for (int ch = 0; ch < 3; ++ch) {
        auto begin = samples[ch].begin(), mid = begin + n / 2;
        std::nth_element(begin, mid, begin + n);
        median[ch] = *mid;
        if (spread) {
          for (int i = 0; i < n; ++i)
            samples[ch][i] = static_cast<std::uint8_t>(std::abs(int(samples[ch][i]) - median[ch]));
          std::nth_element(begin, mid, begin + n);
          deviation = std::max(deviation, int(*mid));
        }
      }
      if (spread) spread->at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(deviation);
      consensus.at<cv::Vec3b>(v, u) = median;
      has_consensus.at<std::uint8_t>(v, u) = 255;
    }
  });
}

// The keyframe's depth with the rig's pixels replaced by the scene behind the rig: the surroundings' depth
// carried in (inpainted at a coarse width, the seam wrapped), and below the horizon never beyond the floor
// plane when the camera height is known.
cv::Mat depth_behind_rig(const cv::Mat& key_depth, const cv::Mat& rig,
                         const std::vector<Eigen::Vector3f>& rays, double camera_height) {
  const int w = key_depth.cols, h = key_depth.rows;
  const int small_w = std::min(w, 256), small_h = std::max(1, small_w * h / w), pad = small_w / 4;
  cv::Mat small_depth, small_rig, unknown;
  cv::resize(key_depth, small_depth, {small_w, small_h}, 0, 0, cv::INTER_NEAREST);
  cv::resize(rig, small_rig, {small_w, small_h}, 0, 0, cv::INTER_NEAREST);
  cv::dilate(small_rig, small_rig, cv::Mat());
  unknown = small_rig | (small_depth <= 0);
  cv::Mat padded_depth, padded_unknown, filled;
  cv::copyMakeBorder(small_depth, padded_depth, 0, 0, pad, pad, cv::BORDER_WRAP);
  cv::copyMakeBorder(unknown, padded_unknown, 0, 0, pad, pad, cv::BORDER_WRAP);
  padded_depth.setTo(0, padded_unknown);
  cv::inpaint(padded_depth, padded_unknown, filled, 3, cv::INPAINT_TELEA);
  cv::Mat behind;
  cv::resize(filled(cv::Rect(pad, 0, small_w, small_h)), behind, {w, h}, 0, 0, cv::INTER_LINEAR);
  cv::Mat out = key_depth.clone();
  parallel_for_each(h, 0, [&](int v) {
    for (int u = 0; u < w; ++u) {
      if (!rig.at<std::uint8_t>(v, u)) continue;
      float d = behind.at<float>(v, u);
      const float down = -rays[static_cast<std::size_t>(v) * w + u].z();
      if (camera_height > 0 && down > 0.02f) {
        const float floor = static_cast<float>(camera_height) / down;
        d = d > 0 ? std::min(d, floor) : floor;
      }
      out.at<float>(v, u) = d;
    }
  });
  return out;
}

cv::Mat ellipse(int radius) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1));
}

struct Neighbour {
  const PathFrame* pose = nullptr;
  cv::Mat image, depth;
  cv::Scalar gain = cv::Scalar::all(1);  // to the keyframe's exposure
};

// Whether a disagreeing keyframe pixel is static geometry that the static depth does not know of (a box on
// a wall, furniture off the plan): then the neighbours' own images agree with it at some other depth along
// its ray (a plane sweep over log-spaced depths). A mover is at no depth that most of them agree on.
bool explained_by_another_depth(const PathFrame& key, const cv::Vec3b& colour, const Eigen::Vector3f& ray,
                                const std::vector<Neighbour>& neighbours, const cv::Mat& rig_in_neighbours,
                                int tolerance) {
  constexpr int kDepths = 28;
  constexpr double kNear = 0.3, kFar = 60.0;
  const int w = neighbours.front().image.cols, h = neighbours.front().image.rows;
  for (int d = 0; d < kDepths; ++d) {
    const double depth = kNear * std::pow(kFar / kNear, d / double(kDepths - 1));
    int agree = 0, seen = 0;
    for (const Neighbour& n : neighbours) {
      const Eigen::Vector3d world =
          ray.cast<double>() * depth + Eigen::Vector3d(key.x - n.pose->x, key.y - n.pose->y, 0.0);
      const Eigen::Vector2d p =
          bearing_to_equirect(world_from_camera_rotation(n.pose->heading).transpose() * world, w, h);
      const int u = std::clamp(static_cast<int>(p.x()), 0, w - 1),
                v = std::clamp(static_cast<int>(p.y()), 0, h - 1);
      // A neighbour that sees its own rig there counts against: with an operator in the rig, the frames
      // ahead see any point near the camera through their operator, and the few frames left would agree
      // with someone walking along with the camera by chance.
      ++seen;
      if (!rig_in_neighbours.empty() && rig_in_neighbours.at<std::uint8_t>(v, u)) continue;
      if (max_channel_difference(colour, n.image.at<cv::Vec3b>(v, u), n.gain) <= tolerance) ++agree;
    }
    if (seen >= 3 && agree >= 0.5 * seen) return true;
  }
  return false;
}

// What moves with the camera (the operator, the trolley, someone walking along), at a coarse width, from
// frames far enough away that the scene moves in their images: a pixel that agrees with most of them at the
// same pixel (at the keyframe's exposure) and with few of the samples that the scene's geometry brings there
// from elsewhere. A blank wall agrees both ways and is not taken. Returns CV_8U at the keyframe's size.
cv::Mat moves_with_camera(const PathFrame& key, const cv::Mat& key_image, const cv::Mat& key_depth,
                          const std::vector<Neighbour>& neighbours, const CleanPlateOptions& options) {
  const int w = key_image.cols, h = key_image.rows;
  const int dw = std::min(w, 256), dh = std::max(1, dw * h / w);
  cv::Mat key_small, depth_small;
  cv::resize(key_image, key_small, {dw, dh}, 0, 0, cv::INTER_AREA);
  cv::resize(key_depth, depth_small, {dw, dh}, 0, 0, cv::INTER_NEAREST);
  const std::vector<Eigen::Vector3f> rays = plan_rays(key.heading, dw, dh);
  cv::Mat raw_agree = cv::Mat::zeros(dh, dw, CV_8U), warp_agree = cv::Mat::zeros(dh, dw, CV_8U),
          warp_valid = cv::Mat::zeros(dh, dw, CV_8U);
  const int tolerance = options.rig_tolerance;
  for (const Neighbour& n : neighbours) {
    cv::Mat small, moved;
    cv::resize(n.image, small, {dw, dh}, 0, 0, cv::INTER_AREA);
    Warped warped = warp_onto_keyframe(key, *n.pose, depth_small, small, cv::Mat(), cv::Mat(), cv::Mat(),
                                       rays, options.occlusion_tolerance, &moved, 1.5);
    const cv::Scalar gain = match_exposure(warped, key_small, {});
    for (int v = 0; v < dh; ++v)
      for (int u = 0; u < dw; ++u) {
        const cv::Vec3b& k = key_small.at<cv::Vec3b>(v, u);
        if (max_channel_difference(k, small.at<cv::Vec3b>(v, u), gain) <= tolerance)
          ++raw_agree.at<std::uint8_t>(v, u);
        if (!warped.valid.at<std::uint8_t>(v, u) || !moved.at<std::uint8_t>(v, u)) continue;
        ++warp_valid.at<std::uint8_t>(v, u);
        if (max_channel_difference(k, warped.image.at<cv::Vec3b>(v, u)) <= tolerance)
          ++warp_agree.at<std::uint8_t>(v, u);
      }
  }
  const int count = static_cast<int>(neighbours.size());
  cv::Mat small_mask = cv::Mat::zeros(dh, dw, CV_8U);
  for (int v = 0; v < dh; ++v)
    for (int u = 0; u < dw; ++u) {
      const int valid = warp_valid.at<std::uint8_t>(v, u);
      if (raw_agree.at<std::uint8_t>(v, u) >= 0.6 * count && valid >= 3 &&
          warp_agree.at<std::uint8_t>(v, u) <= 0.3 * valid)
        small_mask.at<std::uint8_t>(v, u) = 255;
    }
  // Holes closed (a uniform shirt is found by its outline and its folds), small blobs dropped.
  cv::morphologyEx(small_mask, small_mask, cv::MORPH_CLOSE, ellipse(2));
  cv::Mat labels, stats, centres;
  const int found = cv::connectedComponentsWithStats(small_mask, labels, stats, centres, 8, CV_32S);
  const double min_area = options.min_rig_region * dw * dh;
  for (int v = 0; v < dh; ++v)
    for (int u = 0; u < dw; ++u) {
      const int l = labels.at<int>(v, u);
      if (l > 0 && l < found && stats.at<int>(l, cv::CC_STAT_AREA) < min_area)
        small_mask.at<std::uint8_t>(v, u) = 0;
    }
  cv::Mat mask;
  cv::resize(small_mask, mask, {w, h}, 0, 0, cv::INTER_NEAREST);
  if (cv::countNonZero(mask) == 0) return mask;
  cv::dilate(mask, mask, ellipse(std::max(1, w / 256)));  // the coarse outline, the rig's soft edges
  return mask;
}

}  // namespace

namespace {

// What the first stage found at a coarser width, brought to this one: the pass then only warps and fills.
struct Found {
  cv::Mat moving;  // CV_8U, the movers to replace
  cv::Mat rig;     // CV_8U, the rig given and the rig found (empty: none)
};

// Stage 3: the movers, from the keyframe's disagreement with the consensus (see the header).
cv::Mat find_movers(const PathFrame& key, const cv::Mat& key_image, const cv::Mat& key_depth,
                    const std::vector<Eigen::Vector3f>& rays, const cv::Mat& consensus,
                    const cv::Mat& has_consensus, const cv::Mat& spread, const cv::Mat& rig,
                    const std::vector<Neighbour>& near, const cv::Mat& rig_in_neighbours,
                    const CleanPlateOptions& options) {
  const int w = key_image.cols, h = key_image.rows;
  // Where the static depth jumps (an edge of a pillar, a door frame), a small pose or depth error moves the
  // warped edge: disagreement there is not a mover.
  cv::Mat log_depth, grad_x, grad_y, depth_edges;
  cv::log(cv::max(key_depth, 0.05), log_depth);
  cv::Sobel(log_depth, grad_x, CV_32F, 1, 0, 3);
  cv::Sobel(log_depth, grad_y, CV_32F, 0, 1, 3);
  cv::magnitude(grad_x, grad_y, depth_edges);
  depth_edges = depth_edges > options.depth_edge;
  cv::dilate(depth_edges, depth_edges, cv::Mat(), cv::Point(-1, -1), 2);

  cv::Mat disagree = cv::Mat::zeros(h, w, CV_8U), weak = cv::Mat::zeros(h, w, CV_8U);
  // The keyframe disagrees where no consensus pixel within one pixel matches it: a sharp texture edge warped
  // half a pixel off is not a mover.
  parallel_for_each(h, 0, [&](int v) {
    for (int u = 0; u < w; ++u) {
      if (!has_consensus.at<std::uint8_t>(v, u) || (!rig.empty() && rig.at<std::uint8_t>(v, u))) continue;
      const cv::Vec3b& k = key_image.at<cv::Vec3b>(v, u);
      int best = 255;
      for (int dv = -1; dv <= 1 && best > options.disagreement; ++dv)
        for (int du = -1; du <= 1; ++du) {
          const int y = std::clamp(v + dv, 0, h - 1), x = (u + du + w) % w;
          if (!has_consensus.at<std::uint8_t>(y, x)) continue;
          best = std::min(best, max_channel_difference(k, consensus.at<cv::Vec3b>(y, x)));
        }
      if (best > options.disagreement && !depth_edges.at<std::uint8_t>(v, u) &&
          spread.at<std::uint8_t>(v, u) <= options.max_spread)
        disagree.at<std::uint8_t>(v, u) = 255;
      if (best > options.weak_disagreement) weak.at<std::uint8_t>(v, u) = 255;
    }
  });

  // Blobs large enough to be a mover, grown (hysteresis) over the weakly disagreeing pixels connected to
  // them, then replaced where the neighbours saw the scene.
  cv::Mat labels, stats, centroids;
  const int blobs = cv::connectedComponentsWithStats(disagree, labels, stats, centroids, 8, CV_32S);
  // A blob most of whose pixels the neighbours agree with at another depth is static geometry the static
  // depth does not know of: left as the keyframe has it (judged on a sparse grid of its pixels).
  std::vector<int> tested(static_cast<std::size_t>(blobs), 0), explained(static_cast<std::size_t>(blobs), 0);
  if (!near.empty()) {
    std::vector<std::pair<int, int>> grid;
    const int step = std::max(1, w / 512);
    for (int v = 0; v < h; v += step)
      for (int u = 0; u < w; u += step) {
        const int l = labels.at<int>(v, u);
        if (l > 0 && l < blobs && stats.at<int>(l, cv::CC_STAT_AREA) >= options.min_region_px)
          grid.emplace_back(v, u);
      }
    std::vector<std::uint8_t> is_explained(grid.size(), 0);
    parallel_for_each(static_cast<int>(grid.size()), 0, [&](int i) {
      const auto [v, u] = grid[static_cast<std::size_t>(i)];
      is_explained[static_cast<std::size_t>(i)] = explained_by_another_depth(
          key, key_image.at<cv::Vec3b>(v, u), rays[static_cast<std::size_t>(v) * w + u], near,
          rig_in_neighbours, static_cast<int>(options.weak_disagreement * 2));
    });
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const int l = labels.at<int>(grid[i].first, grid[i].second);
      ++tested[static_cast<std::size_t>(l)];
      explained[static_cast<std::size_t>(l)] += is_explained[i];
    }
  }
  // The seeds grow over the weakly disagreeing pixels connected to them; a grown region is a mover unless
  // its seeds are mostly explained (a box in front of a wall disagrees in two blobs: where it is and where
  // the warp puts it; together they are explained).
  cv::Mat seeds = cv::Mat::zeros(h, w, CV_8U);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = labels.at<int>(v, u);
      if (l > 0 && l < blobs && stats.at<int>(l, cv::CC_STAT_AREA) >= options.min_region_px)
        seeds.at<std::uint8_t>(v, u) = 255;
    }
  cv::Mat weak_labels;
  const int weak_blobs = cv::connectedComponents(weak | seeds, weak_labels, 8, CV_32S);
  std::vector<int> region_tested(static_cast<std::size_t>(weak_blobs), 0),
      region_explained(static_cast<std::size_t>(weak_blobs), 0);
  std::vector<int> blob_region(static_cast<std::size_t>(blobs), -1);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      if (seeds.at<std::uint8_t>(v, u))
        blob_region[static_cast<std::size_t>(labels.at<int>(v, u))] = weak_labels.at<int>(v, u);
  for (int l = 1; l < blobs; ++l) {
    const int region = blob_region[static_cast<std::size_t>(l)];
    if (region < 0) continue;
    region_tested[static_cast<std::size_t>(region)] += tested[static_cast<std::size_t>(l)];
    region_explained[static_cast<std::size_t>(region)] += explained[static_cast<std::size_t>(l)];
  }
  std::vector<std::uint8_t> seeded(static_cast<std::size_t>(weak_blobs), 0);
  for (int region = 1; region < weak_blobs; ++region)
    seeded[static_cast<std::size_t>(region)] =
        region_tested[static_cast<std::size_t>(region)] > 0 &&
        region_explained[static_cast<std::size_t>(region)] <=
            options.max_explained_share * region_tested[static_cast<std::size_t>(region)];
  cv::Mat moving = cv::Mat::zeros(h, w, CV_8U);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = weak_labels.at<int>(v, u);
      if (l > 0 && seeded[static_cast<std::size_t>(l)]) moving.at<std::uint8_t>(v, u) = 255;
    }
  // Holes inside a mover (a patch of clothing the colour of the wall behind it) are the mover too.
  if (options.mask_closing_px > 0)
    cv::morphologyEx(moving, moving, cv::MORPH_CLOSE, ellipse(options.mask_closing_px));
  if (options.mask_dilation_px > 0) cv::dilate(moving, moving, ellipse(options.mask_dilation_px));
  if (!rig.empty()) moving.setTo(0, rig);  // the rig is filled on its own
  return moving;
}

// Stage 4: the rig, from the frames further away, warped through the depth of the scene behind it and
// brought to the keyframe's exposure on a band round the rig (what the fill must join without a seam).
void fill_rig(const PathFrame& key, const cv::Mat& key_image, const cv::Mat& key_depth,
              const std::vector<Eigen::Vector3f>& rays, const cv::Mat& rig, const std::vector<Neighbour>& far,
              const cv::Mat& rig_in_neighbours, const CleanPlateOptions& options, CleanPlate& out,
              Progress& progress) {
  const int w = key_image.cols, h = key_image.rows;
  const cv::Mat rig_depth = depth_behind_rig(key_depth, rig, rays, options.camera_height_m);
  cv::Mat band, rig_and_band;
  cv::dilate(rig, rig_and_band, ellipse(std::max(4, w / 128)));
  band = rig_and_band & ~rig;
  std::vector<Warped> warped;
  for (std::size_t c = 0; c < far.size(); ++c) {
    progress.checkpoint(double(c) / far.size(),
                        "filling the rig from frame " + std::to_string(far[c].pose->index));
    warped.push_back(warp_onto_keyframe(key, *far[c].pose, rig_depth, far[c].image, far[c].depth,
                                        rig_in_neighbours, rig_and_band, rays, options.occlusion_tolerance));
    match_exposure(warped.back(), key_image, band);
  }
  cv::Mat rig_consensus = key_image.clone(), rig_has = cv::Mat::zeros(h, w, CV_8U);
  cv::Mat rig_support = cv::Mat::zeros(h, w, CV_8U);
  median_of(warped, rig, options.rig_min_support, rig_consensus, rig_has, rig_support);
  out.rig_filled = rig_has.clone();
  out.rig_unfilled = rig & ~rig_has;
  rig_consensus.copyTo(out.image, out.rig_filled);
  rig_consensus.copyTo(out.consensus, out.rig_filled);
  const int rig_px = cv::countNonZero(rig);
  out.rig_share = double(rig_px) / (double(w) * h);
  out.rig_unfilled_share = double(cv::countNonZero(out.rig_unfilled)) / std::max(1, rig_px);
}

// The clean plate at the frames' own width. With `found`, the movers and the rig come from a coarser pass:
// the neighbours are warped only there (and on a sparse grid, for their exposure).
CleanPlate clean_plate_at(const CameraPath& path, int keyframe_position,
                          const std::function<cv::Mat(int position)>& frame,
                          const std::function<cv::Mat(int position)>& static_depth, const cv::Mat& rig_mask,
                          const CleanPlateOptions& options, Progress& progress, const Found* found,
                          int interpolation = cv::INTER_CUBIC) {
  const PathFrame& key = path.frames[static_cast<std::size_t>(keyframe_position)];
  const cv::Mat key_image = frame(keyframe_position);
  const cv::Mat key_depth = static_depth(keyframe_position);
  const int w = key_image.cols, h = key_image.rows;
  cv::Mat rig;
  if (found) {
    rig = found->rig;
  } else if (!rig_mask.empty() && cv::countNonZero(rig_mask) > 0) {
    rig = rig_mask != 0;
  }
  const std::vector<Eigen::Vector3f> rays = plan_rays(key.heading, w, h);
  CleanPlate out;
  const std::vector<int> candidates = neighbours_within(path, keyframe_position, options.min_baseline_m,
                                                        options.max_baseline_m, options.neighbours);
  const std::vector<int> rig_candidates =
      neighbours_within(path, keyframe_position, options.rig_min_baseline_m, options.rig_max_baseline_m,
                        options.rig_neighbours);
  auto read_neighbour = [&](int j) {
    Neighbour n;
    n.pose = &path.frames[static_cast<std::size_t>(j)];
    n.image = frame(j);
    if (n.image.size() != key_image.size() || n.image.type() != CV_8UC3)
      throw Error("clean plate: frame " + std::to_string(n.pose->index) +
                  " differs in size or type from the keyframe");
    n.depth = static_depth(j);
    if (!n.depth.empty() && (n.depth.type() != CV_32F || n.depth.size() != key_image.size()))
      n.depth = cv::Mat();
    return n;
  };

  // The frames further away: read once, for finding what moves with the camera and for filling it.
  SubProgress reading(progress, 0.0, 0.25, "reading frames");
  std::vector<Neighbour> far;
  if (!rig.empty() || (options.detect_rig && !found))
    for (std::size_t c = 0; c < rig_candidates.size(); ++c) {
      reading.checkpoint(double(c) / rig_candidates.size());
      far.push_back(read_neighbour(rig_candidates[c]));
    }
  if (!found && options.detect_rig && far.size() >= 4) {
    const cv::Mat moves = moves_with_camera(key, key_image, key_depth, far, options);
    if (cv::countNonZero(moves) > 0) {
      out.detected_rig = moves;
      rig = rig.empty() ? moves : (rig | moves);
    }
  }
  const cv::Mat not_rig = rig.empty() ? cv::Mat() : cv::Mat(rig == 0);
  // In the neighbours' images the rig is looked past with a margin: an operator's arms and legs swing, and
  // what one frame's mask misses of them would come back as a ghost.
  cv::Mat rig_in_neighbours;
  if (!rig.empty())
    cv::dilate(rig, rig_in_neighbours,
               ellipse(std::max(2, static_cast<int>(w * options.rig_margin_deg / 360))));

  // Stage 1: the neighbours warped onto the keyframe (with `found`: at the movers, and on a sparse grid
  // away from them for the exposure).
  cv::Mat where = not_rig, exposure_where;
  if (found) {
    cv::Mat grid = cv::Mat::zeros(h, w, CV_8U);
    for (int v = 0; v < h; v += 8)
      for (int u = 0; u < w; u += 8) grid.at<std::uint8_t>(v, u) = 255;
    exposure_where = grid & ~found->moving;
    if (!rig.empty()) exposure_where &= not_rig;
    where = (found->moving | grid);
    if (!rig.empty()) where &= not_rig;
  }
  SubProgress warping(progress, 0.25, 0.7, "warping frames");
  std::vector<Warped> warped;
  std::vector<Neighbour> near;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    warping.checkpoint(
        double(c) / candidates.size(),
        "warping frame " + std::to_string(path.frames[static_cast<std::size_t>(candidates[c])].index));
    Neighbour n = read_neighbour(candidates[c]);
    warped.push_back(warp_onto_keyframe(key, *n.pose, key_depth, n.image, n.depth, rig_in_neighbours, where,
                                        rays, options.occlusion_tolerance, nullptr, 0, interpolation));
    n.gain = match_exposure(warped.back(), key_image, exposure_where);
    n.depth = cv::Mat();
    if (!found) near.push_back(std::move(n));
    out.neighbours_used.push_back(candidates[c]);
  }
  progress.checkpoint(0.7, "consensus");

  // Stage 2: the median of the other frames; stage 3: the movers, replaced where the neighbours saw the
  // scene.
  cv::Mat consensus = key_image.clone(), has_consensus = cv::Mat::zeros(h, w, CV_8U);
  cv::Mat spread = cv::Mat::zeros(h, w, CV_8U);
  out.support = cv::Mat::zeros(h, w, CV_8U);
  median_of(warped, found ? found->moving : not_rig, options.min_support, consensus, has_consensus,
            out.support, found ? nullptr : &spread);
  warped.clear();
  const cv::Mat moving =
      found ? cv::Mat(found->moving & (rig.empty() ? cv::Mat(h, w, CV_8U, cv::Scalar(255)) : not_rig))
            : find_movers(key, key_image, key_depth, rays, consensus, has_consensus, spread, rig, near,
                          rig_in_neighbours, options);
  near.clear();
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

  if (!rig.empty()) {
    SubProgress filling(progress, 0.75, 1.0, "filling the rig");
    fill_rig(key, key_image, key_depth, rays, rig, far, rig_in_neighbours, options, out, filling);
    for (const Neighbour& n : far)
      out.rig_neighbours_used.push_back(static_cast<int>(n.pose - path.frames.data()));
  }
  progress.report(1.0);
  return out;
}

cv::Mat upscaled(const cv::Mat& mask, cv::Size size, int grow) {
  if (mask.empty()) return {};
  cv::Mat out;
  cv::resize(mask, out, size, 0, 0, cv::INTER_NEAREST);
  if (grow > 0) cv::dilate(out, out, ellipse(grow));
  return out;
}

}  // namespace

CleanPlate clean_plate(const CameraPath& path, int keyframe_position,
                       const std::function<cv::Mat(int position)>& frame,
                       const std::function<cv::Mat(int position)>& static_depth, const cv::Mat& rig_mask,
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
  if (!rig_mask.empty() && (rig_mask.type() != CV_8U || rig_mask.size() != key_image.size()))
    throw Error("clean plate: the rig mask is not a grey image of the frames' size (" +
                std::to_string(key_image.cols) + " x " + std::to_string(key_image.rows) + ")");
  const int w = key_image.cols, h = key_image.rows;
  if (w <= options.detection_width)
    return clean_plate_at(path, keyframe_position, frame, static_depth, rig_mask, options, progress, nullptr);

  // Wider frames: the movers and the rig found at detection_width (a quarter of the pixels at 2048), then
  // warped and filled at full width only there. Frames read once for both (up to 4096 wide: about 36
  // frames of 24 MB at most).
  const cv::Size small(options.detection_width, std::max(1, options.detection_width * h / w));
  const bool keep = w <= 4096;
  std::map<int, cv::Mat> images;
  auto full_frame = [&](int position) -> cv::Mat {
    if (position == keyframe_position) return key_image;
    auto it = images.find(position);
    if (it != images.end()) return it->second;
    cv::Mat image = frame(position);
    if (keep) images.emplace(position, image);
    return image;
  };
  auto small_frame = [&](int position) {
    const cv::Mat image = full_frame(position);
    if (image.empty() || image.type() != CV_8UC3) return image;
    cv::Mat out;
    cv::resize(image, out, small, 0, 0, cv::INTER_AREA);
    return out;
  };
  // Depths too: from the plan they are rendered, and both passes need them.
  std::map<int, cv::Mat> depths;
  auto full_depth = [&](int position) -> cv::Mat {
    if (position == keyframe_position) return key_depth;
    auto it = depths.find(position);
    if (it != depths.end()) return it->second;
    cv::Mat depth = static_depth(position);
    if (keep) depths.emplace(position, depth);
    return depth;
  };
  auto small_depth = [&](int position) {
    const cv::Mat depth = full_depth(position);
    if (depth.empty() || depth.type() != CV_32F) return depth;
    cv::Mat out;
    cv::resize(depth, out, small, 0, 0, cv::INTER_NEAREST);
    return out;
  };
  cv::Mat small_rig_mask;
  if (!rig_mask.empty()) cv::resize(rig_mask, small_rig_mask, small, 0, 0, cv::INTER_NEAREST);
  SubProgress coarse_progress(progress, 0.0, 0.45, "finding what moved");
  // Bicubic there too: a bilinear warp blurs texture, which then disagrees with the sharp keyframe (11 %
  // of a 2048-wide render taken for movers instead of 2 %).
  const CleanPlate coarse = clean_plate_at(path, keyframe_position, small_frame, small_depth, small_rig_mask,
                                           options, coarse_progress, nullptr, cv::INTER_CUBIC);
  Found found;
  const int grow = (w + options.detection_width - 1) / options.detection_width;
  found.moving = upscaled(coarse.moving_mask, key_image.size(), grow);
  cv::Mat rig;
  if (!rig_mask.empty() && cv::countNonZero(rig_mask) > 0) rig = rig_mask != 0;
  if (!coarse.detected_rig.empty()) {
    const cv::Mat detected = upscaled(coarse.detected_rig, key_image.size(), grow);
    rig = rig.empty() ? detected : (rig | detected);
  }
  found.rig = rig;
  SubProgress fine_progress(progress, 0.45, 1.0, "replacing what moved");
  CleanPlate out = clean_plate_at(path, keyframe_position, full_frame, full_depth, rig_mask, options,
                                  fine_progress, &found);
  out.detected_rig = upscaled(coarse.detected_rig, key_image.size(), grow);
  return out;
}

}  // namespace plenopath
