#pragma once
// A CG capture (issue 23): the author's POV-Ray scene (.pov, povray_render.h) or Blender scene (.blend,
// blender_render.h; chosen by the file's extension) rendered along a path into a capture folder laid out
// as `plenopath render` writes one (DIR/groundtruth.json with `file` fields, DIR/frames/NNNNNN.jpg,
// DIR/depth/NNNNNN.png in 16-bit millimetres), so tracking, sampling and the studio take it like any other.
// Every frame, or online (online_sampling.h): the whole path as coarse depth, full frames only for the
// keyframes, which are then the capture (DIR/online_sampling.json says what was rendered at each size).
// The command line's render-scene and the studio's Process > Render CG scene both call it.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"
#include "processing/capture/blender_render.h"
#include "processing/capture/povray_render.h"
#include "processing/sampling/depth_section.h"
#include "processing/util/progress.h"

namespace plenopath {

struct CgCaptureOptions {
  PovrayOptions povray;    // a .pov scene: size, camera height, units, depth, quality, processes
  BlenderOptions blender;  // a .blend scene: size, camera height, units (0 = the scene's), depth, samples
  int jpeg_quality = 92;
  bool online = false;
  SamplingParameters online_parameters;  // online: the depth sampler's budget (count, or ratio)
  int coarse_width = 256;                // online: width of the coarse depth pass
  // The scene cut at eye height as the path saw it (depth_section.h), from every frame's depth (online: the
  // coarse pass's): the project's plan when the scene comes without a DXF.
  bool section_plan = false;
  DepthSectionOptions section;
  double online_loss_target = 0.0;  // online: > 0, the fewest keyframes losing at most this (see
                                    // OnlineSamplingOptions::loss_target); the budget count caps them
  void check() const;               // throws Error naming the bad field
};

struct CgCaptureResult {
  CameraPath path;  // the frames written (all, or the online keyframes); scale_source "ground_truth"
  int path_frames = 0, full_frames = 0, coarse_frames = 0;
  bool depth = false;            // depth maps were written (DIR/depth)
  double camera_height_m = 0.0;  // the renderer's camera height
  double online_loss = 0.0;      // online: the keyframes' geometric loss on the coarse depth's envelopes
  bool online_loss_target_met = true;
  FloorPlan section_plan;      // with CgCaptureOptions::section_plan; empty otherwise
  Keyframes online_keyframes;  // online: the sampler's keyframes (path frame indices), every frame written
  double seconds_coarse = 0.0, seconds_total = 0.0;
};

// "X,Y X,Y ..." (metres, plan frame): the points, repeats dropped. Throws Error naming an item that is not
// X,Y.
std::vector<Eigen::Vector2d> parse_waypoints(const std::string& text);

// "X,Y X,Y ..." (metres, plan frame): a walk along the polyline, a frame every `step` metres, each facing
// along the path (the direction over the half metre around it, so corners turn smoothly). Throws Error.
CameraPath walk_waypoints(const std::string& text, double step);

// The waypoints as walk_waypoints reads them: "X,Y X,Y ..." in metres with two decimals.
std::string waypoints_text(const std::vector<Eigen::Vector2d>& points);

// A path's positions thinned to its corners (Douglas-Peucker): every frame lies within `tolerance` metres
// of the polyline through the points kept; the first and last frames are kept. The frames are taken in
// order as one polyline (pieces are not told apart). Throws Error when tolerance is not > 0.
std::vector<Eigen::Vector2d> path_corners(const CameraPath& path, double tolerance);

// Throws Error (POV-Ray's or Blender's own messages included) or Cancelled; `out_dir` is created, and a
// cancelled or failed run leaves what it wrote so far (without its work folder).
CgCaptureResult render_cg_capture(const std::string& scene_file, const CameraPath& path,
                                  const CgCaptureOptions& options, const std::string& out_dir,
                                  Progress& progress = null_progress());

}  // namespace plenopath
