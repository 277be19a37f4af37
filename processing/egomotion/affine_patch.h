#pragma once
// Affine refinement of a tracked feature (Shi and Tomasi's affine check, solved by Baker and Matthews'
// inverse compositional Gauss-Newton): a feature's patch, cut once where the track starts, is aligned to each
// later frame under an affine warp with photometric gain and bias removed, starting from the translation
// pyramidal Lucas-Kanade found.
//
// Why: translation-only Lucas-Kanade between consecutive frames is biased as the camera moves. The patch
// grows, shrinks and shears from frame to frame (a few per cent at walking speed indoors), and a translation
// estimate then follows the window's gradient centroid rather than the feature: measured on rendered walks
// with exact depth, tracks slid 0.10 px per frame (window 21; 0.07 at 9, 0.14 at 31), 1 px after 10 frames.
// That error is systematic along each track, so a bundle adjustment cannot average it away: it left the
// headings wandering by a few tenths of a degree. An affine warp absorbs the deformation, and aligning with
// the patch as first seen (not the previous frame's) keeps the per-frame errors from adding up.
#include <opencv2/core.hpp>
#include <string>

namespace plenopath {

struct AffinePatchOptions {
  int window_px = 21;  // odd; the patch aligned (a Gaussian weight favours its centre)
  int max_iterations = 12;
  double converged_px = 0.003;  // stop when the update moves the patch's corners less than this
  // The alignment is refused when, after it, the normalised residual (RMS of the zero-mean, unit-variance
  // patches' difference, weighted) exceeds this: 0.5 is a correlation of about 0.88.
  double max_residual = 0.5;
  double min_scale = 0.6, max_scale = 1.7;  // singular values of the warp's linear part
  void check() const;                       // throws Error naming the bad field
};

// The feature as first seen: a normalised patch and what inverse compositional alignment precomputes.
struct AffinePatch {
  cv::Mat values;    // CV_32F window x window, zero weighted mean, unit weighted variance
  cv::Mat steepest;  // CV_32F (window^2) x 6: template gradient times the warp Jacobian, per pixel
  cv::Matx66d hessian_inverse;
  bool valid = false;  // false when the patch has too little texture to align
};

// Where the patch lies in a frame: image position of its centre and the linear part of the warp (the
// patch's deformation since it was cut).
struct AffineWarp {
  cv::Point2d centre;
  cv::Matx22d linear = cv::Matx22d::eye();
};

// The singular values of a 2x2 linear map (how much it stretches at most and at least), and its rotation.
struct LinearStretch {
  double smallest = 1.0, largest = 1.0, rotation = 0.0;  // rotation in radians
};
LinearStretch linear_stretch(const cv::Matx22d& a);

// image: CV_8U; centre in OpenCV pixel coordinates (pixel centres on integers). The window plus a one-pixel
// margin must lie inside the image.
AffinePatch make_affine_patch(const cv::Mat& image, cv::Point2d centre, const AffinePatchOptions& options);

// Refines *warp (its centre and linear part on input: the starting guess) so that the patch matches `image`.
// Returns false (warp unspecified) when the alignment leaves the image, does not converge, deforms the
// patch beyond the scale limits, or leaves a residual above max_residual.
bool align_affine_patch(const AffinePatch& patch, const cv::Mat& image, AffineWarp* warp,
                        const AffinePatchOptions& options, double* residual = nullptr);

}  // namespace plenopath
