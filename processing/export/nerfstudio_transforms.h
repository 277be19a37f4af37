#pragma once
// The keyframes as a nerfstudio dataset (transforms.json beside images/), so NeRF and Gaussian-splatting
// tools train from the tour's own panoramas without solving their poses again.
//
// Conventions (nerfstudio's "Data conventions" page and its cameras.py): "transform_matrix" is
// camera-to-world with OpenGL camera axes, x right, y up, z back (the panorama's centre looks along -z);
// the world's up is +Z. The EQUIRECTANGULAR camera takes fl_x = w/2, fl_y = h, cx = w/2, cy = h/2 and a
// pixel centre (x, y) to theta = -pi (x - cx) / fl_x, phi = pi (1/2 + (y - cy) / fl_y), direction
// (-sin theta sin phi, cos phi, -cos theta sin phi): azimuth grows to the right, as ours does, and
// (x, y) are our continuous equirectangular coordinates. The world is that of world_camera()
// (trajectory_formats.h): the anchor's east/north/up when georeferenced, else the plan.
#include <nlohmann/json.hpp>
#include <vector>

#include "model/project.h"
#include "processing/export/tour_json.h"

namespace plenopath {

// transforms.json for the full keyframe JPEGs (`full_width` x `full_height`), one frame per keyframe image,
// "file_path" package-relative. Throws Error for a keyframe without a pose.
nlohmann::json nerfstudio_transforms(const Project& project, const std::vector<KeyframeImageFiles>& images,
                                     int full_width, int full_height);

}  // namespace plenopath
