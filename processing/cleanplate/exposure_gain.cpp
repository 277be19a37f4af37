#include "processing/cleanplate/exposure_gain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace plenopath {

cv::Scalar exposure_gain(const cv::Mat& key, const cv::Mat& image, const cv::Mat& valid,
                         const cv::Mat& where) {
  struct Pair {
    cv::Vec3b key, image;
    float log_ratio;  // of the brightness (sum of the channels)
  };
  std::vector<Pair> pairs;
  for (int v = 0; v < key.rows; v += 3)
    for (int u = 0; u < key.cols; u += 3) {
      if (!valid.at<std::uint8_t>(v, u) || (!where.empty() && !where.at<std::uint8_t>(v, u))) continue;
      const cv::Vec3b& k = key.at<cv::Vec3b>(v, u);
      const cv::Vec3b& n = image.at<cv::Vec3b>(v, u);
      bool usable = true;
      for (int ch = 0; ch < 3; ++ch)
        usable = usable && k[ch] > 24 && k[ch] < 240 && n[ch] > 24 && n[ch] < 240;
      if (usable) pairs.push_back({k, n, std::log(float(k[0] + k[1] + k[2]) / float(n[0] + n[1] + n[2]))});
    }
  if (pairs.size() < 200) return cv::Scalar::all(1);
  // The mode of the log brightness ratio over [log 0.5, log 2): bins of 0.5 %, counted over five bins.
  constexpr float kLow = -0.6931472f, kBin = 0.005f;
  constexpr int kBins = 278;
  std::array<int, kBins> histogram{};
  for (const Pair& p : pairs) {
    const int bin = static_cast<int>(std::floor((p.log_ratio - kLow) / kBin));
    if (bin >= 0 && bin < kBins) ++histogram[static_cast<std::size_t>(bin)];
  }
  int best_bin = 0, best_count = -1;
  for (int b = 0; b < kBins; ++b) {
    int count = 0;
    for (int d = std::max(0, b - 2); d <= std::min(kBins - 1, b + 2); ++d)
      count += histogram[static_cast<std::size_t>(d)];
    if (count > best_count) best_count = count, best_bin = b;
  }
  const float mode = kLow + (best_bin + 0.5f) * kBin;
  std::array<std::vector<float>, 3> ratios;
  for (const Pair& p : pairs) {
    if (std::abs(p.log_ratio - mode) > 0.04f) continue;
    for (int ch = 0; ch < 3; ++ch) ratios[ch].push_back(float(p.key[ch]) / float(p.image[ch]));
  }
  if (ratios[0].size() < 100) return cv::Scalar::all(1);
  cv::Scalar gain;
  bool changes = false;
  for (int ch = 0; ch < 3; ++ch) {
    auto mid = ratios[ch].begin() + ratios[ch].size() / 2;
    std::nth_element(ratios[ch].begin(), mid, ratios[ch].end());
    gain[ch] = std::clamp(double(*mid), 0.5, 2.0);
    changes = changes || std::abs(gain[ch] - 1.0) > 0.01;
  }
  return changes ? gain : cv::Scalar::all(1);
}

}  // namespace plenopath
