#include "processing/cleanplate/face_blur.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>

#include "model/error.h"
#include "model/option_check.h"

namespace plenopath {

void FaceBlurOptions::check() const {
  const std::string s = "FaceBlurOptions.";
  require_option(max_elevation_deg > 0 && max_elevation_deg <= 90, s + "max_elevation_deg",
                 "must be in (0, 90]", max_elevation_deg);
  require_option(min_face_px >= 8, s + "min_face_px", "must be >= 8", min_face_px);
  require_option(scale_factor > 1.0 && scale_factor <= 2.0, s + "scale_factor", "must be in (1, 2]",
                 scale_factor);
  require_option(min_neighbours >= 0, s + "min_neighbours", "must be >= 0", min_neighbours);
  require_option(margin >= 0 && margin <= 2, s + "margin", "must be in [0, 2]", margin);
}

std::string default_face_cascade() {
  for (const char* path : {"/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml",
                           "/usr/share/opencv/haarcascades/haarcascade_frontalface_default.xml"})
    if (std::ifstream(path).good()) return path;
  throw Error(
      "face blur: no face detector found (haarcascade_frontalface_default.xml; Debian's opencv-data package "
      "installs it)");
}

FaceBlurResult blur_faces(const cv::Mat& image, const FaceBlurOptions& options) {
  options.check();
  if (image.empty() || image.type() != CV_8UC3) throw Error("face blur: the image is not a colour image");
  const std::string cascade_file =
      options.cascade_file.empty() ? default_face_cascade() : options.cascade_file;
  cv::CascadeClassifier detector;
  if (!std::ifstream(cascade_file).good() || !detector.load(cascade_file))
    throw Error(cascade_file + ": cannot read it as an OpenCV cascade classifier (face detector)");

  // The band round the horizon, padded on both sides with what lies across the seam.
  const int w = image.cols, h = image.rows;
  const int band_top =
      std::clamp(static_cast<int>(std::floor((90 - options.max_elevation_deg) / 180 * h)), 0, h - 1);
  const int band_bottom =
      std::clamp(static_cast<int>(std::ceil((90 + options.max_elevation_deg) / 180 * h)), band_top + 1, h);
  const int pad = std::min(w, std::max(64, w / 16));
  cv::Mat band, grey;
  cv::copyMakeBorder(image.rowRange(band_top, band_bottom), band, 0, 0, pad, pad, cv::BORDER_WRAP);
  cv::cvtColor(band, grey, cv::COLOR_BGR2GRAY);
  cv::equalizeHist(grey, grey);
  std::vector<cv::Rect> found;
  detector.detectMultiScale(grey, found, options.scale_factor, options.min_neighbours, 0,
                            cv::Size(options.min_face_px, options.min_face_px));

  FaceBlurResult out;
  out.image = image.clone();
  cv::Mat mask = cv::Mat::zeros(band.size(), CV_8U);
  for (const cv::Rect& f : found) {
    // A face wholly in the padding is the same face as its copy inside: kept once, by its left edge.
    if (f.x + f.width <= pad || f.x >= pad + w) continue;
    if (f.x < pad && f.x + w >= pad && f.x + w < pad + w) {
      bool twin = false;
      for (const cv::Rect& g : found)
        twin = twin || (std::abs(g.x - (f.x + w)) < f.width / 3 && std::abs(g.y - f.y) < f.height / 3);
      if (twin) continue;
    }
    out.faces.push_back(cv::Rect((f.x - pad + w) % w, f.y + band_top, f.width, f.height));
    const cv::Point centre(f.x + f.width / 2, f.y + f.height / 2);
    const cv::Size axes(static_cast<int>(f.width * (0.5 + options.margin)),
                        static_cast<int>(f.height * (0.6 + options.margin)));
    cv::ellipse(mask, centre, axes, 0, 0, 360, cv::Scalar(255), cv::FILLED);
  }
  if (out.faces.empty()) return out;

  // One strong blur for all faces (sized to the largest), blended in through a softened mask, and folded
  // back across the seam.
  int largest = 0;
  for (const cv::Rect& f : out.faces) largest = std::max(largest, f.height);
  cv::Mat blurred, alpha;
  cv::GaussianBlur(band, blurred, cv::Size(0, 0), std::max(2.0, largest / 5.0));
  mask.convertTo(alpha, CV_32F, 1.0 / 255);
  cv::GaussianBlur(alpha, alpha, cv::Size(0, 0), std::max(1.0, largest / 12.0));
  // A column of the panorama may appear twice in the padded band: the larger weight wins.
  cv::Mat weight = cv::Mat::zeros(band.rows, w, CV_32F);
  cv::Mat source = cv::Mat::zeros(band.rows, w, CV_8UC3);
  for (int y = 0; y < band.rows; ++y)
    for (int x = 0; x < band.cols; ++x) {
      const float a = std::min(1.0f, 1.5f * alpha.at<float>(y, x));
      const int c = (x - pad + 2 * w) % w;
      if (a <= weight.at<float>(y, c)) continue;
      weight.at<float>(y, c) = a;
      source.at<cv::Vec3b>(y, c) = blurred.at<cv::Vec3b>(y, x);
    }
  for (int y = 0; y < band.rows; ++y)
    for (int c = 0; c < w; ++c) {
      const float a = weight.at<float>(y, c);
      if (a <= 0.004f) continue;
      cv::Vec3b& target = out.image.at<cv::Vec3b>(y + band_top, c);
      const cv::Vec3b& b = source.at<cv::Vec3b>(y, c);
      for (int ch = 0; ch < 3; ++ch)
        target[ch] = cv::saturate_cast<std::uint8_t>(a * b[ch] + (1 - a) * target[ch]);
    }
  return out;
}

}  // namespace plenopath
