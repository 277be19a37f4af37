#include "rig/equirect_sampling.h"

#include <cmath>

#include "model/error.h"

namespace plenopath {
namespace {

template <typename T>
void sample_typed(const cv::Mat& image, double x, double y, float* out) {
  const int w = image.cols, h = image.rows, c = image.channels();
  const double fx = x - 0.5, fy = y - 0.5;  // to pixel-centre coordinates
  const double x0f = std::floor(fx), y0f = std::floor(fy);
  const double tx = fx - x0f, ty = fy - y0f;
  int x0 = static_cast<int>(x0f) % w;
  if (x0 < 0) x0 += w;
  const int x1 = (x0 + 1) % w;
  const int y0 = std::min(std::max(static_cast<int>(y0f), 0), h - 1);
  const int y1 = std::min(std::max(static_cast<int>(y0f) + 1, 0), h - 1);
  const T* r0 = image.ptr<T>(y0);
  const T* r1 = image.ptr<T>(y1);
  for (int k = 0; k < c; ++k) {
    const double top = (1 - tx) * r0[x0 * c + k] + tx * r0[x1 * c + k];
    const double bottom = (1 - tx) * r1[x0 * c + k] + tx * r1[x1 * c + k];
    out[k] = static_cast<float>((1 - ty) * top + ty * bottom);
  }
}

}  // namespace

void sample_equirect_bilinear(const cv::Mat& image, double x, double y, float* out) {
  if (image.empty()) throw Error("sample_equirect_bilinear: empty image");
  if (!std::isfinite(x) || !std::isfinite(y)) throw Error("sample_equirect_bilinear: non-finite coordinates");
  switch (image.depth()) {
    case CV_8U:
      sample_typed<unsigned char>(image, x, y, out);
      break;
    case CV_16U:
      sample_typed<unsigned short>(image, x, y, out);
      break;
    case CV_32F:
      sample_typed<float>(image, x, y, out);
      break;
    default:
      throw Error("sample_equirect_bilinear: unsupported image depth");
  }
}

cv::Vec3f sample_equirect_bilinear_bgr(const cv::Mat& image, double x, double y) {
  float v[4] = {0, 0, 0, 0};
  sample_equirect_bilinear(image, x, y, v);
  return {v[0], v[1], v[2]};
}

}  // namespace plenopath
