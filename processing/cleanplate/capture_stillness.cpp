#include "processing/cleanplate/capture_stillness.h"

#include <algorithm>
#include <array>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/cleanplate/colour_difference.h"

namespace plenopath {

void CaptureStillnessOptions::check() const {
  const std::string s = "CaptureStillnessOptions.";
  require_option(frames >= 8 && frames <= 255, s + "frames", "must be in [8, 255]", frames);
  require_option(width >= 32 && width % 2 == 0, s + "width", "must be even and >= 32", width);
  require_option(tolerance >= 1 && tolerance <= 128, s + "tolerance", "must be in [1, 128]", tolerance);
}

namespace {

cv::Mat normalised(const cv::Mat& image, int width) {
  if (image.empty() || image.type() != CV_8UC3)
    throw Error("capture stillness: a frame is not a colour image");
  cv::Mat small;
  const int height = std::max(1, width * image.rows / image.cols);
  cv::resize(image, small, {width, height}, 0, 0, cv::INTER_AREA);
  const cv::Scalar mean = cv::mean(small);
  const double brightness = (mean[0] + mean[1] + mean[2]) / 3;
  if (brightness > 1.0) small.convertTo(small, CV_8UC3, 128.0 / brightness);
  return small;
}

}  // namespace

cv::Mat at_stillness_scale(const cv::Mat& image, const CaptureStillness& stillness) {
  return normalised(image, stillness.median.cols);
}

cv::Mat stays_in_place(const cv::Mat& image, const CaptureStillness& stillness, double min_share) {
  const cv::Mat small = at_stillness_scale(image, stillness);
  cv::Mat out(small.size(), CV_8U);
  for (int v = 0; v < small.rows; ++v)
    for (int u = 0; u < small.cols; ++u)
      out.at<std::uint8_t>(v, u) =
          max_channel_difference(small.at<cv::Vec3b>(v, u), stillness.median.at<cv::Vec3b>(v, u)) <=
                      stillness.tolerance &&
                  stillness.share.at<std::uint8_t>(v, u) >= min_share * 255
              ? 255
              : 0;
  return out;
}

CaptureStillness capture_stillness(const std::function<cv::Mat(int)>& frame, int frame_count,
                                   const CaptureStillnessOptions& options, Progress& progress) {
  options.check();
  CaptureStillness out;
  const int count = std::min(frame_count, options.frames);
  if (count < 8) return out;
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    progress.checkpoint(double(i) / count, "looking for what stays in place");
    const int k = static_cast<int>((static_cast<long>(i) * (frame_count - 1)) / std::max(1, count - 1));
    frames.push_back(normalised(frame(k), options.width));
    if (frames.back().size() != frames.front().size())
      throw Error("capture stillness: frame " + std::to_string(k) + " differs in size from frame 0");
  }
  const int w = frames.front().cols, h = frames.front().rows, n = static_cast<int>(frames.size());
  out.median = cv::Mat(h, w, CV_8UC3);
  out.share = cv::Mat(h, w, CV_8U);
  std::vector<std::uint8_t> samples(static_cast<std::size_t>(n));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      cv::Vec3b median;
      for (int ch = 0; ch < 3; ++ch) {
        for (int i = 0; i < n; ++i) samples[static_cast<std::size_t>(i)] = frames[i].at<cv::Vec3b>(v, u)[ch];
        std::nth_element(samples.begin(), samples.begin() + n / 2, samples.end());
        median[ch] = samples[static_cast<std::size_t>(n / 2)];
      }
      int within = 0;
      for (const cv::Mat& f : frames) {
        within += max_channel_difference(f.at<cv::Vec3b>(v, u), median) <= options.tolerance;
      }
      out.median.at<cv::Vec3b>(v, u) = median;
      out.share.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>((255 * within) / n);
    }
  out.frames = n;
  out.tolerance = options.tolerance;
  progress.report(1.0);
  return out;
}

}  // namespace plenopath
