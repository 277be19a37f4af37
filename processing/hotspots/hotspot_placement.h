#pragma once
// Authoring a hotspot's quad: where the corners marked in one frame go in 3-D (the wall they lie on, else the
// frame's depth map, else a plane facing the camera, and which was used), how a corner dragged in any frame
// moves on the quad's plane, and in which frames the quad can be seen. The studio calls these; the
// geometry underneath is hotspot_geometry.h.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "model/hotspots.h"
#include "processing/hotspots/hotspot_geometry.h"
#include "rig/spherical.h"

namespace plenopath {

enum class HotspotPlacement {
  kWall,          // snapped to the plan's wall hit in the corners' direction
  kDepth,         // from the frame's depth map
  kFacingCamera,  // neither: a vertical plane facing the camera at fallback_distance_m
};
const char* to_string(HotspotPlacement placement);

struct HotspotPlacementOptions {
  HotspotLiftOptions lift;           // camera and wall height, depth spread tolerance
  double fallback_distance_m = 3.0;  // no wall and no depth: the quad's plane this far in front
  void check() const;                // throws Error naming the bad field
};

struct PlacedQuad {
  LiftedQuad quad;
  HotspotPlacement placement = HotspotPlacement::kWall;
  std::string message;  // what was done, for the status bar: "on the wall ...", "from depth", the fallback
};

// Places the corners (azimuth, elevation radians in frame `pose`). Tries the plan's walls; when no wall is
// hit or the wall lift warns, the depth map (CV_32F metres, may be empty); else the camera-facing plane.
// Throws Error only for unusable input (fewer than three corners, non-finite angles, a corner pointing away
// from every candidate plane).
PlacedQuad place_hotspot_quad(const std::vector<SphericalAngles>& corners, const PathFrame& pose,
                              const FloorPlan& plan, const cv::Mat& depth,
                              const HotspotPlacementOptions& options = {});

// Unit normal and centroid of the best plane through the points (at least three, not collinear).
struct Plane3 {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double rms_m = 0.0;  // rms distance of the points from it
};
Plane3 fit_plane(const std::vector<Eigen::Vector3d>& points);

// Where the ray at `angles` from frame `pose` meets the plane of `quad` (used when a corner handle is
// dragged in any frame). Throws Error when the ray is parallel to the plane or meets it behind the camera.
Eigen::Vector3d point_on_quad_plane(const std::vector<Eigen::Vector3d>& quad, const SphericalAngles& angles,
                                    const PathFrame& pose, double camera_height_m);

struct HotspotVisibilityOptions {
  double camera_height_m = 1.6;
  double max_distance_m = 15.0;  // farther quads are too small to matter
  void check() const;
};
// Whether the 3-D quad is seen from frame `pose`: its centre is in range and the sight line to it (ending
// 5 cm in front of the quad, so the quad's own wall does not count) crosses no occluder of the plan. With
// `authoring_pose` (the frame it was marked in) "in front" is that camera's side, and a camera behind the
// quad's plane does not see it.
bool hotspot_visible_from(const std::vector<Eigen::Vector3d>& quad, const PathFrame& pose,
                          const FloorPlan& plan, const HotspotVisibilityOptions& options = {},
                          const PathFrame* authoring_pose = nullptr);

// The path position to show a hotspot at: its authoring frame when it is on the path, else the position
// nearest `near_position` from which the quad is visible, else -1.
int position_to_show_hotspot(const Hotspot& hotspot, const CameraPath& path, const FloorPlan& plan,
                             int near_position, const HotspotVisibilityOptions& options = {});

// Camera height to use for a capture (its own when known, else the 1.6 m the renderer and player assume).
double camera_height_or_default(double capture_camera_height_m);

}  // namespace plenopath
