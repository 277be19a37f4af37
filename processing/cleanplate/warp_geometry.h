#pragma once
// What the clean plate and the rig finder share to warp one frame of a path onto another: which frames to
// take, and each pixel's ray in the plan's axes.
#include <Eigen/Core>
#include <vector>

#include "model/camera_path.h"

namespace plenopath {

// Path positions in the keyframe's piece with baselines in [min_m, max_m], both directions, 2 * each_side of
// them spread evenly over the lot (frames further apart in time see a walking person further away; near a
// path's end, the other side gives more).
std::vector<int> neighbours_within(const CameraPath& path, int key_position, double min_m, double max_m,
                                   int each_side);

// The unit ray of every pixel (row-major, w * h) of an equirectangular frame with this heading, in the
// plan's axes (x east, y north, z up).
std::vector<Eigen::Vector3f> plan_rays(double heading, int w, int h);

}  // namespace plenopath
