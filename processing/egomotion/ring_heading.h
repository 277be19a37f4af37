#pragma once
// Step 1 of the egomotion (seed paper §4.1): coarse headings from ring images. A ring image is the column
// mean of an equirectangular frame over a latitude band, each row weighted by the angle it subtends
// (cos elevation). A pure rotation about the vertical is an exact circular shift of the ring, so circular
// 1-D phase correlation with a sub-pixel peak gives the heading change: shift (pixels) x 2pi / w.
#include <deque>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace plenopath {

struct RingOptions {
  double min_elevation_deg = -35.0;  // latitude band averaged into the ring (walls, not floor or ceiling)
  double max_elevation_deg = 35.0;
  // Column weight near the camera's axis (azimuth 0 and 180, the foci of expansion and contraction, where
  // a trolley's own translation makes no parallax): w(a) = axis_floor + (1 - axis_floor) * cos(a)^2.
  // axis_floor = 1 weighs all columns alike.
  double axis_floor = 0.25;
  // Spectral taper: frequencies above this fraction of Nyquist are faded out (whitened high frequencies
  // are mostly noise and aliasing).
  double max_frequency_fraction = 0.5;
  double max_turn_deg_per_frame = 18.0;  // bounds the peak search around the expected turn (RingRegistrar)
  std::vector<int> frame_offsets = {1, 2, 4, 8};  // each frame is registered against these earlier frames
  double min_peak = 0.05;                         // weaker correlation peaks are treated as failures

  // Empty when valid, otherwise what is wrong.
  void check() const;  // throws Error naming the bad field
};

// Ring image of a BGR (CV_8UC3) or gray (CV_8U / CV_32F) equirectangular frame: one value per column.
std::vector<double> make_ring_image(const cv::Mat& equirect, const RingOptions& options);
// With a mask (CV_8U, the frame's size, 0 = not to use: the trolley, the operator): each column is the mean
// of its usable rows; a column with none takes the ring's mean (and should get no weight).
std::vector<double> make_ring_image(const cv::Mat& equirect, const RingOptions& options, const cv::Mat& mask);
// Share of each column's band (by solid angle) that the mask leaves usable, in [0, 1]: column weights for
// the registration.
std::vector<double> ring_column_weights(const cv::Mat& mask, const RingOptions& options);

struct RingShift {
  double shift_px = 0.0;  // b(x) ~ a(x - shift): b is a turned right by shift pixels
  double peak = 0.0;      // normalised correlation at the peak (1 = identical up to the shift)
  bool valid = false;
};

// Circular phase correlation on the exact length (no padding), peak searched within
// |shift - center_px| <= max_shift_px and refined to sub-pixel by Newton steps on the band-limited
// (trigonometric) interpolation of the correlation. `window_a` (optional, same length) weights the columns of
// `a`; the window for `b` follows it through the estimated shift so that the window itself does not pull the
// peak towards zero.
RingShift circular_phase_correlation(const std::vector<double>& a, const std::vector<double>& b,
                                     double center_px, double max_shift_px,
                                     const std::vector<double>* window_a = nullptr,
                                     double max_frequency_fraction = 0.5);

// Column weights of RingOptions::axis_floor for a ring of `width` columns, evaluated at column positions
// shifted by `shift_px`.
std::vector<double> axis_window(int width, double axis_floor, double shift_px = 0.0);

struct RingHeadings {
  std::vector<double> headings;   // radians, unwrapped, frame 0 = 0
  std::vector<double> step_peak;  // correlation peak of frame i against frame i-1 (0 for frame 0)
  std::vector<bool> failed;       // frame had no valid registration against any earlier frame
  int registrations = 0;          // pairwise registrations used in the joint solve
};

// The same, streaming: rings are added in capture order and registered against the earlier ones as they
// come, keeping only the last max(frame_offsets) rings, so a long capture's memory is its registrations (a
// few dozen bytes a frame), not its rings (8 KB a frame at 1024 wide). solve() runs the joint solve.
class RingRegistrar {
 public:
  explicit RingRegistrar(const RingOptions& options, const std::vector<double>* column_weights = nullptr);
  // Registers the next frame's ring; returns its registration against the frame before (invalid for the
  // first frame, or when it failed: see RingOptions::min_peak). The peak is searched within
  // max_turn_deg_per_frame of `expected_shift_px` (ring pixels): the turn the frame before was measured to
  // make, so that a turn faster than the bound is followed once it is under way.
  RingShift add(const std::vector<double>& ring, double expected_shift_px = 0.0);
  int frame_count() const { return frame_count_; }
  RingHeadings solve() const;

 private:
  struct Pair {
    int i, j;  // j > i
    double delta;
    double weight;
  };
  RingOptions options_;
  std::vector<double> column_weights_, window_;
  int max_offset_ = 1, width_ = 0, frame_count_ = 0;
  std::deque<std::vector<double>> recent_;  // the last max_offset_ rings
  std::vector<double> chained_, step_peak_;
  std::vector<bool> failed_;
  std::vector<Pair> pairs_;
};

// Registers every ring against several earlier ones (RingOptions::frame_offsets) and solves all headings
// jointly by robust (iteratively reweighted) least squares.
// `column_weights` (optional, one per column): multiplies the axis window (ring_column_weights of a mask).
RingHeadings solve_ring_headings(const std::vector<std::vector<double>>& rings, const RingOptions& options,
                                 const std::vector<double>* column_weights = nullptr);

}  // namespace plenopath
