#include "processing/cleanplate/nadir_patch.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>
#include <vector>

#include "model/error.h"
#include "model/option_check.h"

namespace plenopath {

void NadirPatchOptions::check() const {
  const std::string s = "NadirPatchOptions.";
  require_option(min_image_radius_deg > 0, s + "min_image_radius_deg", "must be > 0", min_image_radius_deg);
  require_option(max_image_radius_deg >= min_image_radius_deg && max_image_radius_deg <= 80,
                 s + "max_image_radius_deg", "must be in [min_image_radius_deg, 80]", max_image_radius_deg);
  require_option(blur_width >= 32, s + "blur_width", "must be >= 32", blur_width);
  if (kind == NadirPatch::kImage && (image.empty() || (image.type() != CV_8UC3 && image.type() != CV_8UC4)))
    throw Error(
        "NadirPatchOptions.image: a nadir image patch needs a picture (choose one in the tour settings, or "
        "export --nadir FILE)");
}

cv::Mat read_nadir_image(const std::string& file) {
  cv::Mat image = cv::imread(file, cv::IMREAD_UNCHANGED);
  if (image.empty()) throw Error(file + ": cannot read it as an image (the nadir patch)");
  if (image.depth() == CV_16U) image.convertTo(image, CV_8U, 1.0 / 257);
  if (image.depth() != CV_8U) throw Error(file + ": the nadir patch must be an 8- or 16-bit image");
  if (image.channels() == 1) cv::cvtColor(image, image, cv::COLOR_GRAY2BGR);
  if (image.channels() == 2)
    throw Error(file + ": the nadir patch must be grey, colour or colour with alpha");
  return image;
}

namespace {

// Degrees from the nadir of row v's centre.
double from_nadir_deg(int v, int h) { return 180.0 - (v + 0.5) * 180.0 / h; }

cv::Mat blurred_fill(const cv::Mat& image, const cv::Mat& region, int blur_width) {
  const int w = image.cols, h = image.rows;
  const int small_w = std::min(w, blur_width), small_h = std::max(1, small_w * h / w), pad = small_w / 8;
  cv::Mat small, small_region;
  cv::resize(image, small, {small_w, small_h}, 0, 0, cv::INTER_AREA);
  cv::resize(region, small_region, {small_w, small_h}, 0, 0, cv::INTER_NEAREST);
  cv::dilate(small_region, small_region, cv::Mat());
  cv::Mat padded, padded_region, filled;
  cv::copyMakeBorder(small, padded, 0, 0, pad, pad, cv::BORDER_WRAP);
  cv::copyMakeBorder(small_region, padded_region, 0, 0, pad, pad, cv::BORDER_WRAP);
  // A region that reaches the nadir row all round has nothing below it: the bottom row is part of it.
  cv::inpaint(padded, padded_region, filled, 5, cv::INPAINT_TELEA);
  cv::GaussianBlur(filled, filled, cv::Size(0, 0), std::max(1.0, small_w / 256.0));
  cv::Mat out;
  cv::resize(filled(cv::Rect(pad, 0, small_w, small_h)), out, {w, h}, 0, 0, cv::INTER_LINEAR);
  return out;
}

// `top` over `bottom` where `alpha` (CV_32F in [0, 1]) says.
void blend_into(cv::Mat& bottom, const cv::Mat& top, const cv::Mat& alpha) {
  for (int v = 0; v < bottom.rows; ++v)
    for (int u = 0; u < bottom.cols; ++u) {
      const float a = alpha.at<float>(v, u);
      if (a <= 0) continue;
      cv::Vec3b& b = bottom.at<cv::Vec3b>(v, u);
      const cv::Vec3b& t = top.at<cv::Vec3b>(v, u);
      for (int ch = 0; ch < 3; ++ch) b[ch] = cv::saturate_cast<std::uint8_t>(a * t[ch] + (1 - a) * b[ch]);
    }
}

}  // namespace

double nadir_disc_radius_deg(const cv::Mat& region, const NadirPatchOptions& options) {
  std::vector<double> angles;
  for (int v = 0; v < region.rows; ++v) {
    const double angle = from_nadir_deg(v, region.rows);
    if (angle > options.max_image_radius_deg) continue;
    const int n = cv::countNonZero(region.row(v));
    angles.insert(angles.end(), static_cast<std::size_t>(n), angle);
  }
  if (angles.empty()) return 0.0;
  auto at = angles.begin() + static_cast<std::ptrdiff_t>(0.98 * (angles.size() - 1));
  std::nth_element(angles.begin(), at, angles.end());
  return std::clamp(*at + 1.0, options.min_image_radius_deg, options.max_image_radius_deg);
}

cv::Mat apply_nadir_patch(const cv::Mat& image, const cv::Mat& region, const NadirPatchOptions& options) {
  options.check();
  if (image.empty() || image.type() != CV_8UC3) throw Error("nadir patch: the image is not a colour image");
  if (!region.empty() && (region.type() != CV_8U || region.size() != image.size()))
    throw Error("nadir patch: the region is not a grey image of the image's size");
  if (options.kind == NadirPatch::kNone || region.empty() || cv::countNonZero(region) == 0)
    return image.clone();
  const int w = image.cols, h = image.rows;
  const cv::Mat inside = region != 0;
  // A soft edge a few pixels wide, so that the patch does not show as a cut-out.
  const int feather = std::max(1, w / 512);
  cv::Mat alpha;
  cv::dilate(inside, alpha, cv::Mat(), cv::Point(-1, -1), feather);
  alpha.convertTo(alpha, CV_32F, 1.0 / 255);
  cv::GaussianBlur(alpha, alpha, cv::Size(0, 0), feather);
  cv::Mat hard;
  inside.convertTo(hard, CV_32F, 1.0 / 255);
  alpha = cv::max(alpha, hard);
  cv::Mat out = image.clone();
  blend_into(out, blurred_fill(image, inside, options.blur_width), alpha);
  if (options.kind != NadirPatch::kImage) return out;

  // The author's image on a disc round the nadir: gnomonic, so that it looks flat on the floor; its top
  // towards the panorama's forward direction (the centre column).
  const double radius = nadir_disc_radius_deg(inside, options) * M_PI / 180;
  if (radius <= 0) return out;  // nothing left near the nadir: no disc
  const cv::Mat& logo = options.image;
  cv::Mat map_x(h, w, CV_32F, cv::Scalar(-1)), map_y(h, w, CV_32F, cv::Scalar(-1));
  cv::Mat disc = cv::Mat::zeros(h, w, CV_32F);
  const double tan_radius = std::tan(radius);
  for (int v = 0; v < h; ++v) {
    const double angle = from_nadir_deg(v, h) * M_PI / 180;
    if (angle > radius + M_PI / h) continue;
    const double r = std::tan(angle) / tan_radius;
    // Antialiased rim: one row's worth of angle.
    const float rim = static_cast<float>(std::clamp((radius - angle) / (M_PI / h) + 0.5, 0.0, 1.0));
    for (int u = 0; u < w; ++u) {
      const double azimuth = ((u + 0.5) / w * 360.0 - 180.0) * M_PI / 180;
      const double x = r * std::sin(azimuth), y = -r * std::cos(azimuth);
      map_x.at<float>(v, u) = static_cast<float>((x + 1) / 2 * logo.cols - 0.5);
      map_y.at<float>(v, u) = static_cast<float>((y + 1) / 2 * logo.rows - 0.5);
      disc.at<float>(v, u) = rim;
    }
  }
  cv::Mat drawn;
  cv::remap(logo, drawn, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  if (drawn.channels() == 4) {
    std::vector<cv::Mat> channels;
    cv::split(drawn, channels);
    cv::Mat logo_alpha;
    channels[3].convertTo(logo_alpha, CV_32F, 1.0 / 255);
    disc = disc.mul(logo_alpha);
    channels.pop_back();
    cv::merge(channels, drawn);
  }
  blend_into(out, drawn, disc);
  return out;
}

}  // namespace plenopath
