#include "processing/cleanplate/author_edits.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "model/tour_settings.h"

namespace plenopath {

cv::Mat read_clean_plate_edit(const std::string& file, cv::Size size) {
  cv::Mat mask = cv::imread(file, cv::IMREAD_GRAYSCALE);
  if (mask.empty()) throw Error(file + ": cannot read the clean-plate edit (a grey image)");
  if (mask.size() != size) cv::resize(mask, mask, size, 0, 0, cv::INTER_NEAREST);
  return mask;
}

cv::Mat apply_clean_plate_edits(const CleanPlate& plate, const cv::Mat& original, const cv::Mat& edits,
                                cv::Mat& patch_region) {
  const cv::Size size = original.size();
  patch_region = plate.rig_unfilled.empty() ? cv::Mat::zeros(size, CV_8U) : plate.rig_unfilled.clone();
  if (edits.empty()) return plate.image.clone();
  if (edits.size() != size || edits.type() != CV_8U)
    throw Error("clean-plate edit: the mask is not a grey image of the keyframe's size");
  const cv::Mat remove = edits > 191, keep = (edits > 63) & (edits <= 191);
  cv::Mat out = plate.image.clone();
  original.copyTo(out, keep);
  patch_region.setTo(0, keep);
  // Painted away: the consensus where some frame saw the scene there (the people's support, or the rig's
  // fill); elsewhere the nadir patch.
  cv::Mat seen = plate.support >= 1;
  if (!plate.rig_filled.empty()) seen |= plate.rig_filled;
  plate.consensus.copyTo(out, remove & seen);
  patch_region |= remove & ~seen;
  return out;
}

}  // namespace plenopath
