#pragma once
// The camera path for SLAM and photogrammetry tools. Both pose files of the package (trajectory.tum and
// OpenSfM's reconstruction.json) give each panorama camera the same axes, those of OpenCV, OpenSfM and
// stella_vslam's equirectangular camera: x to the right of the panorama's centre, y down, z forward (the
// centre column, azimuth 0). So x is azimuth +90 deg, which points along plan angle heading - 90 deg
// (ARCHITECTURE.md: azimuth grows clockwise seen from above), and y is plan -Z.
#include <Eigen/Core>
#include <string>

#include "model/project.h"

namespace plenopath {

// Rotation taking those camera axes to the world's (X right, Y up on the plan, Z up) for a camera whose
// panorama centre looks along world angle `heading` (radians, CCW from +X). Its columns are the camera's
// x, y, z in world coordinates.
Eigen::Matrix3d world_from_pano_camera(double heading);

// A keyframe's camera in the world of the photogrammetry files (OpenSfM, nerfstudio): with a valid
// geo-anchor the topocentric frame at the anchor (x east, y north, z up, metres on the ground), else the plan
// frame; the centre at the capture's camera height above the floor (z = 0).
struct WorldCamera {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double heading = 0.0;  // radians CCW from the world's +X
};
WorldCamera world_camera(const Project& project, const PathFrame& frame);

// TUM RGB-D trajectory, one line per path frame: "timestamp tx ty tz qx qy qz qw". The pose is the
// camera's in the plan frame (world_from_camera: position of the camera centre, orientation as a unit
// quaternion with qw >= 0), z the camera's height above the floor (0 when the capture does not know it);
// the timestamp is the frame's time in the capture, seconds. Lines beginning with '#' are comments, as
// the TUM tools and evo read them.
std::string tum_trajectory(const Project& project);

}  // namespace plenopath
