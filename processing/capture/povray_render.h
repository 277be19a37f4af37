#pragma once
// CG capture from the author's own POV-Ray scene (issue 23; the seed paper's CG plenoptic path): each frame
// is the scene as the author wrote it, seen by the studio's spherical camera at a pose of the path, with its
// depth. POV-Ray uses the last camera a scene declares, so a small wrapper includes the author's file and
// then declares the studio's camera (ARCHITECTURE.md conventions: plan (X, Y, Z) is POV <X, Z, Y>; the
// panorama's centre column looks along the heading, azimuth grows clockwise seen from above).
//
// Depth: POV-Ray writes no depth, so it is coded in two extra passes with a fog of distance D, one black,
// one white. A pixel whose surface has colour C at distance d shows C t (black fog) and C t + 1 - t (white
// fog), t = exp(-d / D): their difference is 1 - t whatever C, its lights and shadows are, so
// d = -D ln(1 - (white - black)). The passes are rendered linear (File_Gamma 1), 16 bits, without
// antialiasing, with max_trace_level 1 (no reflected or refracted rays, which would mix in other distances).
// Sky (nothing hit) is fully fogged: no depth. The author's own fogs, media and radiosity would disturb the
// coding, so the depth passes render a copy of the scene's files without them (povray_atmosphere.h); the
// colour pass keeps them. POV-Ray fogs only empty or hollow space: an object around the camera must be
// `hollow`.
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "processing/util/progress.h"

namespace plenopath {

struct PovrayOptions {
  std::string executable = "povray";  // on PATH, or a path to it
  int width = 2048;                   // panorama width; the height is half
  double camera_height_m = 1.6;       // camera centre above the plan's floor (POV y = 0)
  double units_per_metre = 1.0;       // scene units in a metre (POV scenes have no unit)
  // The scene is modelled with z up (`sky z`, as CAD exports and many examples are): plan (X, Y) is POV
  // (x, y) and the camera height POV z. Otherwise y up: plan (X, Y) is POV (x, z).
  bool z_up = false;
  bool colour = true;  // false: depth only (a coarse pass for online sampling)
  bool depth = true;
  // Fog distance of the depth passes (metres): depth resolution is about D / 65535 / exp(-d / D) at
  // distance d (8 m: 0.12 mm at 0, 0.9 mm at 16 m, 6 mm at 32 m). 0 = 8 m.
  double depth_fog_m = 0.0;
  double max_depth_m = 200.0;  // farther (or sky): no depth (0 in the depth image)
  bool antialias = true;       // the colour pass (+A0.3); the depth passes never
  int quality = 9;             // the colour pass's +Q (0-11)
  double timeout_s = 900.0;    // a pass that takes longer than this a frame is stopped
  // A POV-Ray process idles about a quarter of a second before and after each frame whatever its size, so
  // frames are rendered in animation mode, up to frames_per_process by one process, by several processes at
  // once (0 = the cores + 2; each traces with one thread).
  int frames_per_process = 16;
  int processes = 0;
  void check() const;  // throws Error naming the bad field
};

struct PovrayFrame {
  cv::Mat rgb;    // CV_8UC3 (BGR), width x width/2
  cv::Mat depth;  // CV_32F metres along the ray from the camera centre; 0 = no hit; empty without depth
};

// The povray executable to run (searched on PATH when not a path), or an Error that says how to install it.
std::string find_povray(const std::string& executable);

// Renders one frame. `work_dir` holds the wrapper and the passes' images (it must exist); POV-Ray runs in the
// scene's folder, so the scene's own includes and image maps resolve as when the author renders it. Throws
// Error naming the scene when POV-Ray fails (its last messages included), or Cancelled.
PovrayFrame render_povray_frame(const std::string& scene_file, const PathFrame& pose,
                                const PovrayOptions& options, const std::string& work_dir,
                                Progress& progress = null_progress());

// Renders every pose, handing each frame to `deliver` in the poses' order (index into `poses`, on the
// calling thread), a few processes' chunks at a time, so that memory holds only those. Throws as
// render_povray_frame does; the frames delivered before stay delivered.
void render_povray_frames(const std::string& scene_file, const std::vector<PathFrame>& poses,
                          const PovrayOptions& options, const std::string& work_dir,
                          const std::function<void(int index, PovrayFrame&& frame)>& deliver,
                          Progress& progress = null_progress());

}  // namespace plenopath
