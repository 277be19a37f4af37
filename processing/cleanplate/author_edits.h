#pragma once
// The author's corrections of a clean plate (model/tour_settings.h, CleanPlateEdit): where they painted a
// region away, the keyframe takes what the other frames saw (the plate's consensus; where none saw it, the
// nadir patch); where they painted it back, the keyframe stays as captured.
#include <opencv2/core.hpp>
#include <string>

#include "processing/cleanplate/clean_plate.h"

namespace plenopath {

// The edit mask of `file` at `size` (nearest neighbour), values as CleanPlateEdit says. Throws Error naming
// the file when it cannot be read.
cv::Mat read_clean_plate_edit(const std::string& file, cv::Size size);

// `plate` with `edits` applied on top of `original` (the keyframe as captured): returns the image, and in
// `patch_region` (CV_8U) what is left for the nadir patch (the rig nothing saw, minus what was painted
// back, plus what was painted away that nothing saw).
cv::Mat apply_clean_plate_edits(const CleanPlate& plate, const cv::Mat& original, const cv::Mat& edits,
                                cv::Mat& patch_region);

}  // namespace plenopath
