// GeoJSON GPS tracks. GeoJSON (RFC 7946) has no time; the common conventions are togeojson's
// properties.coordTimes (one time per vertex of a LineString) and Point features with properties.time.
#include <optional>
#include <string>
#include <vector>

#include "model/error.h"
#include "model/json_reader.h"
#include "processing/capture/gps_track.h"
#include "processing/capture/gps_track_internal.h"

namespace plenopath {
namespace {

// ISO 8601 text, or a number of Unix milliseconds (what JavaScript's Date.now() writes).
double time_of(const JsonReader& t) {
  if (t.value().is_number()) return t.number() / 1000.0;
  try {
    return parse_iso8601_utc(t.string());
  } catch (const Error& e) {
    t.fail(e.what());
  }
}

GpsPoint point_of(const JsonReader& position) {
  if (position.size() < 2) position.fail("a position needs [longitude, latitude]");
  GpsPoint p;
  p.lon = position.at(std::size_t{0}).number();
  p.lat = position.at(std::size_t{1}).number();
  if (position.size() > 2) p.ele = position.at(std::size_t{2}).number();
  if (p.lat < -90 || p.lat > 90) position.fail("latitude out of range (GeoJSON is [longitude, latitude])");
  if (p.lon < -180 || p.lon > 360) position.fail("longitude out of range");
  if (p.lon > 180) p.lon -= 360;
  return p;
}

// The per-vertex times of a line feature, flattened over its lines.
std::vector<std::optional<JsonReader>> vertex_times(const JsonReader& properties) {
  std::vector<std::optional<JsonReader>> out;
  for (const char* key : {"coordTimes", "times"}) {
    const auto times = properties.find(key);
    if (!times) continue;
    for (std::size_t i = 0; i < times->size(); ++i) {
      const JsonReader t = times->at(i);
      if (t.value().is_array())
        for (std::size_t k = 0; k < t.size(); ++k) out.push_back(t.at(k));  // MultiLineString: one per line
      else
        out.push_back(t);
    }
    break;
  }
  return out;
}

void read_feature(const JsonReader& feature, std::vector<GpsPoint>& points, GpsTrack& track) {
  if (feature.string_or("type", "") != "Feature") feature.fail("expected a Feature");
  const auto geometry = feature.find("geometry");
  if (!geometry || geometry->value().is_null()) return;
  static const nlohmann::json no_properties = nlohmann::json::object();
  const auto found = feature.find("properties");
  const JsonReader properties =
      found && found->value().is_object()
          ? *found
          : JsonReader(no_properties, feature.file(), feature.pointer() + "/properties");
  if (track.name.empty()) track.name = properties.string_or("name", "");
  const std::string type = geometry->string("type");
  const JsonReader coordinates = geometry->at("coordinates");
  if (type == "Point") {
    GpsPoint p = point_of(coordinates);
    if (const auto t = properties.find("time"); t && !t->value().is_null()) {
      p.time = time_of(*t);
      p.has_time = true;
    }
    points.push_back(p);
    return;
  }
  std::vector<JsonReader> lines;
  if (type == "LineString")
    lines.push_back(coordinates);
  else if (type == "MultiLineString")
    for (std::size_t i = 0; i < coordinates.size(); ++i) lines.push_back(coordinates.at(i));
  else
    return;  // polygons and the like are not tracks
  const std::vector<std::optional<JsonReader>> times = vertex_times(properties);
  std::size_t vertex = 0;
  for (const JsonReader& line : lines)
    for (std::size_t i = 0; i < line.size(); ++i, ++vertex) {
      GpsPoint p = point_of(line.at(i));
      if (vertex < times.size() && !times[vertex]->value().is_null()) {
        p.time = time_of(*times[vertex]);
        p.has_time = true;
      }
      points.push_back(p);
    }
  if (!times.empty() && times.size() != vertex)
    track.notes.push_back("times for " + std::to_string(times.size()) + " of " + std::to_string(vertex) +
                          " vertices");
}

}  // namespace

GpsTrack parse_geojson_track(const std::string& text, const std::string& file) {
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw file_error(file, std::string("not valid JSON: ") + e.what());
  }
  const JsonReader root(document, file);
  if (!document.is_object()) root.fail("expected a GeoJSON object");
  GpsTrack track;
  std::vector<GpsPoint> points;
  const std::string type = root.string_or("type", "");
  if (type == "FeatureCollection") {
    const JsonReader features = root.at("features");
    for (std::size_t i = 0; i < features.size(); ++i) read_feature(features.at(i), points, track);
  } else if (type == "Feature") {
    read_feature(root, points, track);
  } else {
    root.fail("not a GeoJSON Feature or FeatureCollection (type '" + type + "')");
  }
  return gps_track_from_points(std::move(points), std::move(track), file,
                               "points (LineString or Point features)");
}

}  // namespace plenopath
