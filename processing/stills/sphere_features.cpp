#include "processing/stills/sphere_features.h"

#include <algorithm>
#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/util/grey_image.h"
#include "rig/spherical.h"

namespace plenopath {

void SphereFeatureOptions::check() const {
  const std::string s = "SphereFeatureOptions.";
  require_option(work_width >= 64 && work_width % 2 == 0, s + "work_width", "must be even and >= 64",
                 work_width);
  require_option(max_features >= 16, s + "max_features", "must be >= 16", max_features);
  require_option(max_abs_elevation_deg > 0 && max_abs_elevation_deg <= 90, s + "max_abs_elevation_deg",
                 "must be in (0, 90]", max_abs_elevation_deg);
  require_option(equalize_clip >= 0, s + "equalize_clip", "must be >= 0 (0 = off)", equalize_clip);
  require_option(contrast_threshold > 0, s + "contrast_threshold", "must be > 0", contrast_threshold);
}

namespace {

// The columns [w/4, 3w/4) of `grey` (and their keypoints) are the copy's own; the rest belong to the other.
void detect_central_half(const cv::Mat& grey, int shift, int max_features, double contrast_threshold,
                         double max_abs_elevation, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) {
  const int w = grey.cols, h = grey.rows;
  // Ask for more than needed: the outer half is thrown away.
  cv::Ptr<cv::SIFT> sift = cv::SIFT::create(2 * max_features, 3, contrast_threshold);
  std::vector<cv::KeyPoint> detected;
  sift->detect(grey, detected);
  std::vector<cv::KeyPoint> kept;
  for (const cv::KeyPoint& k : detected) {
    if (k.pt.x < 0.25f * w || k.pt.x >= 0.75f * w) continue;
    // The descriptor's support (a radius of about 5.3 x the keypoint's size in OpenCV's SIFT) must stay
    // inside the copy, which extends a quarter width beyond the kept half on each side.
    if (k.size > w / 24.0f) continue;
    const double elevation = M_PI / 2 - ((k.pt.y + 0.5) / h) * M_PI;  // at the pixel centre
    if (std::abs(elevation) > max_abs_elevation) continue;
    kept.push_back(k);
  }
  std::sort(kept.begin(), kept.end(),
            [](const cv::KeyPoint& a, const cv::KeyPoint& b) { return a.response > b.response; });
  if (static_cast<int>(kept.size()) > max_features) kept.resize(static_cast<std::size_t>(max_features));
  cv::Mat desc;
  sift->compute(grey, kept, desc);
  for (cv::KeyPoint& k : kept) {
    k.pt.x = std::fmod(k.pt.x + static_cast<float>(shift), static_cast<float>(w));
    if (k.pt.x < 0) k.pt.x += static_cast<float>(w);
  }
  keypoints->insert(keypoints->end(), kept.begin(), kept.end());
  descriptors->push_back(desc);
}

// SIFT may report one keypoint twice (the same place, size and orientation from neighbouring scales): the
// copy with the weaker response goes, so that no direction is matched twice.
void remove_duplicates(std::vector<cv::KeyPoint>* keypoints, cv::Mat* descriptors) {
  const int n = static_cast<int>(keypoints->size());
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return (*keypoints)[static_cast<std::size_t>(a)].pt.x < (*keypoints)[static_cast<std::size_t>(b)].pt.x;
  });
  std::vector<char> drop(static_cast<std::size_t>(n), 0);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const cv::KeyPoint& a = (*keypoints)[static_cast<std::size_t>(order[i])];
    for (std::size_t j = i + 1; j < order.size(); ++j) {
      const cv::KeyPoint& b = (*keypoints)[static_cast<std::size_t>(order[j])];
      if (b.pt.x - a.pt.x >= 0.5f) break;
      const float dangle = std::abs(std::remainder(a.angle - b.angle, 360.0f));
      if (std::abs(a.pt.y - b.pt.y) < 0.5f && std::abs(a.size - b.size) < 0.01f * a.size && dangle < 1.0f)
        drop[static_cast<std::size_t>(a.response >= b.response ? order[j] : order[i])] = 1;
    }
  }
  std::vector<cv::KeyPoint> kept;
  cv::Mat kept_descriptors;
  for (int i = 0; i < n; ++i) {
    if (drop[static_cast<std::size_t>(i)]) continue;
    kept.push_back((*keypoints)[static_cast<std::size_t>(i)]);
    kept_descriptors.push_back(descriptors->row(i));
  }
  *keypoints = std::move(kept);
  *descriptors = kept_descriptors;
}

}  // namespace

SphereFeatures detect_sphere_features(const cv::Mat& image, const SphereFeatureOptions& options) {
  options.check();
  if (image.empty()) throw Error("sphere features: empty image");
  if (image.cols != 2 * image.rows)
    throw Error("sphere features: the panorama is " + std::to_string(image.cols) + " x " +
                std::to_string(image.rows) + ", not equirectangular (width = 2 x height)");
  cv::Mat grey = grey_image_8u(image, "sphere features");
  const int w = options.work_width, h = w / 2;
  if (grey.cols != w)
    cv::resize(grey, grey, cv::Size(w, h), 0, 0, grey.cols > w ? cv::INTER_AREA : cv::INTER_LINEAR);
  // Equalised round the seam: one tile of w / 16 columns wrapped on each side, so that no direction sits at
  // an image border of the equalisation (a turned camera gets the same values).
  if (options.equalize_clip > 0) {
    const int tile = w / 16;
    cv::Mat padded, equalised;
    cv::copyMakeBorder(grey, padded, 0, 0, tile, tile, cv::BORDER_WRAP);
    cv::createCLAHE(options.equalize_clip, cv::Size(18, 8))->apply(padded, equalised);
    grey = equalised.colRange(tile, tile + w).clone();
  }
  // The copy rolled by half the width: its column x shows the panorama's column (x + w/2) mod w.
  cv::Mat rolled(grey.size(), grey.type());
  grey.colRange(w / 2, w).copyTo(rolled.colRange(0, w / 2));
  grey.colRange(0, w / 2).copyTo(rolled.colRange(w / 2, w));

  SphereFeatures out;
  out.width = w;
  out.height = h;
  const double max_elevation = options.max_abs_elevation_deg * M_PI / 180.0;
  const int per_copy = options.max_features / 2;
  detect_central_half(grey, 0, per_copy, options.contrast_threshold, max_elevation, &out.keypoints,
                      &out.descriptors);
  detect_central_half(rolled, w / 2, per_copy, options.contrast_threshold, max_elevation, &out.keypoints,
                      &out.descriptors);
  remove_duplicates(&out.keypoints, &out.descriptors);
  // RootSIFT: Hellinger kernel on the histograms, which matches better than L2 on raw SIFT.
  for (int r = 0; r < out.descriptors.rows; ++r) {
    cv::Mat row = out.descriptors.row(r);
    const double l1 = cv::norm(row, cv::NORM_L1);
    if (l1 > 0) row /= l1;
    cv::sqrt(row, row);
  }
  out.bearings.reserve(out.keypoints.size());
  for (const cv::KeyPoint& k : out.keypoints)
    out.bearings.push_back(equirect_to_bearing(Eigen::Vector2d(k.pt.x + 0.5, k.pt.y + 0.5), w, h));
  return out;
}

}  // namespace plenopath
