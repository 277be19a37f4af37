#include "processing/egomotion/ring_heading.h"

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <complex>
#include <deque>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/util/grey_image.h"
#include "rig/spherical.h"

namespace plenopath {
namespace {
constexpr double kPi = M_PI;
using Complex = std::complex<double>;

// Full complex spectrum of a real sequence, exact length (cv::dft handles any length).
std::vector<Complex> spectrum(const std::vector<double>& x) {
  cv::Mat in(1, static_cast<int>(x.size()), CV_64F, const_cast<double*>(x.data()));
  cv::Mat out;
  cv::dft(in, out, cv::DFT_COMPLEX_OUTPUT);
  std::vector<Complex> s(x.size());
  for (size_t k = 0; k < x.size(); ++k) {
    const cv::Vec2d v = out.at<cv::Vec2d>(0, static_cast<int>(k));
    s[k] = {v[0], v[1]};
  }
  return s;
}

// Signed frequency of DFT bin k for length n.
double signed_frequency(int k, int n) { return k <= n / 2 ? k : k - n; }

struct ShiftEstimate {
  double shift = 0.0;
  double peak = 0.0;
};

// The whitened, tapered cross spectrum and its band-limited correlation r(d) = sum T_k Re(C_k e^{i w_k d}).
ShiftEstimate correlate(const std::vector<double>& a, const std::vector<double>& b, double center,
                        double max_shift, double max_frequency_fraction) {
  const int n = static_cast<int>(a.size());
  const std::vector<Complex> sa = spectrum(a), sb = spectrum(b);
  std::vector<Complex> cross(n, 0.0);
  const double cutoff = std::max(2.0, max_frequency_fraction * n / 2.0);
  double taper_sum = 0.0;
  double max_power = 0.0;
  for (int k = 0; k < n; ++k) max_power = std::max(max_power, std::abs(sa[k]) * std::abs(sb[k]));
  const double eps = 1e-9 * max_power + 1e-300;
  for (int k = 1; k < n; ++k) {
    const double f = std::abs(signed_frequency(k, n));
    if (n % 2 == 0 && k == n / 2) continue;  // the Nyquist bin has no sign
    if (f >= cutoff) continue;
    const double taper = 0.5 * (1.0 + std::cos(kPi * f / cutoff));
    const Complex c = std::conj(sa[k]) * sb[k];
    cross[k] = taper * c / (std::abs(c) + eps);
    taper_sum += taper;
  }
  if (taper_sum <= 0.0) return {};
  for (auto& c : cross) c /= taper_sum;

  auto value = [&](double d, double* first, double* second) {
    double v = 0.0, d1 = 0.0, d2 = 0.0;
    for (int k = 1; k < n; ++k) {
      if (cross[k] == 0.0) continue;
      const double w = 2.0 * kPi * signed_frequency(k, n) / n;
      const Complex e = cross[k] * std::polar(1.0, w * d);
      v += e.real();
      d1 -= w * e.imag();
      d2 -= w * w * e.real();
    }
    if (first) *first = d1;
    if (second) *second = d2;
    return v;
  };

  // Integer peak within the search window (inverse DFT gives r at every integer shift).
  cv::Mat spec(1, n, CV_64FC2);
  for (int k = 0; k < n; ++k) spec.at<cv::Vec2d>(0, k) = {cross[k].real(), cross[k].imag()};
  cv::Mat corr;
  cv::dft(spec, corr, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT);
  const int lo = static_cast<int>(std::ceil(center - max_shift));
  const int hi = static_cast<int>(std::floor(center + max_shift));
  double best = -1e300;
  int best_d = 0;
  for (int d = lo; d <= hi; ++d) {
    const int k = ((d % n) + n) % n;
    const double v = corr.at<double>(0, k);
    if (v > best) {
      best = v;
      best_d = d;
    }
  }
  // Newton on the exact interpolation, kept within one pixel of the integer peak.
  double d = best_d;
  for (int it = 0; it < 12; ++it) {
    double g = 0.0, h = 0.0;
    value(d, &g, &h);
    double step;
    if (h < 0.0) {
      step = -g / h;
    } else {
      step = g > 0 ? 0.25 : -0.25;
    }
    step = std::clamp(step, -0.5, 0.5);
    d = std::clamp(d + step, best_d - 1.0, best_d + 1.0);
    if (std::abs(step) < 1e-7) break;
  }
  return {d, value(d, nullptr, nullptr)};
}

double weighted_mean(const std::vector<double>& x, const std::vector<double>& w) {
  double s = 0, sw = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    s += x[i] * w[i];
    sw += w[i];
  }
  return sw > 0 ? s / sw : 0.0;
}

std::vector<double> apply_window(const std::vector<double>& x, const std::vector<double>& w) {
  const double m = weighted_mean(x, w);
  std::vector<double> y(x.size());
  for (size_t i = 0; i < x.size(); ++i) y[i] = (x[i] - m) * w[i];
  return y;
}
}  // namespace

void RingOptions::check() const {
  const std::string s = "RingOptions.";
  require_option(min_elevation_deg >= -90 && min_elevation_deg < max_elevation_deg, s + "min_elevation_deg",
                 "must be in [-90, max_elevation_deg)", min_elevation_deg);
  require_option(max_elevation_deg <= 90, s + "max_elevation_deg", "must be <= 90", max_elevation_deg);
  require_option(axis_floor >= 0.0 && axis_floor <= 1.0, s + "axis_floor", "must be in [0, 1]", axis_floor);
  require_option(max_frequency_fraction > 0.0 && max_frequency_fraction <= 1.0, s + "max_frequency_fraction",
                 "must be in (0, 1]", max_frequency_fraction);
  require_option(max_turn_deg_per_frame > 0.0 && max_turn_deg_per_frame < 180.0, s + "max_turn_deg_per_frame",
                 "must be in (0, 180)", max_turn_deg_per_frame);
  require_option(!frame_offsets.empty() && frame_offsets.front() == 1, s + "frame_offsets",
                 "must start with 1",
                 frame_offsets.empty() ? std::string("none") : std::to_string(frame_offsets.front()));
  for (int f : frame_offsets) require_option(f >= 1, s + "frame_offsets", "must be positive", f);
  require_option(min_peak >= 0.0 && min_peak < 1.0, s + "min_peak", "must be in [0, 1)", min_peak);
}

namespace {
// Per image row, the solid angle it subtends inside the latitude band (the exact angle between its edges,
// weighted by cos(elevation): sin(top) - sin(bottom)); 0 for rows outside the band.
std::vector<double> band_row_weights(int height, const RingOptions& options) {
  std::vector<double> weights(height, 0.0);
  const double lo = options.min_elevation_deg * kPi / 180.0, hi = options.max_elevation_deg * kPi / 180.0;
  for (int v = 0; v < height; ++v) {
    const double top = std::min(hi, kPi / 2 - static_cast<double>(v) / height * kPi);
    const double bottom = std::max(lo, kPi / 2 - static_cast<double>(v + 1) / height * kPi);
    if (top > bottom) weights[v] = std::sin(top) - std::sin(bottom);
  }
  return weights;
}
}  // namespace

std::vector<double> make_ring_image(const cv::Mat& equirect, const RingOptions& options,
                                    const cv::Mat& mask) {
  if (mask.empty()) return make_ring_image(equirect, options);
  cv::Mat gray32;
  grey_image(equirect, "ring image").convertTo(gray32, CV_32F);
  if (mask.type() != CV_8U || mask.size() != gray32.size())
    throw Error("ring image: the mask must be 8-bit and the frame's size");
  const int w = gray32.cols, h = gray32.rows;
  const std::vector<double> row_weight = band_row_weights(h, options);
  std::vector<double> ring(w, 0.0), total(w, 0.0);
  for (int v = 0; v < h; ++v) {
    const double weight = row_weight[v];
    if (weight <= 0.0) continue;
    const float* row = gray32.ptr<float>(v);
    const uchar* m = mask.ptr<uchar>(v);
    for (int u = 0; u < w; ++u)
      if (m[u]) {
        ring[u] += weight * row[u];
        total[u] += weight;
      }
  }
  double sum = 0.0, weight_sum = 0.0;
  for (int u = 0; u < w; ++u) {
    sum += ring[u];
    weight_sum += total[u];
  }
  if (weight_sum <= 0.0) throw Error("ring image: the mask leaves nothing of the latitude band");
  const double mean = sum / weight_sum;
  for (int u = 0; u < w; ++u) ring[u] = total[u] > 0 ? ring[u] / total[u] : mean;
  return ring;
}

std::vector<double> ring_column_weights(const cv::Mat& mask, const RingOptions& options) {
  if (mask.empty() || mask.type() != CV_8U) throw Error("ring column weights: the mask must be 8-bit");
  const int w = mask.cols, h = mask.rows;
  const std::vector<double> row_weight = band_row_weights(h, options);
  std::vector<double> usable(w, 0.0);
  double full = 0.0;
  for (int v = 0; v < h; ++v) {
    const double weight = row_weight[v];
    if (weight <= 0.0) continue;
    full += weight;
    const uchar* m = mask.ptr<uchar>(v);
    for (int u = 0; u < w; ++u)
      if (m[u]) usable[u] += weight;
  }
  for (double& x : usable) x = full > 0 ? x / full : 0.0;
  return usable;
}

std::vector<double> make_ring_image(const cv::Mat& equirect, const RingOptions& options) {
  cv::Mat gray32;
  grey_image(equirect, "ring image").convertTo(gray32, CV_32F);
  const int w = gray32.cols, h = gray32.rows;
  const std::vector<double> row_weight = band_row_weights(h, options);
  std::vector<double> ring(w, 0.0);
  double total = 0.0;
  for (int v = 0; v < h; ++v) {
    const double weight = row_weight[v];
    if (weight <= 0.0) continue;
    const float* row = gray32.ptr<float>(v);
    for (int u = 0; u < w; ++u) ring[u] += weight * row[u];
    total += weight;
  }
  if (total <= 0.0) throw Error("ring image: the latitude band covers no row");
  for (double& r : ring) r /= total;
  return ring;
}

std::vector<double> axis_window(int width, double axis_floor, double shift_px) {
  std::vector<double> w(width);
  for (int u = 0; u < width; ++u) {
    const double azimuth = (u + 0.5 - shift_px) / width * 2.0 * kPi - kPi;
    const double c = std::cos(azimuth);
    w[u] = axis_floor + (1.0 - axis_floor) * c * c;
  }
  return w;
}

RingShift circular_phase_correlation(const std::vector<double>& a, const std::vector<double>& b,
                                     double center_px, double max_shift_px,
                                     const std::vector<double>* window_a, double max_frequency_fraction) {
  if (a.size() != b.size() || a.size() < 8)
    throw Error("phase correlation: rings differ in length or are too short");
  const int n = static_cast<int>(a.size());
  max_shift_px = std::min(max_shift_px, n / 2.0);
  std::vector<double> ones(n, 1.0);
  const std::vector<double>& wa = window_a ? *window_a : ones;
  if (static_cast<int>(wa.size()) != n) throw Error("phase correlation: window length differs from the ring");
  const std::vector<double> aw = apply_window(a, wa);
  ShiftEstimate e = correlate(aw, apply_window(b, wa), center_px, max_shift_px, max_frequency_fraction);
  if (window_a) {
    // The window of b must sit where a's window went: resample it through the shift, re-register.
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<double> wb(n);
      for (int u = 0; u < n; ++u) {
        // Linear interpolation of the window at u - shift (windows are smooth).
        double x = u - e.shift;
        x = std::fmod(x, static_cast<double>(n));
        if (x < 0) x += n;
        const int i0 = static_cast<int>(std::floor(x)) % n;
        const double t = x - std::floor(x);
        wb[u] = (1 - t) * wa[i0] + t * wa[(i0 + 1) % n];
      }
      e = correlate(aw, apply_window(b, wb), e.shift, 1.5, max_frequency_fraction);
    }
  }
  RingShift r;
  r.shift_px = e.shift;
  r.peak = e.peak;
  r.valid = e.peak > 0.0;
  return r;
}

RingRegistrar::RingRegistrar(const RingOptions& options, const std::vector<double>* column_weights)
    : options_(options) {
  options_.check();
  if (column_weights) column_weights_ = *column_weights;
  for (int offset : options_.frame_offsets) max_offset_ = std::max(max_offset_, offset);
}

RingShift RingRegistrar::add(const std::vector<double>& ring, double expected_shift_px) {
  const int j = frame_count_++;
  if (j == 0) {
    width_ = static_cast<int>(ring.size());
    window_ = axis_window(width_, options_.axis_floor);
    if (!column_weights_.empty()) {
      if (static_cast<int>(column_weights_.size()) != width_)
        throw Error("ring headings: column weights differ in length from the rings");
      for (int u = 0; u < width_; ++u) window_[u] *= column_weights_[u];
    }
  } else if (static_cast<int>(ring.size()) != width_) {
    throw Error("ring headings: rings differ in length");
  }
  const double px_per_rad = width_ / (2.0 * kPi);
  const double max_step_px = options_.max_turn_deg_per_frame * kPi / 180.0 * px_per_rad;
  step_peak_.push_back(0.0);
  failed_.push_back(false);
  chained_.push_back(0.0);
  RingShift step;
  if (j > 0) {
    // Chain first (the consecutive registration), then longer offsets centred on the chained prediction.
    step = circular_phase_correlation(recent_.back(), ring, expected_shift_px, max_step_px, &window_,
                                      options_.max_frequency_fraction);
    step_peak_[j] = step.peak;
    if (step.valid && step.peak >= options_.min_peak) {
      chained_[j] = chained_[j - 1] + step.shift_px / px_per_rad;
      pairs_.push_back({j - 1, j, step.shift_px / px_per_rad, step.peak});
    } else {
      chained_[j] = chained_[j - 1];
      failed_[j] = true;
    }
    for (int offset : options_.frame_offsets) {
      if (offset == 1 || offset > j) continue;
      const int i = j - offset;
      const double predicted = (chained_[j] - chained_[i]) * px_per_rad;
      const double tolerance = std::min(max_step_px, std::max(4.0, 0.25 * max_step_px * offset));
      const std::vector<double>& earlier = recent_[recent_.size() - static_cast<std::size_t>(offset)];
      const RingShift s = circular_phase_correlation(earlier, ring, predicted, tolerance, &window_,
                                                     options_.max_frequency_fraction);
      if (!s.valid || s.peak < options_.min_peak) continue;
      pairs_.push_back({i, j, s.shift_px / px_per_rad, s.peak});
      failed_[j] = false;
    }
  }
  recent_.push_back(ring);
  if (static_cast<int>(recent_.size()) > max_offset_) recent_.pop_front();
  return step;
}

RingHeadings RingRegistrar::solve() const {
  RingHeadings out;
  const int n = frame_count_;
  out.headings = chained_;
  out.step_peak = step_peak_;
  out.failed = failed_;
  out.registrations = static_cast<int>(pairs_.size());
  if (n <= 1 || pairs_.empty()) return out;

  // Joint robust least squares: theta_j - theta_i = delta, theta_0 = 0 (the gauge).
  const double huber = 0.3 * kPi / 180.0;
  std::vector<double> robust(pairs_.size(), 1.0);
  for (int iteration = 0; iteration < 4; ++iteration) {
    std::vector<Eigen::Triplet<double>> triplets;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n - 1);
    auto add = [&](int r, int c, double v) {
      if (r > 0 && c > 0) triplets.emplace_back(r - 1, c - 1, v);
    };
    for (size_t k = 0; k < pairs_.size(); ++k) {
      const Pair& p = pairs_[k];
      const double wgt = p.weight * robust[k];
      add(p.i, p.i, wgt);
      add(p.j, p.j, wgt);
      add(p.i, p.j, -wgt);
      add(p.j, p.i, -wgt);
      if (p.j > 0) rhs[p.j - 1] += wgt * p.delta;
      if (p.i > 0) rhs[p.i - 1] -= wgt * p.delta;
    }
    // A weak prior on consecutive equality keeps frames without any registration attached.
    for (int j = 1; j < n; ++j) {
      add(j - 1, j - 1, 1e-6);
      add(j, j, 1e-6);
      add(j - 1, j, -1e-6);
      add(j, j - 1, -1e-6);
    }
    Eigen::SparseMatrix<double> a(n - 1, n - 1);
    a.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
    if (solver.info() != Eigen::Success) break;
    const Eigen::VectorXd theta = solver.solve(rhs);
    for (int j = 1; j < n; ++j) out.headings[j] = theta[j - 1];
    for (size_t k = 0; k < pairs_.size(); ++k) {
      const double r = std::abs(out.headings[pairs_[k].j] - out.headings[pairs_[k].i] - pairs_[k].delta);
      robust[k] = r <= huber ? 1.0 : huber / r;
    }
  }
  return out;
}

RingHeadings solve_ring_headings(const std::vector<std::vector<double>>& rings, const RingOptions& options,
                                 const std::vector<double>* column_weights) {
  RingRegistrar registrar(options, column_weights);
  for (const std::vector<double>& ring : rings) registrar.add(ring);
  return registrar.solve();
}

}  // namespace plenopath
