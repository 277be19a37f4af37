#include "processing/export/nerfstudio_transforms.h"

#include "model/error.h"
#include "processing/export/trajectory_formats.h"

namespace plenopath {

nlohmann::json nerfstudio_transforms(const Project& project, const std::vector<KeyframeImageFiles>& images,
                                     int full_width, int full_height) {
  using nlohmann::json;
  json frames = json::array();
  for (const KeyframeImageFiles& image : images) {
    const PathFrame* f = project.path.find_frame(image.frame);
    if (!f)
      throw Error("nerfstudio export: keyframe " + std::to_string(image.frame) + " has no pose in the path");
    const WorldCamera camera = world_camera(project, *f);
    // OpenGL axes from ours (x right, y down, z forward): y and z flip.
    Eigen::Matrix3d rotation = world_from_pano_camera(camera.heading);
    rotation.col(1) = -rotation.col(1);
    rotation.col(2) = -rotation.col(2);
    json matrix = json::array();
    for (int r = 0; r < 3; ++r)
      matrix.push_back({rotation(r, 0), rotation(r, 1), rotation(r, 2), camera.centre(r)});
    matrix.push_back({0.0, 0.0, 0.0, 1.0});
    frames.push_back({{"file_path", image.full}, {"transform_matrix", matrix}, {"frame", f->index}});
  }
  return {{"camera_model", "EQUIRECTANGULAR"},
          {"fl_x", full_width / 2.0},
          {"fl_y", static_cast<double>(full_height)},
          {"cx", full_width / 2.0},
          {"cy", full_height / 2.0},
          {"w", full_width},
          {"h", full_height},
          {"frames", frames}};
}

}  // namespace plenopath
