#pragma once
// CG capture from the author's own Blender scene (issue 23): each frame is the .blend as the author made it,
// seen by a Cycles equirectangular camera at a pose of the path, with its depth (Cycles' Z pass). The studio
// writes a Python script into the work folder and runs Debian's blender headless on the scene
// (`blender -b SCENE.blend --factory-startup --python-exit-code 1 --python SCRIPT -- JOB.json`); one process
// renders every pose, since Blender takes seconds to start. The script puts a new panoramic camera in the
// scene (the author's stays, unused) and renders on the CPU.
//
// Frames (ARCHITECTURE.md conventions): Blender is z up, so plan (X, Y) is Blender (x, y) and the camera
// height Blender z, all times the scene's units per metre (1 / its unit scale unless set). The camera's
// rotation is (90 deg, 0, heading - 90 deg): Cycles' equirectangular image has the camera's view direction
// at its centre column and, seen from above, azimuth growing clockwise to the right, row 0 the zenith, as
// the studio's (BlenderRender.* checks it against coloured walls and hand-intersected geometry).
//
// Depth: Cycles' Z pass of a panoramic camera is the distance from the camera's centre to the first surface
// along the ray (kernel camera_z_depth), written by the first sample only. So depth is its own render:
// one sample, a pixel filter 0.01 px wide (the ray through the pixel's centre), no compositing, saved as an
// uncompressed 32-bit multilayer EXR that this file reads; sky (Cycles writes 1e10) is 0. Colour is a
// render with the scene's own settings (its samples unless `samples` is set, its pixel filter, denoising,
// colour management and compositing), saved as 8-bit PNG.
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "processing/util/progress.h"

namespace plenopath {

struct BlenderOptions {
  std::string executable = "blender";  // on PATH, or a path to it
  int width = 2048;                    // panorama width; the height is half
  double camera_height_m = 1.6;        // camera centre above the plan's floor (Blender z = 0)
  double units_per_metre = 0.0;        // Blender units in a metre; 0 = the scene's (1 / its unit scale)
  bool colour = true;                  // false: depth only (a coarse pass for online sampling)
  bool depth = true;
  int samples = 0;             // Cycles samples of the colour render (0 = the scene's own)
  int threads = 0;             // Cycles render threads (0 = every core)
  double max_depth_m = 200.0;  // farther (or sky): no depth (0 in the depth image)
  double timeout_s = 900.0;    // Blender's start and each frame may take this long, or it is stopped
  void check() const;          // throws Error naming the bad field
};

struct BlenderFrame {
  cv::Mat rgb;    // CV_8UC3 (BGR), width x width/2; empty without colour
  cv::Mat depth;  // CV_32F metres along the ray from the camera centre; 0 = no hit; empty without depth
};

// True when `scene_file` is a Blender scene (.blend, any case): render_cg_capture and render-scene route it
// here, anything else to POV-Ray.
bool is_blender_scene(const std::string& scene_file);

// The blender executable to run (searched on PATH when not a path), or an Error that says how to install it.
std::string find_blender(const std::string& executable);

// Reads the first channel whose name ends in `suffix` (e.g. ".Depth.Z") from an uncompressed scanline
// OpenEXR file (as Blender writes a multilayer EXR with codec NONE), FLOAT or HALF, as CV_32F, top row
// first. Throws Error naming the file when it is not such a file or has no such channel.
cv::Mat read_uncompressed_exr_channel(const std::string& file, const std::string& suffix);

// Renders every pose with one Blender process, handing each frame to `deliver` in the poses' order (index
// into `poses`, on the calling thread) as soon as Blender has written it. `work_dir` (it must exist) holds
// the script, the job and the frames' files until they are delivered. Throws Error naming the scene when
// Blender fails or writes no frame (its last messages included), or Cancelled; frames delivered before stay
// delivered.
void render_blender_frames(const std::string& scene_file, const std::vector<PathFrame>& poses,
                           const BlenderOptions& options, const std::string& work_dir,
                           const std::function<void(int index, BlenderFrame&& frame)>& deliver,
                           Progress& progress = null_progress());

// One frame (a Blender process of its own: seconds of start-up).
BlenderFrame render_blender_frame(const std::string& scene_file, const PathFrame& pose,
                                  const BlenderOptions& options, const std::string& work_dir,
                                  Progress& progress = null_progress());

}  // namespace plenopath
