#include "processing/export/tour_interop.h"

#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>

#include "model/error.h"
#include "processing/export/interop_scenes.h"
#include "rig/spherical.h"

namespace plenopath {

nlohmann::json pannellum_config(const Project& project, const std::vector<KeyframeImageFiles>& images,
                                const CubeTileLayout* tiles) {
  using nlohmann::json;
  json scenes = json::object();
  for (const InteropScene& s : interop_scenes(project, images)) {
    json scene = {{"title", s.title}, {"northOffset", s.north_offset_deg}, {"hotSpots", json::array()}};
    if (tiles && !s.images->tiles.empty()) {
      // Pannellum's levels 1..n are ours; level 0 (one tile a face) is what it shows without WebGL.
      scene["type"] = "multires";
      scene["multiRes"] = {{"path", s.images->tiles + "/%l/%s/%y_%x"},
                           {"fallbackPath", s.images->tiles + "/0/%s/0_0"},
                           {"extension", "jpg"},
                           {"tileResolution", tiles->tile_size()},
                           {"maxLevel", tiles->max_level()},
                           {"cubeResolution", tiles->face_size()}};
    } else {
      scene["type"] = "equirectangular";
      scene["panorama"] = s.images->full;  // (the package's preview is a script: no Pannellum preview)
    }
    // With "sameAzimuth" Pannellum keeps northOffset + yaw across the change: the world direction.
    for (const InteropLink& l : s.links)
      scene["hotSpots"].push_back({{"pitch", l.pitch_deg},
                                   {"yaw", l.yaw_deg},
                                   {"type", "scene"},
                                   {"text", l.label},
                                   {"sceneId", l.target_id},
                                   {"targetYaw", "sameAzimuth"}});
    for (const InteropSpot& h : s.spots) {
      json spot = {{"id", h.id}, {"pitch", h.pitch_deg}, {"yaw", h.yaw_deg}};
      // Pannellum escapes "text" itself (escapeHTML), so titles stay plain text.
      const std::string text = h.text.empty() ? h.title : h.title + ": " + h.text;
      if (h.jump_frame >= 0) {
        spot.update({{"type", "scene"},
                     {"text", text},
                     {"sceneId", interop_scene_id(h.jump_frame)},
                     {"targetYaw", "sameAzimuth"}});
      } else {
        spot.update({{"type", "info"}, {"text", text}});
        if (!h.url.empty()) spot["URL"] = h.url;
      }
      scene["hotSpots"].push_back(spot);
    }
    scenes[s.id] = scene;
  }
  const int first = images.empty() ? 0 : images.front().frame;
  return {
      {"default", {{"firstScene", interop_scene_id(first)}, {"sceneFadeDuration", 600}, {"autoLoad", true}}},
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
