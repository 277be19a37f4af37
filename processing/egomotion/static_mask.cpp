#include "processing/egomotion/static_mask.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/util/grey_image.h"

namespace plenopath {

void StaticMaskOptions::check() const {
  const std::string s = "StaticMaskOptions.";
  require_option(frames >= 0, s + "frames", "must be >= 0", frames);
  require_option(min_frames >= 2, s + "min_frames", "must be >= 2", min_frames);
  require_option(frames == 0 || min_frames <= frames, s + "min_frames", "must be <= frames", min_frames);
  require_option(plateau_frames >= 1 && plateau_frames < min_frames, s + "plateau_frames",
                 "must be in [1, min_frames)", plateau_frames);
  require_option(plateau_growth >= 0 && plateau_growth < 1, s + "plateau_growth", "must be in [0, 1)",
                 plateau_growth);
  require_option(min_decided_fraction >= 0 && min_decided_fraction < 1, s + "min_decided_fraction",
                 "must be in [0, 1)", min_decided_fraction);
  require_option(width >= 32 && width % 2 == 0, s + "width", "must be even and >= 32", width);
  require_option(change_threshold > 0, s + "change_threshold", "must be > 0", change_threshold);
  require_option(texture_threshold >= 0, s + "texture_threshold", "must be >= 0", texture_threshold);
  require_option(min_textured_pixels >= 0, s + "min_textured_pixels", "must be >= 0", min_textured_pixels);
  require_option(margin_deg >= 0 && margin_deg <= 30, s + "margin_deg", "must be in [0, 30]", margin_deg);
  require_option(min_region_fraction >= 0 && min_region_fraction < 1, s + "min_region_fraction",
                 "must be in [0, 1)", min_region_fraction);
  require_option(min_texture_ratio >= 0 && min_texture_ratio < 1, s + "min_texture_ratio",
                 "must be in [0, 1)", min_texture_ratio);
  require_option(max_fraction > 0 && max_fraction <= 1, s + "max_fraction", "must be in (0, 1]",
                 max_fraction);
}

StaticMaskEstimator::StaticMaskEstimator(const StaticMaskOptions& options) : options_(options) {
  options.check();
}

void StaticMaskEstimator::add(const cv::Mat& frame) {
  cv::Mat small;
  cv::resize(grey_image_8u(frame, "static mask"), small, cv::Size(options_.width, options_.width / 2), 0, 0,
             cv::INTER_AREA);
  small.convertTo(small, CV_32F);
  cv::GaussianBlur(small, small, cv::Size(3, 3), 0.8, 0.8, cv::BORDER_REPLICATE);
  const double mean = cv::mean(small)[0];
  if (mean > 1.0) small *= 128.0 / mean;  // exposure
  // A frame with hardly any structure (a lens cap, a blank frame, a wall passed at arm's length) changes
  // nearly every pixel at once: counted, it would end the wait early and leave unchanged whatever of the
  // scene matched its flat grey. It says nothing about what moves with the camera; it is skipped.
  cv::Mat gx, gy, magnitude;
  cv::Sobel(small, gx, CV_32F, 1, 0, 3, 1.0 / 8);
  cv::Sobel(small, gy, CV_32F, 0, 1, 3, 1.0 / 8);
  cv::magnitude(gx, gy, magnitude);
  const double texture = cv::mean(magnitude)[0];
  if (frames_ > 0 && texture < options_.min_texture_ratio * first_texture_) {
    ++skipped_;
    return;
  }
  if (frames_ == 0) {
    first_texture_ = texture;
    first_ = small.clone();
    max_change_ = cv::Mat::zeros(small.size(), CV_32F);
    sum_ = cv::Mat::zeros(small.size(), CV_32F);
  }
  if (small.size() != first_.size()) throw Error("static mask: frame size changed within the capture");
  cv::Mat change;
  cv::absdiff(small, first_, change);
  max_change_ = cv::max(max_change_, change);
  sum_ += small;
  ++frames_;
  history_.push_back(changed_fraction());
}

double StaticMaskEstimator::changed_fraction() const {
  if (frames_ == 0) return 0.0;
  return cv::countNonZero(max_change_ > options_.change_threshold) / static_cast<double>(max_change_.total());
}

bool StaticMaskEstimator::ready() const {
  if (options_.frames == 0 || frames_ + skipped_ >= options_.frames) return true;
  if (frames_ < options_.min_frames) return false;
  const double now = history_.back();
  const double before = history_[history_.size() - 1 - static_cast<std::size_t>(options_.plateau_frames)];
  return now >= options_.min_decided_fraction && now - before < options_.plateau_growth;
}

cv::Mat StaticMaskEstimator::mask(cv::Size size) const {
  if (frames_ < options_.min_frames || changed_fraction() < options_.min_decided_fraction) return {};
  const int w = max_change_.cols, h = max_change_.rows;
  const cv::Mat is_static = max_change_ <= options_.change_threshold;
  cv::Mat mean = sum_ / frames_, gx, gy, magnitude;
  cv::Sobel(mean, gx, CV_32F, 1, 0, 3, 1.0 / 8);
  cv::Sobel(mean, gy, CV_32F, 0, 1, 3, 1.0 / 8);
  cv::magnitude(gx, gy, magnitude);
  const cv::Mat edge = is_static & (magnitude > options_.texture_threshold);
  // Static regions, the seam joined (the operator stands at azimuth 180 deg, on both image edges).
  cv::Mat labels;
  const int count = cv::connectedComponents(is_static, labels, 8, CV_32S);
  std::vector<int> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (int v = 0; v < h; ++v)
    for (int dv = -1; dv <= 1; ++dv) {
      const int v2 = v + dv;
      if (v2 < 0 || v2 >= h) continue;
      const int a = labels.at<int>(v, 0), b = labels.at<int>(v2, w - 1);
      if (a > 0 && b > 0) parent[find(a)] = find(b);
    }
  std::vector<int> edges(count, 0), area(count, 0);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = labels.at<int>(v, u);
      if (l == 0) continue;
      ++area[find(l)];
      if (edge.at<uchar>(v, u)) ++edges[find(l)];
    }
  // A patch of faint scene texture the camera has not yet moved far enough to change is small; the rig and
  // the person pushing it are not.
  const int min_area = static_cast<int>(std::ceil(options_.min_region_fraction * w * h));
  cv::Mat masked(h, w, CV_8U, cv::Scalar(0));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = labels.at<int>(v, u);
      if (l > 0 && edges[find(l)] >= options_.min_textured_pixels && area[find(l)] >= min_area)
        masked.at<uchar>(v, u) = 255;
    }
  // Grow by the margin, the seam wrapped.
  const int margin = static_cast<int>(std::ceil(options_.margin_deg / (360.0 / w)));
  if (margin > 0) {
    cv::Mat padded;
    cv::copyMakeBorder(masked, padded, margin, margin, margin, margin, cv::BORDER_WRAP);
    cv::dilate(padded, padded,
               cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * margin + 1, 2 * margin + 1)));
    masked = padded(cv::Rect(margin, margin, w, h)).clone();
  }
  const double share = cv::countNonZero(masked) / static_cast<double>(masked.total());
  if (share == 0.0 || share > options_.max_fraction) return {};
  cv::Mat usable = 255 - masked, out;
  cv::resize(usable, out, size, 0, 0, cv::INTER_NEAREST);
  return out;
}

cv::Mat combine_masks(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty()) return b.clone();
  if (b.empty()) return a.clone();
  if (a.size() != b.size()) throw Error("masks differ in size");
  cv::Mat out;
  cv::bitwise_and(a, b, out);
  return out;
}

}  // namespace plenopath
