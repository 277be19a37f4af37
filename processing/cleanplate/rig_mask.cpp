#include "processing/cleanplate/rig_mask.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "model/error.h"

namespace plenopath {

cv::Mat rig_mask_of_capture(const std::function<cv::Mat(int)>& frame, int frame_count, cv::Size size,
                            const std::string& author_mask_file, const StaticMaskOptions& options,
                            Progress& progress) {
  cv::Mat usable;
  if (options.frames > 0 && frame_count > 0) {
    StaticMaskEstimator estimator(options);
    const int frames = std::min(frame_count, options.frames);
    for (int k = 0; k < frames && !estimator.ready(); ++k) {
      progress.checkpoint(double(k) / frames, "finding the rig");
      estimator.add(frame(k));
    }
    usable = estimator.mask(size);
  }
  if (!author_mask_file.empty()) {
    cv::Mat author = cv::imread(author_mask_file, cv::IMREAD_GRAYSCALE);
    if (author.empty()) throw Error(author_mask_file + ": cannot read the rig mask image");
    if (author.size() != size) cv::resize(author, author, size, 0, 0, cv::INTER_NEAREST);
    cv::threshold(author, author, 127, 255, cv::THRESH_BINARY);
    usable = combine_masks(usable, author);
  }
  progress.report(1.0);
  if (usable.empty()) return {};
  cv::Mat rig = usable == 0;
  if (cv::countNonZero(rig) == 0) return {};
  return rig;
}

}  // namespace plenopath
