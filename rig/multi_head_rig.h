#pragma once
// The multi-head rig: N pinhole heads sharing (nearly) one nodal point, like the seed's 10-head camera (a
// ring of heads plus one looking up and one looking down). Rig frame = camera frame of rig/spherical.h (+x
// forward, +y left, +z up). Head frame: OpenCV pinhole (x right, y down, z along the optical axis); pixel (u,
// v) has its centre at integer coordinates (u, v), as cv::remap expects.
//
// Calibration file (JSON):
// {"format":"plenopath-rig","version":1,"heads":[{"name":"ring0","width":512,"height":640,
//   "fx":..,"fy":..,"cx":..,"cy":..,"yaw_deg":0,"pitch_deg":0,"roll_deg":0,"offset_m":[0,0,0]}, ...]}
// yaw: azimuth of the optical axis (grows to the right, as in panoramas); pitch: its elevation; roll: about
// the optical axis, clockwise as seen by the head.
#include <Eigen/Core>
#include <array>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/json_reader.h"

namespace plenopath {

class SyntheticScene;
struct RenderOptions;

struct PinholeHead {
  std::string name;
  int width = 512, height = 640;
  double fx = 300, fy = 300, cx = 255.5, cy = 319.5;  // pixels
  double yaw_deg = 0, pitch_deg = 0, roll_deg = 0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // optical centre in the rig frame, metres

  // Columns: the head's x (right), y (down), z (optical axis) in the rig frame.
  Eigen::Matrix3d rig_from_head() const;
  // Unit rig-frame bearing of a (continuous) pixel.
  Eigen::Vector3d bearing(const Eigen::Vector2d& pixel) const;
  // Pixel of a rig-frame direction seen from the head's centre; false when behind the head.
  bool project(const Eigen::Vector3d& rig_direction, Eigen::Vector2d* pixel) const;
  bool inside(const Eigen::Vector2d& pixel) const {
    return pixel.x() >= -0.5 && pixel.y() >= -0.5 && pixel.x() <= width - 0.5 && pixel.y() <= height - 0.5;
  }
};

struct MultiHeadRig {
  std::vector<PinholeHead> heads;
  void check() const;  // throws Error saying what is wrong ("head 2 ('left'): fx and fy must be > 0")
};

struct DefaultRigOptions {
  int ring_heads = 8;           // heads around the horizon, evenly spread in yaw
  bool up = true, down = true;  // one head at the zenith, one at the nadir
  int ring_width = 512, ring_height = 640;
  double ring_horizontal_fov_deg = 62.0;  // > 360 / ring_heads, so neighbours overlap
  double ring_vertical_fov_deg = 104.0;
  int cap_size = 512;
  double cap_fov_deg = 104.0;
  double offset_radius =
      0.0;  // metres: heads sit this far out along their optical axes (0 = one nodal point)
};
// The default is the seed's 10 heads: 8 in a ring, one up, one down.
MultiHeadRig make_default_rig(const DefaultRigOptions& options = {});

nlohmann::json rig_to_json(const MultiHeadRig& rig);
MultiHeadRig rig_from_json(const JsonReader& reader);  // errors name the file and the JSON path
MultiHeadRig read_rig_file(const std::string& file);
void write_rig_file(const MultiHeadRig& rig, const std::string& file);

// One image per head of the synthetic scene seen from `pose` (RGB; depth too when options.depth).
std::vector<cv::Mat> render_heads(const SyntheticScene& scene, const MultiHeadRig& rig, const PathFrame& pose,
                                  const RenderOptions& options, std::vector<cv::Mat>* depths = nullptr);

// ---- stitching to equirectangular
struct StitchOptions {
  int width = 2048, height = 1024;
  double feather = 0.15;  // fraction of the head's half-size over which its weight ramps up from the border
  double stitch_distance = 0.0;  // metres at which head offsets are compensated (0 = infinitely far)
  void check() const;            // throws Error naming the bad field
};
// Precomputed remap tables: build once per rig and size, stitch many frames.
struct StitchMaps {
  int width = 0, height = 0;
  std::vector<cv::Mat> map_x, map_y;  // CV_32F per head
  std::vector<cv::Mat> weight;        // CV_32F per head, normalized so they sum to 1 where covered
  cv::Mat coverage;                   // CV_8U: how many heads see each pixel
};
StitchMaps make_stitch_maps(const MultiHeadRig& rig, const StitchOptions& options = {});
// Feathered blend of the heads' images (CV_8UC3, sizes as in the rig) into an equirectangular panorama.
cv::Mat stitch_heads(const StitchMaps& maps, const std::vector<cv::Mat>& head_images);

// Parallax at the seams: where two or more heads overlap, how far apart (equirect pixels) the heads would
// place the scene point at the depth of `depth_panorama` (metres, as rendered at the rig's nodal point) once
// the stitch assumes `stitch_distance`. Zero for a rig without offsets.
struct SeamParallax {
  double mean_px = 0.0, max_px = 0.0;
  double overlap_fraction = 0.0;  // of the panorama's pixels seen by two or more heads
};
SeamParallax seam_parallax(const MultiHeadRig& rig, const cv::Mat& depth_panorama,
                           const StitchOptions& options);

// ---- cube maps (faces as in rig/spherical.h: front, back, left, right, up, down)
std::array<cv::Mat, 6> equirect_to_cube(const cv::Mat& equirect, int face_size);
cv::Mat cube_to_equirect(const std::array<cv::Mat, 6>& faces, int width, int height);

// Peak signal-to-noise ratio (dB) between two 8-bit images of the same size, over the mask (all if empty).
double psnr(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask = cv::Mat());

}  // namespace plenopath
