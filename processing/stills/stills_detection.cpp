#include "processing/stills/stills_detection.h"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <string>
#include <vector>

#include "model/option_check.h"
#include "processing/util/grey_image.h"
#include "processing/util/statistics.h"

namespace plenopath {

void StillsDetectionOptions::check() const {
  const std::string s = "StillsDetectionOptions.";
  require_option(min_frames >= 2, s + "min_frames", "must be >= 2", min_frames);
  require_option(sample_pairs >= 1, s + "sample_pairs", "must be >= 1", sample_pairs);
  require_option(work_width >= 64, s + "work_width", "must be >= 64", work_width);
  require_option(corners >= 10, s + "corners", "must be >= 10", corners);
  require_option(max_fb_error_px > 0, s + "max_fb_error_px", "must be > 0", max_fb_error_px);
  require_option(min_followed_fraction > 0 && min_followed_fraction < 1, s + "min_followed_fraction",
                 "must be in (0, 1)", min_followed_fraction);
}

namespace {

// Share of the corners of `a` that KLT follows into `b` and back to where they started.
double followed_fraction(const cv::Mat& a, const cv::Mat& b, const StillsDetectionOptions& options) {
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(a, corners, options.corners, 0.01, 6.0);
  if (corners.empty()) return 0.0;
  std::vector<cv::Point2f> forward, backward;
  std::vector<unsigned char> status_f, status_b;
  std::vector<float> error;
  const cv::Size window(21, 21);
  cv::calcOpticalFlowPyrLK(a, b, corners, forward, status_f, error, window, 3);
  cv::calcOpticalFlowPyrLK(b, a, forward, backward, status_b, error, window, 3);
  int followed = 0;
  const double max_error2 = options.max_fb_error_px * options.max_fb_error_px;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    if (!status_f[k] || !status_b[k]) continue;
    const cv::Point2f d = backward[k] - corners[k];
    followed += d.dot(d) <= max_error2;
  }
  return static_cast<double>(followed) / static_cast<double>(corners.size());
}

}  // namespace

StillsDetection detect_stills(int count, const std::function<cv::Mat(int)>& read,
                              const StillsDetectionOptions& options) {
  options.check();
  StillsDetection out;
  if (count < options.min_frames) {
    out.reason = "too few frames (" + std::to_string(count) + ") to tell stills from video";
    return out;
  }
  const int pairs = std::min(options.sample_pairs, count - 1);
  std::vector<double> fractions;
  for (int p = 0; p < pairs; ++p) {
    // Pair starts spread evenly over [0, count - 2].
    const int i = pairs == 1 ? 0 : static_cast<int>(static_cast<long long>(p) * (count - 2) / (pairs - 1));
    const cv::Mat a = equirect_at_width(grey_image_8u(read(i), "stills detection"), options.work_width);
    const cv::Mat b = equirect_at_width(grey_image_8u(read(i + 1), "stills detection"), options.work_width);
    if (a.size() != b.size()) {
      fractions.push_back(0.0);
      continue;
    }
    fractions.push_back(followed_fraction(a, b, options));
  }
  out.pairs = pairs;
  out.followed_fraction = median(fractions);
  out.stills = out.followed_fraction < options.min_followed_fraction;
  char text[200];
  std::snprintf(
      text, sizeof text,
      "KLT follows %.0f %% of the corners from a frame to the next (median of %d pairs; %s %.0f %%)",
      100.0 * out.followed_fraction, pairs, out.stills ? "stills below" : "video at or above",
      100.0 * options.min_followed_fraction);
  out.reason = text;
  return out;
}

}  // namespace plenopath
