#include "processing/export/tour_json.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "model/error.h"
#include "model/hotspot_io.h"
#include "model/json_reader.h"
#include "processing/export/tour_export.h"
#include "processing/walk/walk_route.h"

namespace plenopath {
namespace {

using nlohmann::json;

json cell_json(const VisibilityCell& c) {
  return {{"first_frame", c.first_frame}, {"last_frame", c.last_frame},
          {"s_begin", c.s_begin},         {"s_end", c.s_end},
          {"length", c.length},           {"area_mid", c.area_mid},
          {"area_mean", c.area_mean}};
}

}  // namespace

json make_tour_json(const Project& project, const std::vector<KeyframeImageFiles>& images,
                    const std::vector<HotspotMediaFile>& media, int full_width, int preview_width) {
  const CameraPath& path = project.path;
  const std::vector<double> s = path.arc_lengths();

  // Stills metres apart: between two whose straight line crosses a wall, the walkable route (through the
  // door) as waypoints of index -1, their s spread over the two stills' own, so every s stays as it was.
  std::optional<WalkRouter> router;
  if (project.capture.stills && !project.plan.occluder_segments().empty()) router.emplace(project.plan);
  json frames = json::array();
  for (std::size_t i = 0; i < path.frames.size(); ++i) {
    const PathFrame& f = path.frames[i];
    frames.push_back({f.index, f.x, f.y, degrees(f.heading), s[i]});
    if (!router || i + 1 >= path.frames.size() || path.frames[i + 1].piece != f.piece) continue;
    const std::vector<Eigen::Vector2d> route = router->route(f.position(), path.frames[i + 1].position());
    if (route.size() <= 2) continue;
    double total = 0.0;
    for (std::size_t k = 1; k < route.size(); ++k) total += (route[k] - route[k - 1]).norm();
    double along = 0.0;
    for (std::size_t k = 1; k + 1 < route.size(); ++k) {
      along += (route[k] - route[k - 1]).norm();
      const Eigen::Vector2d d = route[k + 1] - route[k];
      frames.push_back({-1, route[k].x(), route[k].y(), degrees(std::atan2(d.y(), d.x())),
                        s[i] + (s[i + 1] - s[i]) * along / total});
    }
  }

  std::map<int, std::size_t> position_of_frame;
  for (std::size_t i = 0; i < path.frames.size(); ++i) position_of_frame[path.frames[i].index] = i;
  std::map<int, int> rank_of_frame;
  const std::vector<int> order = project.keyframes.progressive_order();
  for (std::size_t r = 0; r < order.size(); ++r) rank_of_frame[order[r]] = static_cast<int>(r);

  json keyframes = json::array();
  for (const KeyframeImageFiles& img : images) {  // images come in progressive order
    auto it = position_of_frame.find(img.frame);
    if (it == position_of_frame.end())
      throw Error("keyframe " + std::to_string(img.frame) + " has no pose in the path");
    const PathFrame& f = path.frames[it->second];
    json k = {{"frame", f.index},
              {"rank", rank_of_frame.at(f.index)},
              {"x", f.x},
              {"y", f.y},
              {"heading_deg", degrees(f.heading)},
              {"s", s[it->second]},
              {"preview", img.preview},
              {"full", img.full}};
    if (!img.tiles.empty()) k["tiles"] = img.tiles;
    keyframes.push_back(std::move(k));
  }

  json cells = json::array();
  for (const VisibilityCell& c : project.visibility.cells) cells.push_back(cell_json(c));

  const FloorPlan& plan = project.plan;
  json layers = json::array(), lines = json::array(), labels = json::array();
  std::map<std::string, int> layer_index;
  for (const PlanLayer& l : plan.layers) {
    layer_index[l.name] = static_cast<int>(layers.size());
    layers.push_back(
        {{"name", l.name}, {"color", l.color}, {"occluder", l.occluder}, {"visible", l.visible}});
  }
  for (const PlanSegment& seg : plan.segments) {
    if (!layer_index.count(seg.layer)) {  // segments on a layer the plan does not list still get one
      layer_index[seg.layer] = static_cast<int>(layers.size());
      layers.push_back({{"name", seg.layer}, {"color", 7}, {"occluder", seg.occluder}, {"visible", true}});
    }
    lines.push_back({seg.a.x(), seg.a.y(), seg.b.x(), seg.b.y(), layer_index[seg.layer]});
  }
  for (const PlanLabel& l : plan.labels)
    labels.push_back({{"x", l.position.x()}, {"y", l.position.y()}, {"text", l.text}, {"height", l.height}});
  const PlanExtents e = plan.extents();
  json extents =
      e.valid ? json{{"min", {e.min.x(), e.min.y()}}, {"max", {e.max.x(), e.max.y()}}} : json(nullptr);

  std::map<std::string, const HotspotMediaFile*> media_of;
  for (const HotspotMediaFile& m : media) media_of[m.id] = &m;
  json hotspots = json::array();
  for (const Hotspot& h : project.hotspots) {
    // The package's copies of the media replace the author's paths.
    const HotspotMediaFile* m = media_of.count(h.id) ? media_of[h.id] : nullptr;
    json j = hotspot_to_json(h);
    j["media"] = m ? m->media : std::string();
    if (m && !m->action_media.empty()) j["action_target"] = m->action_media;
    hotspots.push_back(std::move(j));
  }

  json geo = nullptr;
  if (project.geo.valid) {
    const GeoAnchor& g = project.geo;
    geo = {{"latitude_deg", g.latitude_deg},
           {"longitude_deg", g.longitude_deg},
           {"altitude_m", g.altitude_m},
           {"plan_rotation_deg", degrees(g.plan_rotation)},
           {"scale", g.scale},
           {"plan_origin", {g.plan_origin.x(), g.plan_origin.y()}}};
  }

  int start_frame = project.tour.start_frame;
  if (start_frame < 0 || !position_of_frame.count(start_frame))
    start_frame = project.keyframes.indices.empty() ? (path.empty() ? 0 : path.frames.front().index)
                                                    : project.keyframes.indices.front();

  return {
      {"format", kTourFormatName},
      {"version", kTourFormatVersion},
      {"generator", std::string("Plenopath Studio ") + PLENOPATH_VERSION},
      {"title", project.tour.title},
      {"description", project.tour.description},
      {"units", "m"},
      {"camera_height_m", project.capture.camera_height_m > 0 ? project.capture.camera_height_m : 1.6},
      {"image",
       {{"projection", "equirectangular"}, {"full_width", full_width}, {"preview_width", preview_width}}},
      {"start_frame", start_frame},
      {"path",
       {{"columns", {"index", "x", "y", "heading_deg", "s"}},
        {"frames", frames},
        {"length_m", s.empty() ? 0.0 : s.back()}}},
      {"keyframes", keyframes},
      {"cells", cells},
      {"plan",
       {{"svg", "plan.svg"}, {"extents", extents}, {"layers", layers}, {"lines", lines}, {"labels", labels}}},
      {"hotspots", hotspots},
      {"geo_anchor", geo}};
}

Project project_from_tour_json(const json& tour, const std::string& file) {
  const JsonReader r(tour, file);
  if (!tour.is_object() || r.string_or("format", "") != kTourFormatName)
    r.fail(std::string("not a Plenopath tour (\"format\" must be \"") + kTourFormatName + "\")");
  const int version = r.integer("version");
  if (version > kTourFormatVersion)
    r.at("version").fail("tour format version " + std::to_string(version) +
                         " is newer than this build reads (" + std::to_string(kTourFormatVersion) + ")");
  Project p;
  p.tour.title = r.string("title");
  p.tour.description = r.string_or("description", "");
  p.capture.camera_height_m = r.number_or("camera_height_m", 0.0);

  const JsonReader frames = r.at("path").at("frames");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const JsonReader f = frames.at(i);
    if (f.size() < 4) f.fail("expected [index, x, y, heading_deg, s]");
    if (f.at(0).integer() < 0) continue;  // a waypoint of the walkable route between stills
    PathFrame frame;
    frame.index = f.at(0).integer();
    frame.x = f.at(1).number();
    frame.y = f.at(2).number();
    frame.heading = radians_of_written(f.at(3).number());
    p.path.frames.push_back(frame);
  }

  const JsonReader keyframes = r.at("keyframes");
  std::vector<std::pair<int, int>> frame_rank;
  for (std::size_t i = 0; i < keyframes.size(); ++i)
    frame_rank.emplace_back(keyframes.at(i).integer("frame"), keyframes.at(i).integer("rank"));
  std::sort(frame_rank.begin(), frame_rank.end());
  for (auto [frame, rank] : frame_rank) {
    p.keyframes.indices.push_back(frame);
    p.keyframes.rank.push_back(rank);
  }

  if (auto cells = r.find("cells"))
    for (std::size_t i = 0; i < cells->size(); ++i) {
      const JsonReader c = cells->at(i);
      p.visibility.cells.push_back({c.integer("first_frame"), c.integer("last_frame"), c.number("s_begin"),
                                    c.number("s_end"), c.number("length"), c.number("area_mid"),
                                    c.number("area_mean")});
    }

  const JsonReader plan = r.at("plan");
  const JsonReader layers = plan.at("layers");
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const JsonReader l = layers.at(i);
    PlanLayer layer;
    layer.name = l.string("name");
    layer.color = l.integer_or("color", 7);
    layer.occluder = l.boolean_or("occluder", false);
    layer.visible = l.boolean_or("visible", true);
    p.plan.layers.push_back(layer);
  }
  const JsonReader lines = plan.at("lines");
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const JsonReader l = lines.at(i);
    if (l.size() != 5) l.fail("expected [x1, y1, x2, y2, layer_index]");
    const int layer = l.at(4).integer();
    if (layer < 0 || layer >= static_cast<int>(p.plan.layers.size())) l.at(4).fail("no such layer");
    const PlanLayer& pl = p.plan.layers[static_cast<std::size_t>(layer)];
    p.plan.segments.push_back(
        {{l.at(0).number(), l.at(1).number()}, {l.at(2).number(), l.at(3).number()}, pl.name, pl.occluder});
  }
  if (auto labels = plan.find("labels"))
    for (std::size_t i = 0; i < labels->size(); ++i) {
      const JsonReader l = labels->at(i);
      p.plan.labels.push_back(
          {{l.number("x"), l.number("y")}, l.string("text"), l.number_or("height", 0.0), ""});
    }

  const JsonReader hotspots = r.at("hotspots");
  for (std::size_t i = 0; i < hotspots.size(); ++i) p.hotspots.push_back(hotspot_from_json(hotspots.at(i)));

  if (auto g = r.find("geo_anchor")) {
    p.geo.valid = true;
    p.geo.latitude_deg = g->number("latitude_deg");
    p.geo.longitude_deg = g->number("longitude_deg");
    p.geo.altitude_m = g->number_or("altitude_m", 0.0);
    p.geo.plan_rotation = radians_of_written(g->number_or("plan_rotation_deg", 0.0));
    p.geo.scale = g->number_or("scale", 1.0);
    const JsonReader o = g->at("plan_origin");
    p.geo.plan_origin = {o.at(0).number(), o.at(1).number()};
  }
  p.tour.start_frame = r.integer_or("start_frame", -1);
  return p;
}

}  // namespace plenopath
