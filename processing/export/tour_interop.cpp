#include "processing/export/tour_interop.h"

#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>

#include "model/error.h"
#include "rig/spherical.h"

namespace plenopath {
namespace {

std::string scene_id(int frame) { return "k" + std::to_string(frame); }

}  // namespace

nlohmann::json pannellum_config(const Project& project, const std::vector<KeyframeImageFiles>& images) {
  using nlohmann::json;
  // Scenes linked along the path: sort the keyframes by frame index.
  std::vector<const KeyframeImageFiles*> along;
  for (const auto& img : images) along.push_back(&img);
  std::sort(along.begin(), along.end(), [](auto* a, auto* b) { return a->frame < b->frame; });

  json scenes = json::object();
  for (std::size_t i = 0; i < along.size(); ++i) {
    const PathFrame* f = project.path.find_frame(along[i]->frame);
    if (!f) throw Error("keyframe " + std::to_string(along[i]->frame) + " has no pose in the path");
    json scene = {{"title", project.tour.title + " — frame " + std::to_string(f->index)},
                  {"type", "equirectangular"},
                  {"panorama", along[i]->full},
                  {"preview", along[i]->preview},
                  {"hotSpots", json::array()}};
    if (project.geo.valid) {
      // Compass bearing (clockwise from north) of the panorama's centre.
      const double enu_angle = f->heading + project.geo.plan_rotation;
      scene["northOffset"] = std::remainder(90.0 - degrees(enu_angle), 360.0);
    }
    for (std::size_t j : {i - 1, i + 1}) {
      if (j >= along.size()) continue;  // i - 1 wraps to a huge value at i = 0
      const PathFrame* g = project.path.find_frame(along[j]->frame);
      const double world = std::atan2(g->y - f->y, g->x - f->x);
      const double yaw = degrees(azimuth_of_world_angle(f->heading, world));
      scene["hotSpots"].push_back({{"pitch", -10.0},
                                   {"yaw", yaw},
                                   {"type", "scene"},
                                   {"text", j > i ? "Forward" : "Back"},
                                   {"sceneId", scene_id(g->index)},
                                   {"targetYaw", "sameAzimuth"}});
    }
    scenes[scene_id(f->index)] = scene;
  }
  const int first = images.empty() ? 0 : images.front().frame;
  return {{"default", {{"firstScene", scene_id(first)}, {"sceneFadeDuration", 600}, {"autoLoad", true}}},
          {"scenes", scenes}};
}

Eigen::Vector3d wgs84_from_plan(const GeoAnchor& anchor, const Eigen::Vector2d& plan) {
  const GeographicLib::LocalCartesian local(anchor.latitude_deg, anchor.longitude_deg, anchor.altitude_m);
  const Eigen::Vector2d enu = anchor.enu_from_plan(plan);
  double lat = 0, lon = 0, alt = 0;
  local.Reverse(enu.x(), enu.y(), 0.0, lat, lon, alt);
  return {lat, lon, alt};
}

nlohmann::json path_geojson(const Project& project) {
  using nlohmann::json;
  if (!project.geo.valid)
    throw Error("GeoJSON export needs a geo-anchor (latitude, longitude, plan rotation) in the project");
  auto lon_lat = [&](double x, double y) {
    const Eigen::Vector3d g = wgs84_from_plan(project.geo, {x, y});
    return json::array({g.y(), g.x()});  // GeoJSON order: longitude, latitude
  };
  json line = json::array();
  for (const PathFrame& f : project.path.frames) line.push_back(lon_lat(f.x, f.y));
  json features = json::array();
  features.push_back({{"type", "Feature"},
                      {"geometry", {{"type", "LineString"}, {"coordinates", line}}},
                      {"properties",
                       {{"name", project.tour.title},
                        {"kind", "path"},
                        {"frames", project.path.size()},
                        {"length_m", project.path.length()}}}});
  const std::vector<int> order = project.keyframes.progressive_order();
  for (std::size_t r = 0; r < order.size(); ++r) {
    const PathFrame* f = project.path.find_frame(order[r]);
    if (!f) continue;
    features.push_back(
        {{"type", "Feature"},
         {"geometry", {{"type", "Point"}, {"coordinates", lon_lat(f->x, f->y)}}},
         {"properties",
          {{"kind", "keyframe"}, {"frame", f->index}, {"rank", r}, {"heading_deg", degrees(f->heading)}}}});
  }
  return {{"type", "FeatureCollection"}, {"features", features}};
}

}  // namespace plenopath
