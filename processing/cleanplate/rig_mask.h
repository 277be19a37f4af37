#pragma once
// The rig's pixels for clean plates and the nadir patch (issue 24): the trolley, the operator, a tripod,
// whatever covers the same pixels in every frame. The tracker's own estimate (egomotion/static_mask.h: what
// does not change over the first frames while the scene does) made again from the capture, combined with
// the author's mask image when the capture has one (black = rig, as `track --mask`).
#include <functional>
#include <opencv2/core.hpp>
#include <string>

#include "processing/egomotion/static_mask.h"
#include "processing/util/progress.h"

namespace plenopath {

// `frame(k)`: capture frame k in capture order (BGR), k in [0, frame_count). `author_mask_file`: the
// capture's rig mask image or empty. Returns CV_8U at `size`, 255 where the rig is; empty when there is no
// rig (the camera never moved, or nothing stayed put). Throws Error naming the mask file when it cannot be
// read. Progress: once per frame looked at; a cancel ends it with Cancelled.
cv::Mat rig_mask_of_capture(const std::function<cv::Mat(int)>& frame, int frame_count, cv::Size size,
                            const std::string& author_mask_file, const StaticMaskOptions& options = {},
                            Progress& progress = null_progress());

}  // namespace plenopath
