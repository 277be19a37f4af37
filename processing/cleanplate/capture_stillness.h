#pragma once
// What stays in the same pixels over a whole capture (issue 24): the operator pushing the trolley stands in
// every frame, lit differently as the walk goes on and swaying a little, where the scene behind changes as
// the camera walks the building. Frames spread evenly over the capture (not only its first ones, as the
// tracker's static mask must), each at a coarse width and brought to one brightness (exposure): per pixel
// and channel their median, and the share of the frames within `tolerance` of it. Plain walls, the ceiling
// and the floor stay too: this is evidence for the rig, not the rig; the clean plate decides per keyframe
// with the scene's geometry (clean_plate.h).
#include <functional>
#include <opencv2/core.hpp>

#include "processing/util/progress.h"

namespace plenopath {

struct CaptureStillnessOptions {
  int frames = 32;     // frames looked at, spread evenly over the capture
  int width = 256;     // working width (1.4 deg per pixel)
  int tolerance = 14;  // grey levels (max over channels) from the median that still count as the same
  void check() const;  // throws Error naming the bad field
};

struct CaptureStillness {
  cv::Mat median;      // CV_8UC3 at the working width, each frame at mean brightness 128
  cv::Mat share;       // CV_8U, 255 * share of the frames within tolerance of the median
  int frames = 0;      // frames used
  int tolerance = 14;  // the options' tolerance
  bool empty() const { return median.empty(); }
};

// `frame(k)`: capture frame k (BGR), k in [0, frame_count). Fewer than 8 frames: empty (too few to tell).
// Progress: once per frame read; a cancel ends it with Cancelled.
CaptureStillness capture_stillness(const std::function<cv::Mat(int)>& frame, int frame_count,
                                   const CaptureStillnessOptions& options = {},
                                   Progress& progress = null_progress());

// `image` (BGR, any size with the capture's aspect) at the stillness's width and brightness.
cv::Mat at_stillness_scale(const cv::Mat& image, const CaptureStillness& stillness);

// CV_8U at the stillness's size: 255 where `image` (a frame of the capture) shows what the capture shows
// there (within the tolerance of the median) and at least `min_share` of the capture's frames do.
cv::Mat stays_in_place(const cv::Mat& image, const CaptureStillness& stillness, double min_share);

}  // namespace plenopath
