#include "processing/export/opensfm_reconstruction.h"

#include <Eigen/Geometry>

#include "model/error.h"
#include "processing/export/trajectory_formats.h"

namespace plenopath {
namespace {

constexpr const char* kCameraId = "plenopath spherical";

std::string shot_id(const std::string& package_path) {
  const std::string prefix = "images/";
  if (package_path.compare(0, prefix.size(), prefix) != 0)
    throw Error("OpenSfM export: keyframe image '" + package_path + "' is not under images/");
  return package_path.substr(prefix.size());
}

}  // namespace

nlohmann::json opensfm_reconstruction(const Project& project, const std::vector<KeyframeImageFiles>& images,
                                      int full_width, int full_height) {
  using nlohmann::json;
  const GeoAnchor& geo = project.geo;
  json shots = json::object();
  for (const KeyframeImageFiles& image : images) {
    const PathFrame* f = project.path.find_frame(image.frame);
    if (!f)
      throw Error("OpenSfM export: keyframe " + std::to_string(image.frame) + " has no pose in the path");
    const WorldCamera camera = world_camera(project, *f);
    const Eigen::Vector3d& centre = camera.centre;
    const Eigen::Matrix3d camera_from_world = world_from_pano_camera(camera.heading).transpose();
    const Eigen::AngleAxisd rotation(camera_from_world);
    const Eigen::Vector3d r = rotation.angle() * rotation.axis();
    const Eigen::Vector3d t = -camera_from_world * centre;
    json shot = {{"camera", kCameraId},
                 {"rotation", {r.x(), r.y(), r.z()}},
                 {"translation", {t.x(), t.y(), t.z()}},
                 {"orientation", 1}};  // EXIF orientation: the image is upright as stored
    if (geo.valid) shot["gps_position"] = {centre.x(), centre.y(), centre.z()};
    shots[shot_id(image.full)] = shot;
  }
  json reconstruction = {
      {"cameras",
       {{kCameraId, {{"projection_type", "spherical"}, {"width", full_width}, {"height", full_height}}}}},
      {"shots", shots},
      {"points", json::object()}};
  if (geo.valid)
    reconstruction["reference_lla"] = {
        {"latitude", geo.latitude_deg}, {"longitude", geo.longitude_deg}, {"altitude", geo.altitude_m}};
  return json::array({reconstruction});
}

std::vector<std::pair<std::string, std::string>> opensfm_files(const Project& project,
                                                               const std::vector<KeyframeImageFiles>& images,
                                                               int full_width, int full_height) {
  const nlohmann::json reconstruction = opensfm_reconstruction(project, images, full_width, full_height);
  std::vector<std::pair<std::string, std::string>> files = {
      {"reconstruction.json",
       reconstruction.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n"}};
  if (project.geo.valid)
    files.emplace_back("reference_lla.json", reconstruction[0]["reference_lla"].dump(1) + "\n");
  return files;
}

}  // namespace plenopath
