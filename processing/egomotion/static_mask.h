#pragma once
// Image regions that do not change as the camera moves: the trolley and the operator pushing it, in every
// frame of a trolley capture (issue 18). Their corners would be tracked as points that move with the camera,
// their columns would pull the ring registration towards no turn. The estimate watches the first frames of
// a capture (buffered by the tracker until it is decided): a pixel of the scene changes as the camera moves
// and turns, a pixel of the rig does not. At a coarse width (so shake and noise average out) and with each
// frame's brightness normalised (exposure), a pixel is static when it never changed by more than
// change_threshold against the first frame; static regions with structure of their own (edges that stayed
// put while the scene moved) are kept, grown by a margin, and masked. The estimate waits until the changed
// share of the image stops growing (the camera moved far enough that all of the scene changed); if the
// camera never moves, nothing is masked. On the office walk (512 wide): the scene alone reaches 99 % changed
// within 40 frames and nothing is masked; with the trolley and operator the changed share levels off at 77 %
// after about 40 frames and the mask covers 30 % of the image (the rig and its margin).
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace plenopath {

struct StaticMaskOptions {
  int frames = 60;      // frames the automatic estimate may look at (and the tracker buffer); 0 = off
  int min_frames = 20;  // it never decides on fewer
  // It decides once the share of the image that has changed stops growing: by less than plateau_growth over
  // the last plateau_frames frames (what has not changed by then is not going to), with at least
  // min_decided_fraction changed (else the camera has not moved yet: it waits, up to `frames`; if it still
  // has not moved, nothing is masked).
  int plateau_frames = 10;
  double plateau_growth = 0.01;
  double min_decided_fraction = 0.3;
  int width = 128;                     // working width of the estimate (2.8 deg per pixel)
  double change_threshold = 10.0;      // grey levels (each frame scaled to mean 128) a scene pixel changes by
  double texture_threshold = 3.0;      // grey levels per pixel of the mean image: a static edge
  int min_textured_pixels = 3;         // a static region needs this many static edge pixels to be masked
  double min_region_fraction = 0.004;  // ... and to cover this share of the image (before the margin)
  double margin_deg = 2.5;             // the mask grows by this much (shake, the rig's outline)
  double max_fraction = 0.4;           // more than this share static: not trusted, nothing is masked
  // Frames whose mean gradient is below this share of the first frame's are skipped (nearly blank).
  double min_texture_ratio = 0.25;
  void check() const;  // throws Error naming the bad field
};

class StaticMaskEstimator {
 public:
  explicit StaticMaskEstimator(const StaticMaskOptions& options);  // throws Error on bad options
  // A frame (CV_8U or BGR, equirectangular), in capture order.
  void add(const cv::Mat& frame);
  int frames() const { return frames_; }    // frames used (skipped ones not counted)
  int skipped() const { return skipped_; }  // nearly blank frames left out
  // Share of the image that has changed since the first frame.
  double changed_fraction() const;
  // Enough frames seen to decide (the camera moved, or options.frames reached).
  bool ready() const;
  // 255 = usable, 0 = static (do not use), at `size`; empty when nothing is masked.
  cv::Mat mask(cv::Size size) const;

 private:
  StaticMaskOptions options_;
  int frames_ = 0;
  int skipped_ = 0;
  double first_texture_ = 0.0;        // mean gradient of the first frame
  cv::Mat first_, max_change_, sum_;  // CV_32F at the working width
  std::vector<double> history_;       // changed_fraction() after each frame
};

// Combines masks (255 = usable): either may be empty; the result is empty when both are.
cv::Mat combine_masks(const cv::Mat& a, const cv::Mat& b);

}  // namespace plenopath
