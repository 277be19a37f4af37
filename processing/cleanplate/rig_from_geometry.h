#pragma once
// The rig over a whole capture, from the scene's geometry (issue 24). The tracker's static mask finds what
// never changed over the first frames: the trolley, and of a walking operator at best the outline. The
// operator's body stays in the same pixels over the whole capture (capture_stillness.h), as do plain walls,
// floor and ceiling; what tells them apart is the geometry. Keyframes spread over the capture are each
// compared with frames along the path (baselines min..max): a keyframe pixel's scene point, through its
// static depth, lands elsewhere in the other frame. A plain wall agrees with what lands there; the operator
// does not — except where the scene point lands in the other frame's own operator (frames ahead see the
// scene behind the operator through their own operator). So the decision is iterated: samples that land
// in the rig found so far are left out, and the rig grows from its edges, where the parallax is, inwards.
// A pixel is the rig when it stays over the capture and at most max_agree_share of the samples that land
// outside the rig agree with it. Things off the plan (furniture, a lintel) disagree too, but do not stay.
#include <functional>
#include <opencv2/core.hpp>

#include "model/camera_path.h"
#include "processing/cleanplate/capture_stillness.h"
#include "processing/util/progress.h"

namespace plenopath {

struct RigFromGeometryOptions {
  int keyframes = 10;            // spread over the path
  int neighbours = 4;            // about this many frames each side of each, over the baselines
  double min_baseline_m = 0.5;   // nearer frames see too little parallax
  double max_baseline_m = 5.0;   // farther ones warp badly where the depth is approximate
  double min_stay_share = 0.7;   // of the capture's frames at the median (capture_stillness.h)
  double max_agree_share = 0.4;  // of the samples landing outside the rig
  int min_samples = 6;           // samples landing outside the rig that a decision needs
  int iterations = 4;
  double min_moved_px = 1.5;  // a sample counts when it lands at least this far from its pixel
  double occlusion_tolerance = 0.05;
  double min_region = 0.002;  // share of the image: smaller regions found are dropped
  void check() const;         // throws Error naming the bad field
};

// `frame(position)`, `static_depth(position)`: as clean_plate (clean_plate.h). `rig_mask`: the rig known
// already (CV_8U, non-zero = rig; may be empty), kept. `stillness` at the working width of the decision.
// Returns CV_8U at the frames' size, 255 = rig: `rig_mask` and what was found; empty when both are empty.
// Progress: once per keyframe compared; a cancel ends it with Cancelled.
cv::Mat rig_from_geometry(const CameraPath& path, const std::function<cv::Mat(int position)>& frame,
                          const std::function<cv::Mat(int position)>& static_depth, const cv::Mat& rig_mask,
                          const CaptureStillness& stillness, const RigFromGeometryOptions& options = {},
                          Progress& progress = null_progress());

}  // namespace plenopath
