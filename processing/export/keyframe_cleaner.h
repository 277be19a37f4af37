#pragma once
// A keyframe as the tour shows it (issue 24): its clean plate (the people who walked through and the rig
// replaced by what other frames saw behind them, the rest of the rig under the nadir patch) and the faces
// that remain blurred. The export makes every keyframe this way and the studio previews one: the same
// code, so the preview is what the visitor will see. The capture is opened once and the rig found once
// (the tracker's static mask over the capture's first frames, and the capture's rig mask image).
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/project.h"
#include "processing/cleanplate/clean_plate.h"
#include "processing/cleanplate/face_blur.h"
#include "processing/cleanplate/nadir_patch.h"
#include "processing/util/progress.h"

namespace plenopath {

class FrameSource;
class SyntheticScene;

struct KeyframeCleaning {
  bool clean_plates = false;  // static depth from the capture's depth maps, else rendered from the plan
  CleanPlateOptions clean_plate;
  bool fill_rig = true;     // with clean plates: the rig filled, what nothing saw under the nadir patch
  NadirPatchOptions nadir;  // kImage: the picture read by from_project (or by the caller)
  bool blur_faces = false;
  FaceBlurOptions face_blur;
  void check() const;  // throws Error naming the bad field
  // The project's tour settings and camera height; the nadir image read here (Error naming it).
  static KeyframeCleaning from_project(const Project& project);
};

struct CleanedKeyframe {
  cv::Mat image;     // CV_8UC3, what the tour shows
  cv::Mat original;  // CV_8UC3, the frame as captured
  bool cleaned = false;
  CleanPlate plate;  // when cleaned
  int faces = 0;     // blurred
  std::vector<std::string> warnings;
};

class KeyframeCleaner {
 public:
  // Opens the capture; with clean plates and fill_rig, finds the rig. Throws Error on bad options, a
  // project without a capture or path, or unreadable frames.
  KeyframeCleaner(const Project& project, const KeyframeCleaning& options,
                  Progress& progress = null_progress());
  ~KeyframeCleaner();
  // Capture frame `frame` (a path frame's index) as the tour shows it. A cancel ends it with Cancelled.
  CleanedKeyframe clean(int frame, Progress& progress = null_progress());
  FrameSource& frames() { return *frames_; }
  const cv::Mat& rig_mask() const { return rig_mask_; }  // CV_8U, 255 = rig; empty: none
  double rig_pct() const;

 private:
  // At the frames' size, or at `size` (the rig finder works at 256 wide: no need to render 2048).
  cv::Mat static_depth(int position, cv::Size size = {});
  const Project& project_;
  KeyframeCleaning options_;
  std::unique_ptr<FrameSource> frames_;
  std::unique_ptr<SyntheticScene> plan_scene_;
  cv::Mat rig_mask_;
};

}  // namespace plenopath
