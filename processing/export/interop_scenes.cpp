#include "processing/export/interop_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "model/error.h"
#include "rig/spherical.h"

namespace plenopath {
namespace {

double camera_height(const Project& p) {
  return p.capture.camera_height_m > 0 ? p.capture.camera_height_m : 1.6;
}

// Proper crossing of segments pq and ab (touching at an end does not count).
bool crosses(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a,
             const Eigen::Vector2d& b) {
  auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p);
  const double d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

bool line_of_sight(const std::vector<PlanSegment>& occluders, const Eigen::Vector2d& from,
                   const Eigen::Vector2d& to) {
  // Stop 5 cm short: a hotspot on a wall must not be hidden by that wall.
  const Eigen::Vector2d d = to - from;
  const double n = d.norm();
  if (n < 0.05) return true;
  const Eigen::Vector2d end = to - d / n * 0.05;
  for (const PlanSegment& s : occluders)
    if (crosses(from, end, s.a, s.b)) return false;
  return true;
}

}  // namespace

std::string interop_scene_id(int frame) { return "k" + std::to_string(frame); }

std::vector<InteropScene> interop_scenes(const Project& project,
                                         const std::vector<KeyframeImageFiles>& images) {
  std::vector<const KeyframeImageFiles*> along;
  for (const auto& img : images) along.push_back(&img);
  std::sort(along.begin(), along.end(), [](auto* a, auto* b) { return a->frame < b->frame; });
  const double north_rotation = project.geo.valid ? project.geo.plan_rotation : 0.0;

  std::vector<InteropScene> scenes;
  std::vector<const PathFrame*> poses;
  for (const KeyframeImageFiles* img : along) {
    const PathFrame* f = project.path.find_frame(img->frame);
    if (!f) throw Error("keyframe " + std::to_string(img->frame) + " has no pose in the path");
    InteropScene s;
    s.frame = f->index;
    s.id = interop_scene_id(f->index);
    s.title = project.tour.title + " — frame " + std::to_string(f->index);
    s.images = img;
    s.x = f->x;
    s.y = f->y;
    s.heading_deg = degrees(f->heading);
    // The centre column looks along ENU angle heading + rotation (CCW from east); bearing = 90 deg - that.
    s.north_offset_deg = std::remainder(90.0 - degrees(f->heading + north_rotation), 360.0);
    scenes.push_back(s);
    poses.push_back(f);
  }

  const double height = camera_height(project);
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const PathFrame* f = poses[i];
    for (std::size_t j : {i - 1, i + 1}) {
      if (j >= scenes.size()) continue;  // i - 1 wraps to a huge value at i = 0
      const PathFrame* g = poses[j];
      const double distance = std::hypot(g->x - f->x, g->y - f->y);
      InteropLink link;
      link.target_frame = g->index;
      link.target_id = scenes[j].id;
      link.yaw_deg = degrees(azimuth_of_world_angle(f->heading, std::atan2(g->y - f->y, g->x - f->x)));
      // The floor under the neighbour, kept within the band where a viewer's arrows are seen.
      link.pitch_deg = std::clamp(-degrees(std::atan2(height, distance)), -35.0, -5.0);
      link.label = j > i ? "Forward" : "Back";
      scenes[i].links.push_back(link);
    }
  }

  const std::vector<PlanSegment> occluders = project.plan.occluder_segments();
  for (const Hotspot& h : project.hotspots) {
    InteropSpot spot;
    spot.id = h.id;
    spot.title = h.title;
    if (h.action == HotspotAction::kShowText) spot.text = h.action_target;
    if (h.action == HotspotAction::kOpenUrl) spot.url = h.action_target;
    if (h.action == HotspotAction::kJump) {
      char* end = nullptr;
      const long target = std::strtol(h.action_target.c_str(), &end, 10);
      if (end && *end == '\0' && !h.action_target.empty())
        for (const InteropScene& s : scenes)
          if (s.frame == target) spot.jump_frame = s.frame;
    }
    if (!h.world_corners.empty()) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (const Eigen::Vector3d& w : h.world_corners) c += w;
      c /= static_cast<double>(h.world_corners.size());
      for (std::size_t i = 0; i < scenes.size(); ++i) {
        const PathFrame* f = poses[i];
        if (!line_of_sight(occluders, f->position(), c.head<2>())) continue;
        const Eigen::Vector2d d = c.head<2>() - f->position();
        InteropSpot s = spot;
        s.yaw_deg = degrees(azimuth_of_world_angle(f->heading, std::atan2(d.y(), d.x())));
        s.pitch_deg = degrees(std::atan2(c.z() - height, d.norm()));
        scenes[i].spots.push_back(s);
      }
    } else if (!h.image_corners.empty() && !scenes.empty()) {
      const PathFrame* author = project.path.find_frame(h.frame);
      if (!author) continue;  // validate_hotspots has warned about it
      Eigen::Vector3d b = Eigen::Vector3d::Zero();
      for (const Eigen::Vector2d& c : h.image_corners) b += angles_to_bearing({c.x(), c.y()});
      const SphericalAngles centre = bearing_to_angles(b);
      std::size_t nearest = 0;
      for (std::size_t i = 1; i < scenes.size(); ++i)
        if (std::abs(scenes[i].frame - h.frame) < std::abs(scenes[nearest].frame - h.frame)) nearest = i;
      // Seen from the nearest keyframe along the same world direction (the author's frame and the
      // keyframe stand close together; where they coincide this is exact).
      const double world = world_angle_of_azimuth(author->heading, centre.azimuth);
      InteropSpot s = spot;
      s.yaw_deg = degrees(azimuth_of_world_angle(poses[nearest]->heading, world));
      s.pitch_deg = degrees(centre.elevation);
      scenes[nearest].spots.push_back(s);
    }
  }
  return scenes;
}

}  // namespace plenopath
