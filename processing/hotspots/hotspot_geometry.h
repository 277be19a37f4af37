#pragma once
// Hotspot geometry: a quad marked by four corners in one frame's panorama is lifted to a planar quad in
// 3-D (on the wall it lies on, from the plan, or from the frame's depth map), re-projected into any other
// frame, and media is warped onto it by the view's homography, so it stays on its wall as the viewer walks.
// World frame: the plan frame (x, y metres) with z up from the floor; the camera's nodal point is
// camera_height above the floor at the frame's (x, y).
#include <Eigen/Core>
#include <array>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "rig/spherical.h"

namespace plenopath {

struct LiftedQuad {
  std::vector<Eigen::Vector3d> corners;              // world frame, in the marked order
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, facing the camera that marked it
  double planarity_rms_m = 0.0;  // how far the unsnapped corners were from the fitted plane
  int wall_segment = -1;         // index into FloorPlan::segments when snapped to a wall
  std::string warning;           // e.g. corners that straddle two walls; empty when all is well
};

struct HotspotLiftOptions {
  double camera_height_m = 1.6;
  double wall_height_m = 2.8;  // corners above this are still accepted, with a warning
  double max_corner_spread_m =
      0.05;  // corners whose depth-lifted points leave the fitted plane by more: warn
  void check() const;
};

// Corners as (azimuth, elevation) radians in the frame `pose`. Snaps to the occluder wall hit by the ray
// through the corners' centre; throws Error when no wall is hit or a corner ray misses the wall's plane.
LiftedQuad lift_quad_to_wall(const std::vector<SphericalAngles>& corners, const PathFrame& pose,
                             const FloorPlan& plan, const HotspotLiftOptions& options = {});

// The same from the frame's depth map (CV_32F metres along the ray, 0 = no hit): each corner at its depth,
// then a least-squares plane through them and the corners projected onto it. Throws Error without depth.
LiftedQuad lift_quad_from_depth(const std::vector<SphericalAngles>& corners, const PathFrame& pose,
                                const cv::Mat& depth, const HotspotLiftOptions& options = {});

// Where a world point appears in the panorama of frame `pose` (equirect pixel coordinates, width x height).
Eigen::Vector2d project_to_equirect(const Eigen::Vector3d& world, const PathFrame& pose,
                                    double camera_height_m, int width, int height);
SphericalAngles direction_in_frame(const Eigen::Vector3d& world, const PathFrame& pose,
                                   double camera_height_m);

// A pinhole view from the frame's nodal point (as the panorama view and the player draw): looking at
// world yaw/pitch with a vertical field of view, width x height pixels.
struct PerspectiveView {
  double yaw = 0.0, pitch = 0.0, fov_y = 1.2;
  int width = 1280, height = 800;
};
// Pixel of a world point in that view (y down), or nullopt when behind the camera.
std::optional<Eigen::Vector2d> project_to_view(const Eigen::Vector3d& world, const PathFrame& pose,
                                               double camera_height_m, const PerspectiveView& view);
// The homography taking media coordinates (u, v) in [0, w_media] x [0, h_media] (corner 0 at (0, 0),
// corner 1 at (w, 0), corner 2 at (w, h), corner 3 at (0, h)) to view pixels. Throws when a corner is
// behind the camera.
cv::Matx33d media_to_view_homography(const std::vector<Eigen::Vector3d>& quad, const PathFrame& pose,
                                     double camera_height_m, const PerspectiveView& view,
                                     cv::Size media_size);

// Paints `media` onto the quad in an equirectangular frame (CV_8UC3, in place): each pixel's ray meets the
// quad's plane and, when inside the quad, takes the media's colour there (bilinear). Returns the number of
// pixels painted. The quad must be a planar parallelogram-like convex quad (corners in order).
int warp_media_into_equirect(cv::Mat& equirect, const cv::Mat& media,
                             const std::vector<Eigen::Vector3d>& quad, const PathFrame& pose,
                             double camera_height_m);

// How far apart the quad's corners marked in two frames lift (max corner distance, metres): a large value
// means the marks are not consistent with one plane seen from both.
double quad_consistency_m(const LiftedQuad& a, const LiftedQuad& b);

}  // namespace plenopath
