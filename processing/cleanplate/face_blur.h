#pragma once
// Faces of the people who remain in a keyframe (a still crowd, a receptionist) blurred on request
// (issue 24), by OpenCV's Haar face detector (Debian's opencv-data) run on the equirectangular band round
// the horizon, where faces are nearly undistorted, with the seam wrapped so that a face across it is found
// whole. Each face is blurred on an ellipse grown by `margin`, smoothly, so that no hard edge shows.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace plenopath {

struct FaceBlurOptions {
  std::string cascade_file;         // empty: the frontal-face cascade of opencv-data (default_face_cascade)
  double max_elevation_deg = 50.0;  // the band looked in: faces further up or down are too distorted
  int min_face_px = 20;             // smaller faces are not looked for
  double scale_factor = 1.08;       // the detector's pyramid step
  int min_neighbours = 6;           // its overlapping detections needed for a face
  double margin = 0.3;              // the blurred ellipse is the face grown by this share each way
  void check() const;               // throws Error naming the bad field
};

struct FaceBlurResult {
  cv::Mat image;                // CV_8UC3
  std::vector<cv::Rect> faces;  // in the panorama's pixels; x + width may pass the right edge (wraps)
};

// The standard location of the frontal-face cascade; throws Error saying which package installs it.
std::string default_face_cascade();

// `image`: CV_8UC3 equirectangular. Throws Error naming the cascade file when it cannot be read.
FaceBlurResult blur_faces(const cv::Mat& image, const FaceBlurOptions& options = {});

}  // namespace plenopath
