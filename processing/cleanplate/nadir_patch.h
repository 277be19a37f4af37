#pragma once
// The nadir patch (issue 24): what covers the part of the rig that no frame saw behind (the trolley's
// footprint, the tripod's legs, the operator's feet), as tour tools do it. Either a blurred fill carried in
// from round the region (inpainted at a coarse width, the seam wrapped, then softened), or the author's
// image (a logo) drawn as a disc centred on the nadir, sized to cover the region below
// max_image_radius_deg from the nadir; what the disc does not cover gets the blurred fill.
#include <opencv2/core.hpp>
#include <string>

#include "model/enums.h"

namespace plenopath {

struct NadirPatchOptions {
  NadirPatch kind = NadirPatch::kBlur;
  cv::Mat image;                     // kImage: BGR (or BGRA: alpha over the blurred fill), any size
  double max_image_radius_deg = 40;  // the disc never grows beyond this from the nadir
  double min_image_radius_deg = 8;   // ... nor shrinks below it
  int blur_width = 512;              // working width of the blurred fill
  void check() const;                // throws Error naming the bad field
};

// `image` (CV_8UC3 equirectangular) with `region` (CV_8U, non-zero = replace) patched; `region` empty or
// all zero, or kind kNone: the image unchanged.
cv::Mat apply_nadir_patch(const cv::Mat& image, const cv::Mat& region, const NadirPatchOptions& options);

// An image file as a nadir patch (BGR, or BGRA when it has alpha; grey and 16-bit converted). Throws Error
// naming the file when it cannot be read.
cv::Mat read_nadir_image(const std::string& file);

// The disc's radius (degrees from the nadir) that apply_nadir_patch gives an image patch for `region`; 0
// when no pixel of it lies within max_image_radius_deg of the nadir (then no disc is drawn).
double nadir_disc_radius_deg(const cv::Mat& region, const NadirPatchOptions& options);

}  // namespace plenopath
