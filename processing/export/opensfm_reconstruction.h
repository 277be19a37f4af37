#pragma once
// The keyframes as an OpenSfM reconstruction (doc/source/dataset.rst and geometry.rst of OpenSfM), so the
// package opens as an OpenSfM dataset: images/ holds the shots, reconstruction.json their poses, each a
// spherical camera. OpenSfM, and OpenDroneMap, Meshroom or a NeRF/splatting importer reading it, can then
// densify, mesh or train from the tour's own images without solving the poses again.
//
// Conventions (OpenSfM's): a shot's pose takes world coordinates to camera coordinates, x_cam = R x + t,
// "rotation" the angle-axis vector of R; camera axes x right, y down, z forward (trajectory_formats.h).
// The spherical camera maps x_cam to lon = atan2(x, z), lat = atan2(-y, hypot(x, z)), normalised image
// coordinates (lon / 2pi, -lat / 2pi) times max(width, height), origin at the image centre; with the
// pixel centre convention of OpenSfM (the top-left pixel's centre at (0, 0)) this is exactly ours:
// lon is our azimuth, lat our elevation.
//
// The world: with a valid geo-anchor, OpenSfM's topocentric frame (x east, y north, z up, metres) at the
// anchor, whose latitude/longitude/altitude are the reconstruction's reference_lla (also written as
// reference_lla.json, where older OpenSfM reads it); without one, the plan frame (X right, Y up, Z up).
// The camera centre is at the capture's camera height above the floor (z = 0).
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "model/project.h"
#include "processing/export/tour_json.h"

namespace plenopath {

// reconstruction.json: [ {cameras: {one spherical camera of the full images' size}, shots: {file name under
// images/: {camera, rotation, translation, capture_time?}}, points: {}, reference_lla?} ].
// `full_width` x `full_height` is the size of the full keyframe JPEGs the shots name.
nlohmann::json opensfm_reconstruction(const Project& project, const std::vector<KeyframeImageFiles>& images,
                                      int full_width, int full_height);

// The package files: reconstruction.json, and reference_lla.json when georeferenced.
std::vector<std::pair<std::string, std::string>> opensfm_files(const Project& project,
                                                               const std::vector<KeyframeImageFiles>& images,
                                                               int full_width, int full_height);

}  // namespace plenopath
