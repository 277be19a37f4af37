#include "model/hotspot_io.h"

#include "model/camera_path.h"
#include "model/error.h"

namespace plenopath {

nlohmann::json hotspot_to_json(const Hotspot& h) {
  nlohmann::json image = nlohmann::json::array(), world = nlohmann::json::array();
  for (const auto& c : h.image_corners) image.push_back({degrees(c.x()), degrees(c.y())});
  for (const auto& c : h.world_corners) world.push_back({c.x(), c.y(), c.z()});
  return {{"id", h.id},
          {"kind", to_string(h.kind)},
          {"title", h.title},
          {"media", h.media},
          {"frame", h.frame},
          {"image_corners_deg", image},
          {"world_corners", world},
          {"trigger", to_string(h.trigger)},
          {"trigger_distance_m", h.trigger_distance_m},
          {"action", to_string(h.action)},
          {"action_target", h.action_target}};
}

Hotspot hotspot_from_json(const JsonReader& j) {
  Hotspot h;
  h.id = j.string("id");
  h.kind = enum_from_json<HotspotKind>(j.at("kind"));
  h.title = j.string_or("title", "");
  h.media = j.string_or("media", "");
  h.frame = j.integer_or("frame", -1);
  if (auto corners = j.find("image_corners_deg"))
    for (std::size_t k = 0; k < corners->size(); ++k) {
      const JsonReader c = corners->at(k);
      if (c.size() != 2) c.fail("expected [azimuth, elevation] in degrees");
      h.image_corners.emplace_back(radians_of_written(c.at(0).number()),
                                   radians_of_written(c.at(1).number()));
    }
  if (auto corners = j.find("world_corners"))
    for (std::size_t k = 0; k < corners->size(); ++k) {
      const JsonReader c = corners->at(k);
      if (c.size() != 3) c.fail("expected [x, y, z]");
      h.world_corners.emplace_back(c.at(0).number(), c.at(1).number(), c.at(2).number());
    }
  h.trigger = enum_from_json(j, "trigger", HotspotTrigger::kClick);
  h.trigger_distance_m = j.number_or("trigger_distance_m", 0.0);
  h.action = enum_from_json(j, "action", HotspotAction::kNone);
  h.action_target = j.string_or("action_target", "");
  return h;
}

}  // namespace plenopath
