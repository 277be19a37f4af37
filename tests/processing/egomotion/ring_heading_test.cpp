// Ring headings against exact rotations: a pure turn of an equirectangular frame is an exact circular column
// shift, so shifting a real panorama (integer, or fractional by band-limited resampling) gives known truth.
#include "processing/egomotion/ring_heading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>

namespace plenopath {
namespace {

cv::Mat load_fixture() {
  cv::Mat img = cv::imread(std::string(PLENOPATH_TEST_DATA_DIR) + "/convention/pano_heading30.png");
  EXPECT_FALSE(img.empty());
  return img;
}

// Exact fractional circular shift of every row (Fourier shift theorem): out(x) = in(x - shift).
cv::Mat fourier_shift(const cv::Mat& bgr, double shift) {
  cv::Mat f;
  bgr.convertTo(f, CV_32F);
  std::vector<cv::Mat> channels;
  cv::split(f, channels);
  const int w = f.cols;
  for (cv::Mat& c : channels) {
    cv::Mat spec;
    cv::dft(c, spec, cv::DFT_ROWS | cv::DFT_COMPLEX_OUTPUT);
    for (int v = 0; v < spec.rows; ++v) {
      for (int k = 0; k < w; ++k) {
        const double freq = k <= w / 2 ? k : k - w;
        double phase = -2.0 * M_PI * freq * shift / w;
        if (w % 2 == 0 && k == w / 2) phase = 0;  // keep the Nyquist bin real
        cv::Vec2f& z = spec.at<cv::Vec2f>(v, k);
        const double re = z[0] * std::cos(phase) - z[1] * std::sin(phase);
        const double im = z[0] * std::sin(phase) + z[1] * std::cos(phase);
        z = cv::Vec2f(static_cast<float>(re), static_cast<float>(im));
      }
    }
    cv::dft(spec, c, cv::DFT_INVERSE | cv::DFT_ROWS | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
  }
  cv::Mat out;
  cv::merge(channels, out);
  return out;  // CV_32FC3, not requantised
}

cv::Mat to_gray32(const cv::Mat& bgr32) {
  std::vector<cv::Mat> c;
  cv::split(bgr32, c);
  return 0.114f * c[0] + 0.587f * c[1] + 0.299f * c[2];
}

TEST(RingHeading, RingIsColumnMeanWeightedBySolidAngle) {
  // A frame whose rows are constant: the ring equals the cos-weighted mean of the band's rows.
  cv::Mat img(64, 128, CV_32F);
  for (int v = 0; v < 64; ++v) img.row(v).setTo(static_cast<float>(v));
  RingOptions o;
  o.min_elevation_deg = -90;
  o.max_elevation_deg = 90;
  const std::vector<double> ring = make_ring_image(img, o);
  // Symmetric rows weighted by solid angle average to the middle value 31.5.
  ASSERT_EQ(ring.size(), 128u);
  EXPECT_NEAR(ring[0], 31.5, 1e-9);
  EXPECT_NEAR(ring[77], 31.5, 1e-9);
}

TEST(RingHeading, IntegerAndFractionalShiftsOfARealPanorama) {
  const cv::Mat img = load_fixture();
  RingOptions o;
  const std::vector<double> a = make_ring_image(img, o);
  for (double shift : {0.0, 1.0, -3.0, 0.25, 0.5, -0.73, 7.31, -20.6}) {
    const std::vector<double> b = make_ring_image(to_gray32(fourier_shift(img, shift)), o);
    const std::vector<double> window = axis_window(img.cols, o.axis_floor);
    const RingShift plain = circular_phase_correlation(a, b, 0.0, 40.0);
    const RingShift weighted = circular_phase_correlation(a, b, 0.0, 40.0, &window);
    EXPECT_NEAR(plain.shift_px, shift, 0.01) << shift;
    EXPECT_NEAR(weighted.shift_px, shift, 0.01) << shift;
    EXPECT_GT(plain.peak, 0.9);
  }
}

TEST(RingHeading, ShiftAcrossTheSeamAndSearchBound) {
  const cv::Mat img = load_fixture();
  RingOptions o;
  const std::vector<double> a = make_ring_image(img, o);
  cv::Mat rolled;
  cv::hconcat(img.colRange(img.cols - 100, img.cols), img.colRange(0, img.cols - 100), rolled);  // +100 px
  const std::vector<double> b = make_ring_image(rolled, o);
  EXPECT_NEAR(circular_phase_correlation(a, b, 0.0, 200.0).shift_px, 100.0, 1e-6);
  // Outside the search window the true peak cannot be found.
  EXPECT_GT(std::abs(circular_phase_correlation(a, b, 0.0, 50.0).shift_px - 100.0), 1.0);
  // Centred on a prediction, a narrow window finds it.
  EXPECT_NEAR(circular_phase_correlation(a, b, 97.0, 5.0).shift_px, 100.0, 1e-6);
}

TEST(RingHeading, JointSolveRecoversASequenceOfTurnsWithNoise) {
  const cv::Mat img = load_fixture();
  RingOptions o;
  std::mt19937 rng(7);
  std::normal_distribution<double> turn(0.0, 1.5), noise(0.0, 2.0);
  std::vector<double> truth;
  std::vector<std::vector<double>> rings;
  double heading = 0.0;
  for (int i = 0; i < 30; ++i) {
    if (i > 0) heading += turn(rng) * M_PI / 180.0;
    truth.push_back(heading);
    cv::Mat f = fourier_shift(img, heading * img.cols / (2 * M_PI));
    cv::Mat n(f.size(), f.type());
    cv::randn(n, 0.0, 2.0);
    rings.push_back(make_ring_image(to_gray32(f + n), o));
  }
  const RingHeadings h = solve_ring_headings(rings, o);
  double sum2 = 0.0;
  for (int i = 0; i < 30; ++i) sum2 += std::pow(h.headings[i] - truth[i], 2);
  const double rms_deg = std::sqrt(sum2 / 30) * 180 / M_PI;
  EXPECT_LT(rms_deg, 0.02);
  EXPECT_GE(h.registrations, 29 + 28 + 26 + 22 - 5);
}

}  // namespace
}  // namespace plenopath
