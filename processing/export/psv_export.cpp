#include "processing/export/psv_export.h"

#include <cmath>

#include "processing/export/interop_scenes.h"
#include "processing/export/plan_svg_frame.h"
#include "processing/export/tour_interop.h"

namespace plenopath {
namespace {

double rad(double deg) { return deg * M_PI / 180.0; }

// Viewer yaw (the bearing) of image azimuth `yaw_deg` in a scene, radians in [0, 2pi).
double bearing(const InteropScene& s, double yaw_deg) {
  double b = std::fmod(s.north_offset_deg + yaw_deg, 360.0);
  if (b < 0) b += 360.0;
  return rad(b);
}

}  // namespace

nlohmann::json psv_tour(const Project& project, const std::vector<KeyframeImageFiles>& images) {
  using nlohmann::json;
  const PlanSvgFrame map = plan_svg_frame(project.plan);
  json nodes = json::array();
  const std::vector<InteropScene> scenes = interop_scenes(project, images);
  for (const InteropScene& s : scenes) {
    const Eigen::Vector2d on_map = map.pixel({s.x, s.y});
    json node = {{"id", s.id},
                 {"name", "Frame " + std::to_string(s.frame)},
                 {"caption", s.title},
                 {"panorama", s.images->full},
                 // PSV turns the sphere by -pan: the image's centre (bearing north_offset) lands at yaw
                 // north_offset, so yaw = bearing everywhere.
                 {"sphereCorrection", {{"pan", -rad(s.north_offset_deg)}}},
                 // The keyframe JPEGs carry their own GPano pose heading (keyframe_metadata.h) for photo
                 // sites; PSV would turn the sphere by it too. The node's panoData takes its place.
                 {"panoData", {{"poseHeading", 0}, {"posePitch", 0}, {"poseRoll", 0}}},
                 {"map", {{"x", on_map.x()}, {"y", on_map.y()}}},
                 {"links", json::array()},
                 {"markers", json::array()}};
    if (project.geo.valid) {
      const Eigen::Vector3d g = wgs84_from_plan(project.geo, {s.x, s.y});
      node["gps"] = {g.y(), g.x(), g.z()};  // PSV order: longitude, latitude, altitude
    }
    for (const InteropLink& l : s.links)
      node["links"].push_back({{"nodeId", l.target_id},
                               {"position", {{"yaw", bearing(s, l.yaw_deg)}, {"pitch", rad(l.pitch_deg)}}}});
    for (const InteropSpot& h : s.spots) {
      if (h.jump_frame >= 0) {
        node["links"].push_back(
            {{"nodeId", interop_scene_id(h.jump_frame)},
             {"position", {{"yaw", bearing(s, h.yaw_deg)}, {"pitch", rad(h.pitch_deg)}}}});
        continue;
      }
      // The markers plugin reads "tooltip" and "content" as HTML: the title and text go in "data", for the
      // page to show as text.
      node["markers"].push_back({{"id", s.id + "-" + h.id},
                                 {"position", {{"yaw", bearing(s, h.yaw_deg)}, {"pitch", rad(h.pitch_deg)}}},
                                 {"circle", 12},
                                 {"data", {{"title", h.title}, {"text", h.text}, {"url", h.url}}}});
    }
    nodes.push_back(node);
  }
  int start = images.empty() ? 0 : images.front().frame;
  for (const KeyframeImageFiles& img : images)
    if (img.frame == project.tour.start_frame) start = img.frame;
  const Eigen::Vector2d centre = [&] {
    for (const InteropScene& s : scenes)
      if (s.frame == start) return map.pixel({s.x, s.y});
    return Eigen::Vector2d(map.width_px() / 2.0, map.height_px() / 2.0);
  }();
  // The map plugin draws plan.svg turned counter-clockwise by yaw + rotation (radians), so that the view
  // points up. Yaw is the bearing; on plan.svg (plan +Y up) north lies plan_rotation clockwise from up, so
  // rotation = plan_rotation brings north up at yaw 0.
  const double rotation = project.geo.valid ? project.geo.plan_rotation : 0.0;
  return {{"startNodeId", interop_scene_id(start)},
          {"positionMode", "manual"},
          {"nodes", nodes},
          {"map",
           {{"imageUrl", "plan.svg"},
            {"size", {{"width", map.width_px()}, {"height", map.height_px()}}},
            {"center", {{"x", centre.x()}, {"y", centre.y()}}},
            {"rotation", rotation}}}};
}

}  // namespace plenopath
