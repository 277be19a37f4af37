#include "model/project_io.h"

#include <cmath>
#include <filesystem>
#include <optional>

#include "model/anchors_io.h"
#include "model/atomic_file.h"
#include "model/error.h"
#include "model/hotspot_io.h"
#include "model/json_reader.h"
#include "model/path_io.h"

namespace plenopath {
namespace {

using nlohmann::json;

json vec2(const Eigen::Vector2d& v) { return json::array({v.x(), v.y()}); }

Eigen::Vector2d read_vec2(const JsonReader& r) {
  if (r.size() != 2) r.fail("expected [x, y]");
  return {r.at(0).number(), r.at(1).number()};
}

// ---- floor plan
json plan_to_json(const FloorPlan& plan, const std::string& base) {
  json layers = json::array(), segments = json::array(), outlines = json::array(), labels = json::array();
  for (const auto& l : plan.layers)
    layers.push_back({{"name", l.name},
                      {"color", l.color},
                      {"visible", l.visible},
                      {"occluder", l.occluder},
                      {"entity_count", l.entity_count}});
  for (const auto& s : plan.segments)
    segments.push_back({{"a", vec2(s.a)}, {"b", vec2(s.b)}, {"layer", s.layer}, {"occluder", s.occluder}});
  for (const auto& o : plan.outlines) {
    json points = json::array();
    for (const auto& p : o.points) points.push_back(vec2(p));
    outlines.push_back({{"points", points}, {"layer", o.layer}, {"closed", o.closed}});
  }
  for (const auto& l : plan.labels)
    labels.push_back(
        {{"position", vec2(l.position)}, {"text", l.text}, {"height", l.height}, {"layer", l.layer}});
  return {{"source_file", path_relative_to(plan.source_file, base)},
          {"units", plan.units},
          {"metres_per_unit", plan.metres_per_unit},
          {"dxf_origin_m", vec2(plan.dxf_origin_m)},
          {"layers", layers},
          {"segments", segments},
          {"outlines", outlines},
          {"labels", labels}};
}

FloorPlan plan_from_json(const JsonReader& r, const std::string& base) {
  FloorPlan plan;
  plan.source_file = path_resolved_against(r.string_or("source_file", ""), base);
  plan.units = r.string_or("units", "m");
  plan.metres_per_unit = r.number_or("metres_per_unit", 1.0);
  if (plan.metres_per_unit <= 0) r.at("metres_per_unit").fail("must be > 0");
  if (auto origin = r.find("dxf_origin_m")) plan.dxf_origin_m = read_vec2(*origin);
  if (auto layers = r.find("layers"))
    for (std::size_t i = 0; i < layers->size(); ++i) {
      const JsonReader l = layers->at(i);
      plan.layers.push_back({l.string("name"), l.integer_or("color", 7), l.boolean_or("visible", true),
                             l.boolean_or("occluder", false), l.integer_or("entity_count", 0)});
    }
  if (auto segments = r.find("segments"))
    for (std::size_t i = 0; i < segments->size(); ++i) {
      const JsonReader s = segments->at(i);
      plan.segments.push_back({read_vec2(s.at("a")), read_vec2(s.at("b")), s.string_or("layer", ""),
                               s.boolean_or("occluder", false)});
    }
  if (auto outlines = r.find("outlines"))
    for (std::size_t i = 0; i < outlines->size(); ++i) {
      const JsonReader o = outlines->at(i);
      PlanOutline outline;
      const JsonReader points = o.at("points");
      for (std::size_t k = 0; k < points.size(); ++k) outline.points.push_back(read_vec2(points.at(k)));
      outline.layer = o.string_or("layer", "");
      outline.closed = o.boolean_or("closed", true);
      plan.outlines.push_back(std::move(outline));
    }
  if (auto labels = r.find("labels"))
    for (std::size_t i = 0; i < labels->size(); ++i) {
      const JsonReader l = labels->at(i);
      plan.labels.push_back({read_vec2(l.at("position")), l.string("text"), l.number_or("height", 0.0),
                             l.string_or("layer", "")});
    }
  return plan;
}

// ---- capture
json capture_to_json(const Capture& c, const std::string& base) {
  json gps = json::array();
  for (const auto& g : c.gps_track)
    gps.push_back(
        {{"t", g.time_s}, {"lat", g.latitude_deg}, {"lon", g.longitude_deg}, {"alt", g.altitude_m}});
  json out = {{"kind", to_string(c.kind)},
              {"source", path_relative_to(c.source, base)},
              {"frame_count", c.frame_count},
              {"width", c.width},
              {"height", c.height},
              {"frame_rate", c.frame_rate},
              {"first_frame", c.first_frame},
              {"stride", c.stride},
              {"frame_names", c.frame_names},
              {"depth_folder", path_relative_to(c.depth_folder, base)},
              {"gps_track", gps},
              {"gps_time_offset_s", c.gps_time_offset_s},
              {"camera_height_m", c.camera_height_m}};
  if (!c.rig_mask.empty()) out["rig_mask"] = path_relative_to(c.rig_mask, base);
  if (c.stills) out["stills"] = true;
  if (!c.frame_times_s.empty()) out["frame_times_s"] = c.frame_times_s;  // variable-rate video only
  return out;
}

Capture capture_from_json(const JsonReader& r, const std::string& base) {
  Capture c;
  try {
    c.kind = capture_kind_from_string(r.string_or("kind", "none"));
  } catch (const Error& e) {
    r.at("kind").fail(e.what());
  }
  c.source = path_resolved_against(r.string_or("source", ""), base);
  c.frame_count = r.integer_or("frame_count", 0);
  if (c.frame_count < 0) r.at("frame_count").fail("must be >= 0");
  c.width = r.integer_or("width", 0);
  c.height = r.integer_or("height", 0);
  c.frame_rate = r.number_or("frame_rate", 30.0);
  if (c.frame_rate <= 0) r.at("frame_rate").fail("must be > 0");
  c.first_frame = r.integer_or("first_frame", 0);
  c.stride = r.integer_or("stride", 1);
  if (c.stride < 1) r.at("stride").fail("must be >= 1");
  if (auto names = r.find("frame_names"))
    for (std::size_t i = 0; i < names->size(); ++i) c.frame_names.push_back(names->at(i).string());
  if (auto times = r.find("frame_times_s")) {
    if (times->size() != static_cast<std::size_t>(c.frame_count))
      times->fail("has " + std::to_string(times->size()) + " times for " + std::to_string(c.frame_count) +
                  " frames");
    for (std::size_t i = 0; i < times->size(); ++i) {
      const double t = times->at(i).number();
      if (!std::isfinite(t) || (i > 0 && !(t > c.frame_times_s.back())))
        times->at(i).fail("must be a finite time after the previous frame's");
      c.frame_times_s.push_back(t);
    }
  }
  c.depth_folder = path_resolved_against(r.string_or("depth_folder", ""), base);
  c.rig_mask = path_resolved_against(r.string_or("rig_mask", ""), base);
  if (auto stills = r.find("stills")) c.stills = stills->boolean();
  if (auto gps = r.find("gps_track"))
    for (std::size_t i = 0; i < gps->size(); ++i) {
      const JsonReader g = gps->at(i);
      c.gps_track.push_back({g.number("t"), g.number("lat"), g.number("lon"), g.number_or("alt", 0.0)});
    }
  c.gps_time_offset_s = r.number_or("gps_time_offset_s", 0.0);
  c.camera_height_m = r.number_or("camera_height_m", 0.0);
  return c;
}

// ---- anchors, visibility, keyframes, hotspots, geo, tour
json visibility_to_json(const VisibilityCells& v) {
  json events = json::array(), cells = json::array(), lines = json::array();
  for (const auto& e : v.events) events.push_back({{"frame", e.frame}, {"s", e.s}});
  for (const auto& c : v.cells)
    cells.push_back({{"first_frame", c.first_frame},
                     {"last_frame", c.last_frame},
                     {"s_begin", c.s_begin},
                     {"s_end", c.s_end},
                     {"length", c.length},
                     {"area_mid", c.area_mid},
                     {"area_mean", c.area_mean}});
  for (const auto& l : v.critical_lines) lines.push_back({vec2(l.a), vec2(l.b)});
  return {{"events", events}, {"cells", cells}, {"critical_lines", lines}};
}

VisibilityCells visibility_from_json(const JsonReader& r) {
  VisibilityCells v;
  if (auto events = r.find("events"))
    for (std::size_t i = 0; i < events->size(); ++i)
      v.events.push_back({events->at(i).integer("frame"), events->at(i).number("s")});
  if (auto cells = r.find("cells"))
    for (std::size_t i = 0; i < cells->size(); ++i) {
      const JsonReader c = cells->at(i);
      v.cells.push_back({c.integer("first_frame"), c.integer("last_frame"), c.number("s_begin"),
                         c.number("s_end"), c.number("length"), c.number("area_mid"), c.number("area_mean")});
    }
  if (auto lines = r.find("critical_lines"))
    for (std::size_t i = 0; i < lines->size(); ++i) {
      const JsonReader l = lines->at(i);
      if (l.size() != 2) l.fail("expected [[x, y], [x, y]]");
      v.critical_lines.push_back({read_vec2(l.at(0)), read_vec2(l.at(1))});
    }
  return v;
}

json keyframes_to_json(const Keyframes& k) {
  const SamplingParameters& p = k.parameters;
  const SamplerSettings& s = k.sampler;
  return {{"indices", k.indices},
          {"rank", k.rank},
          {"pinned", k.pinned},
          {"parameters",
           {{"method", to_string(p.method)},
            {"rule", to_string(p.rule)},
            {"count", p.count},
            {"ratio", p.ratio},
            {"exponent", p.exponent},
            {"transition_boost", p.transition_boost},
            {"min_spacing_m", p.min_spacing_m},
            {"max_spacing_m", p.max_spacing_m}}},
          {"sampler",
           {{"expected_loss",
             {{"probe_spacing_m", s.expected_loss.probe_spacing_m},
              {"loss_power", s.expected_loss.loss_power},
              {"density_floor", s.expected_loss.density_floor}}},
            {"refinement",
             {{"applied", s.refinement.applied},
              {"sweeps", s.refinement.sweeps},
              {"raster_cell_m", s.refinement.raster_cell_m}}},
            {"cell_rule",
             {{"transition_window_m", s.cell_rule.transition_window_m}, {"min_size", s.cell_rule.min_size}}},
            {"depth_changes",
             {{"log_ratio_threshold", s.depth_changes.log_ratio_threshold},
              {"use_mean_range", s.depth_changes.use_mean_range},
              {"min_coverage", s.depth_changes.min_coverage},
              {"max_depth_width", s.depth_changes.max_depth_width}}}}}};
}

// Version 1 files record neither the rule nor the sampler's settings: they read as the defaults of that
// version (rule expected_loss; the samplers' default settings, with the refinement the method applied by
// default: expected_loss and depth refined by loss).
SamplerSettings sampler_settings_from_json(const std::optional<JsonReader>& r, const SamplingParameters& p) {
  SamplerSettings s;
  s.refinement.applied = p.method != SamplingMethod::kUniform &&
                         !(p.method == SamplingMethod::kVisibility && p.rule == VisibilityRule::cell_rule);
  if (!r) return s;
  if (auto e = r->find("expected_loss")) {
    s.expected_loss.probe_spacing_m = e->number_or("probe_spacing_m", s.expected_loss.probe_spacing_m);
    s.expected_loss.loss_power = e->number_or("loss_power", s.expected_loss.loss_power);
    s.expected_loss.density_floor = e->number_or("density_floor", s.expected_loss.density_floor);
  }
  if (auto e = r->find("refinement")) {
    s.refinement.applied = e->boolean_or("applied", s.refinement.applied);
    s.refinement.sweeps = e->integer_or("sweeps", s.refinement.sweeps);
    s.refinement.raster_cell_m = e->number_or("raster_cell_m", s.refinement.raster_cell_m);
  }
  if (auto e = r->find("cell_rule")) {
    s.cell_rule.transition_window_m = e->number_or("transition_window_m", s.cell_rule.transition_window_m);
    s.cell_rule.min_size = e->number_or("min_size", s.cell_rule.min_size);
  }
  if (auto e = r->find("depth_changes")) {
    DepthChangeSettings& d = s.depth_changes;
    d.log_ratio_threshold = e->number_or("log_ratio_threshold", d.log_ratio_threshold);
    d.use_mean_range = e->boolean_or("use_mean_range", d.use_mean_range);
    d.min_coverage = e->number_or("min_coverage", d.min_coverage);
    d.max_depth_width = e->integer_or("max_depth_width", d.max_depth_width);
  }
  return s;
}

std::vector<int> read_int_list(const JsonReader& r) {
  std::vector<int> out;
  for (std::size_t i = 0; i < r.size(); ++i) out.push_back(r.at(i).integer());
  return out;
}

Keyframes keyframes_from_json(const JsonReader& r) {
  Keyframes k;
  if (auto v = r.find("indices")) k.indices = read_int_list(*v);
  if (auto v = r.find("rank")) k.rank = read_int_list(*v);
  if (auto v = r.find("pinned")) k.pinned = read_int_list(*v);
  if (!k.rank.empty() && k.rank.size() != k.indices.size())
    r.at("rank").fail("must have one entry per keyframe index");
  if (auto p = r.find("parameters")) {
    SamplingParameters& s = k.parameters;
    s.method = enum_from_json(*p, "method", s.method);
    s.rule = enum_from_json(*p, "rule", s.rule);
    s.count = p->integer_or("count", s.count);
    s.ratio = p->number_or("ratio", s.ratio);
    s.exponent = p->number_or("exponent", s.exponent);
    s.transition_boost = p->number_or("transition_boost", s.transition_boost);
    s.min_spacing_m = p->number_or("min_spacing_m", s.min_spacing_m);
    s.max_spacing_m = p->number_or("max_spacing_m", s.max_spacing_m);
  }
  k.sampler = sampler_settings_from_json(r.find("sampler"), k.parameters);
  return k;
}

json hotspots_to_json(const std::vector<Hotspot>& hotspots, const std::string& base) {
  json out = json::array();
  for (const auto& h : hotspots) {
    json j = hotspot_to_json(h);
    j["media"] = path_relative_to(h.media, base);
    if (hotspot_action_uses_media(h.action)) j["action_target"] = path_relative_to(h.action_target, base);
    out.push_back(std::move(j));
  }
  return out;
}

std::vector<Hotspot> hotspots_from_json(const JsonReader& r, const std::string& base) {
  std::vector<Hotspot> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    Hotspot h = hotspot_from_json(r.at(i));
    h.media = path_resolved_against(h.media, base);
    if (hotspot_action_uses_media(h.action)) h.action_target = path_resolved_against(h.action_target, base);
    out.push_back(std::move(h));
  }
  return out;
}

json geo_to_json(const GeoAnchor& g) {
  return {{"valid", g.valid},
          {"latitude_deg", g.latitude_deg},
          {"longitude_deg", g.longitude_deg},
          {"altitude_m", g.altitude_m},
          {"plan_rotation_deg", degrees(g.plan_rotation)},
          {"scale", g.scale},
          {"plan_origin", vec2(g.plan_origin)}};
}

GeoAnchor geo_from_json(const JsonReader& r) {
  GeoAnchor g;
  g.valid = r.boolean_or("valid", false);
  g.latitude_deg = r.number_or("latitude_deg", 0.0);
  g.longitude_deg = r.number_or("longitude_deg", 0.0);
  g.altitude_m = r.number_or("altitude_m", 0.0);
  g.plan_rotation = radians_of_written(r.number_or("plan_rotation_deg", 0.0));
  g.scale = r.number_or("scale", 1.0);
  if (g.scale <= 0) r.at("scale").fail("must be > 0");
  if (auto o = r.find("plan_origin")) g.plan_origin = read_vec2(*o);
  if (g.valid && (std::abs(g.latitude_deg) > 90 || std::abs(g.longitude_deg) > 180))
    r.fail("latitude must be within ±90° and longitude within ±180°");
  return g;
}

json tour_to_json(const TourSettings& t, const std::string& base) {
  json out = {{"title", t.title},
              {"description", t.description},
              {"max_size", t.max_size},
              {"preview_size", t.preview_size},
              {"jpeg_quality", t.jpeg_quality},
              {"start_frame", t.start_frame},
              {"export_pannellum", t.export_pannellum},
              {"export_geojson", t.export_geojson},
              {"export_multires", t.export_multires},
              {"export_marzipano", t.export_marzipano},
              {"export_psv", t.export_psv},
              {"export_kml_gpx", t.export_kml_gpx},
              {"export_tum", t.export_tum},
              {"export_opensfm", t.export_opensfm},
              {"export_nerfstudio", t.export_nerfstudio},
              {"export_photo_metadata", t.export_photo_metadata},
              {"export_clean_plates", t.export_clean_plates},
              {"nadir_patch", to_string(t.nadir_patch)},
              {"blur_faces", t.blur_faces}};
  if (!t.nadir_image.empty()) out["nadir_image"] = path_relative_to(t.nadir_image, base);
  if (!t.clean_plate_edits.empty()) {
    json edits = json::array();
    for (const CleanPlateEdit& e : t.clean_plate_edits)
      edits.push_back({{"frame", e.frame}, {"mask", path_relative_to(e.mask, base)}});
    out["clean_plate_edits"] = edits;
  }
  return out;
}

TourSettings tour_from_json(const JsonReader& r, const std::string& base) {
  TourSettings t;
  t.title = r.string_or("title", t.title);
  t.description = r.string_or("description", t.description);
  t.max_size = r.integer_or("max_size", t.max_size);
  t.preview_size = r.integer_or("preview_size", t.preview_size);
  t.jpeg_quality = r.integer_or("jpeg_quality", t.jpeg_quality);
  if (t.jpeg_quality < 1 || t.jpeg_quality > 100) r.at("jpeg_quality").fail("must be within 1..100");
  t.start_frame = r.integer_or("start_frame", t.start_frame);
  t.export_pannellum = r.boolean_or("export_pannellum", t.export_pannellum);
  t.export_geojson = r.boolean_or("export_geojson", t.export_geojson);
  t.export_multires = r.boolean_or("export_multires", t.export_multires);
  t.export_marzipano = r.boolean_or("export_marzipano", t.export_marzipano);
  t.export_psv = r.boolean_or("export_psv", t.export_psv);
  t.export_kml_gpx = r.boolean_or("export_kml_gpx", t.export_kml_gpx);
  t.export_tum = r.boolean_or("export_tum", t.export_tum);
  t.export_opensfm = r.boolean_or("export_opensfm", t.export_opensfm);
  t.export_nerfstudio = r.boolean_or("export_nerfstudio", t.export_nerfstudio);
  t.export_photo_metadata = r.boolean_or("export_photo_metadata", t.export_photo_metadata);
  t.export_clean_plates = r.boolean_or("export_clean_plates", t.export_clean_plates);
  t.nadir_patch = enum_from_json(r, "nadir_patch", t.nadir_patch);
  t.nadir_image = path_resolved_against(r.string_or("nadir_image", ""), base);
  t.blur_faces = r.boolean_or("blur_faces", t.blur_faces);
  if (auto edits = r.find("clean_plate_edits"))
    for (std::size_t i = 0; i < edits->size(); ++i) {
      const JsonReader e = edits->at(i);
      CleanPlateEdit edit;
      edit.frame = e.integer("frame");
      edit.mask = path_resolved_against(e.string("mask"), base);
      if (t.clean_plate_edit(edit.frame)) e.at("frame").fail("has a second clean-plate edit");
      t.clean_plate_edits.push_back(edit);
    }
  return t;
}

}  // namespace

json project_to_json(const Project& p, const std::string& base) {
  return {{"format", kProjectFormatName},
          {"version", kProjectFormatVersion},
          {"generator", std::string("Plenopath Studio ") + PLENOPATH_VERSION},
          {"plan", plan_to_json(p.plan, base)},
          {"capture", capture_to_json(p.capture, base)},
          {"path", path_to_json(p.path)},
          {"anchors", anchors_to_json(p.anchors)},
          {"visibility", visibility_to_json(p.visibility)},
          {"keyframes", keyframes_to_json(p.keyframes)},
          {"hotspots", hotspots_to_json(p.hotspots, base)},
          {"geo_anchor", geo_to_json(p.geo)},
          {"tour", tour_to_json(p.tour, base)}};
}

Project project_from_json(const json& j, const std::string& base, const std::string& file) {
  const JsonReader r(j, file);
  if (!j.is_object()) r.fail("not a Plenopath project (expected a JSON object)");
  if (!r.has("format") || r.string("format") != kProjectFormatName)
    r.fail(std::string("not a Plenopath project (\"format\" must be \"") + kProjectFormatName + "\")");
  const int version = r.integer("version");
  if (version > kProjectFormatVersion)
    throw file_error(file, "written by a newer Plenopath Studio (project format version " +
                               std::to_string(version) + "; this build reads up to version " +
                               std::to_string(kProjectFormatVersion) + "). Update the studio to open it.");
  if (version < 1) r.at("version").fail("invalid project format version " + std::to_string(version));

  Project p;
  if (auto v = r.find("plan")) p.plan = plan_from_json(*v, base);
  if (auto v = r.find("capture")) p.capture = capture_from_json(*v, base);
  if (auto v = r.find("path")) p.path = path_from_json(*v);
  if (auto v = r.find("anchors")) p.anchors = anchors_from_json(*v);
  if (auto v = r.find("visibility")) p.visibility = visibility_from_json(*v);
  if (auto v = r.find("keyframes")) p.keyframes = keyframes_from_json(*v);
  if (auto v = r.find("hotspots")) p.hotspots = hotspots_from_json(*v, base);
  if (auto v = r.find("geo_anchor")) p.geo = geo_from_json(*v);
  if (auto v = r.find("tour")) p.tour = tour_from_json(*v, base);
  return p;
}

Project load_project(const std::string& file) {
  const json j = read_json_file(file);
  const std::string base = std::filesystem::absolute(file).parent_path().string();
  return project_from_json(j, base, file);
}

void save_project(const Project& project, const std::string& file) {
  const std::string base = std::filesystem::absolute(file).parent_path().string();
  write_file_atomically(
      file,
      project_to_json(project, base).dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n",
      true);
}

}  // namespace plenopath
