#include "processing/sampling/image_similarity.h"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "processing/util/grey_image.h"

namespace plenopath {

cv::Mat rotate_to_heading(const cv::Mat& image, double from_heading, double to_heading) {
  if (image.empty()) throw Error("rotate_to_heading: empty image");
  const int w = image.cols;
  double shift = (from_heading - to_heading) / (2.0 * M_PI) * w;              // columns
  shift -= std::floor(shift / w) * w;                                         // [0, w)
  if (std::abs(shift - std::round(shift)) < 1e-6) shift = std::round(shift);  // whole columns stay exact
  int whole = static_cast<int>(std::floor(shift));
  const double fraction = shift - whole;
  if (whole >= w) whole -= w;  // rounding can land exactly on w
  // Exact whole-column shift: result column u = input column (u + whole) mod w.
  cv::Mat shifted(image.size(), image.type());
  const int head = w - whole;  // columns [whole, w) go first
  image.colRange(whole, w).copyTo(shifted.colRange(0, head));
  if (whole > 0) image.colRange(0, whole).copyTo(shifted.colRange(head, w));
  if (fraction < 1e-9) return shifted;
  // Fractional part: blend with the next column over (wrapping).
  cv::Mat next(image.size(), image.type());
  shifted.colRange(1, w).copyTo(next.colRange(0, w - 1));
  shifted.col(0).copyTo(next.col(w - 1));
  cv::Mat out;
  cv::addWeighted(shifted, 1.0 - fraction, next, fraction, 0.0, out);
  return out;
}

namespace {
void check_pair(const cv::Mat& a, const cv::Mat& b, const char* what) {
  if (a.empty() || b.empty()) throw Error(std::string(what) + ": empty image");
  if (a.size() != b.size() || a.type() != b.type())
    throw Error(std::string(what) + ": images differ in size or type");
  if (a.depth() != CV_8U) throw Error(std::string(what) + ": 8-bit images expected");
}
}  // namespace

double psnr_db(const cv::Mat& a, const cv::Mat& b) {
  check_pair(a, b, "psnr");
  const double sum_squares = cv::norm(a, b, cv::NORM_L2SQR);
  if (sum_squares == 0.0) return std::numeric_limits<double>::infinity();
  const double mse = sum_squares / (static_cast<double>(a.total()) * a.channels());
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

double ssim(const cv::Mat& a, const cv::Mat& b) {
  check_pair(a, b, "ssim");
  auto grey = [](const cv::Mat& m) {
    cv::Mat f;
    grey_image(m, "ssim").convertTo(f, CV_64F);
    return f;
  };
  const cv::Mat x = grey(a), y = grey(b);
  const double c1 = std::pow(0.01 * 255, 2), c2 = std::pow(0.03 * 255, 2);
  auto blur = [](const cv::Mat& m) {
    cv::Mat out;
    cv::GaussianBlur(m, out, cv::Size(11, 11), 1.5, 1.5, cv::BORDER_REFLECT);
    return out;
  };
  const cv::Mat mx = blur(x), my = blur(y);
  const cv::Mat sxx = blur(x.mul(x)) - mx.mul(mx);
  const cv::Mat syy = blur(y.mul(y)) - my.mul(my);
  const cv::Mat sxy = blur(x.mul(y)) - mx.mul(my);
  cv::Mat numerator = (2 * mx.mul(my) + c1).mul(2 * sxy + c2);
  cv::Mat denominator = (mx.mul(mx) + my.mul(my) + c1).mul(sxx + syy + c2);
  cv::Mat map;
  cv::divide(numerator, denominator, map);
  return cv::mean(map)[0];
}

}  // namespace plenopath
