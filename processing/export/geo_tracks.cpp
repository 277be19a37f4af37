#include "processing/export/geo_tracks.h"

#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "model/error.h"
#include "processing/export/xml_escape.h"
#include "rig/spherical.h"

namespace plenopath {
namespace {

void require_anchor(const Project& project, const char* what) {
  if (!project.geo.valid)
    throw Error(std::string(what) +
                " needs a geo-anchor (latitude, longitude, plan rotation) in the project: set one, or "
                "export without it");
}

// 1e-9 degree is 0.1 mm on the ground: nothing the path knows is lost.
std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

struct GeoFrame {
  int frame = 0, piece = 0;
  Wgs84Position where;
  double heading_deg = 0.0;  // compass
};

std::vector<GeoFrame> geo_frames(const Project& project) {
  const double height = std::max(0.0, project.capture.camera_height_m);
  std::vector<GeoFrame> out;
  out.reserve(project.path.frames.size());
  for (const PathFrame& f : project.path.frames)
    out.push_back({f.index, f.piece, wgs84_of_plan_point(project.geo, f.position(), height),
                   compass_heading_deg(project.geo, f.heading)});
  return out;
}

// The keyframes along the path (ascending frame index), as a map reader lists them.
std::vector<GeoFrame> geo_keyframes(const Project& project, const std::vector<GeoFrame>& frames) {
  std::vector<GeoFrame> out;
  for (int k : project.keyframes.indices) {
    const PathFrame* f = project.path.find_frame(k);
    if (!f) throw Error("keyframe " + std::to_string(k) + " has no pose in the path");
    out.push_back(frames[static_cast<std::size_t>(f - project.path.frames.data())]);
  }
  std::sort(out.begin(), out.end(), [](const GeoFrame& a, const GeoFrame& b) { return a.frame < b.frame; });
  return out;
}

// Frames split where the piece changes: pieces are not joined by a line nobody walked.
std::vector<std::vector<GeoFrame>> by_piece(const std::vector<GeoFrame>& frames) {
  std::vector<std::vector<GeoFrame>> out;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i == 0 || frames[i].piece != frames[i - 1].piece) out.emplace_back();
    out.back().push_back(frames[i]);
  }
  return out;
}

std::string kml_coordinates(const Wgs84Position& g) {
  return fixed(g.longitude_deg, 9) + "," + fixed(g.latitude_deg, 9) + "," + fixed(g.altitude_m, 3);
}

}  // namespace

Wgs84Position wgs84_of_plan_point(const GeoAnchor& anchor, const Eigen::Vector2d& plan, double height_m) {
  const GeographicLib::LocalCartesian local(anchor.latitude_deg, anchor.longitude_deg, anchor.altitude_m);
  const Eigen::Vector2d enu = anchor.enu_from_plan(plan);
  Wgs84Position g;
  local.Reverse(enu.x(), enu.y(), height_m, g.latitude_deg, g.longitude_deg, g.altitude_m);
  return g;
}

double compass_heading_deg(const GeoAnchor& anchor, double heading) {
  const double enu_angle = heading + (anchor.valid ? anchor.plan_rotation : 0.0);
  double deg = std::fmod(90.0 - degrees(enu_angle), 360.0);
  if (deg < 0) deg += 360.0;
  return deg >= 360.0 ? 0.0 : deg;
}

bool wants_geo_tracks(GeoTrackFiles choice, const Project& project) {
  if (choice == GeoTrackFiles::kOn) require_anchor(project, "export: the KML and GPX of the path");
  return choice != GeoTrackFiles::kOff && project.geo.valid;
}

std::string path_kml(const Project& project) {
  require_anchor(project, "KML export");
  const std::vector<GeoFrame> frames = geo_frames(project);
  std::string kml =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n<name>" +
      xml_escape(project.tour.title) + "</name>\n";
  kml += "<Placemark>\n<name>Path</name>\n<MultiGeometry>\n";
  for (const std::vector<GeoFrame>& piece : by_piece(frames)) {
    // altitudeMode absolute: the anchor's altitude is the camera's datum, not a height above the terrain.
    kml += "<LineString><altitudeMode>absolute</altitudeMode><coordinates>\n";
    for (const GeoFrame& f : piece) kml += kml_coordinates(f.where) + "\n";
    kml += "</coordinates></LineString>\n";
  }
  kml += "</MultiGeometry>\n</Placemark>\n<Folder>\n<name>Keyframes</name>\n";
  for (const GeoFrame& k : geo_keyframes(project, frames)) {
    kml += "<Placemark><name>Keyframe " + std::to_string(k.frame) + "</name><ExtendedData>";
    kml += "<Data name=\"frame\"><value>" + std::to_string(k.frame) + "</value></Data>";
    kml += "<Data name=\"heading_deg\"><value>" + fixed(k.heading_deg, 3) + "</value></Data>";
    kml += "</ExtendedData><Point><altitudeMode>absolute</altitudeMode><coordinates>" +
           kml_coordinates(k.where) + "</coordinates></Point></Placemark>\n";
  }
  kml += "</Folder>\n</Document>\n</kml>\n";
  return kml;
}

std::string path_gpx(const Project& project) {
  require_anchor(project, "GPX export");
  const std::vector<GeoFrame> frames = geo_frames(project);
  auto point = [](const char* tag, const GeoFrame& f) {
    return std::string("<") + tag + " lat=\"" + fixed(f.where.latitude_deg, 9) + "\" lon=\"" +
           fixed(f.where.longitude_deg, 9) + "\"><ele>" + fixed(f.where.altitude_m, 3) + "</ele>";
  };
  std::string gpx =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<gpx version=\"1.1\" creator=\"Plenopath Studio\" xmlns=\"http://www.topografix.com/GPX/1/1\">\n"
      "<metadata><name>" +
      xml_escape(project.tour.title) + "</name></metadata>\n";
  // GPX 1.1 wants the waypoints before the tracks.
  for (const GeoFrame& k : geo_keyframes(project, frames))
    gpx += point("wpt", k) + "<name>Keyframe " + std::to_string(k.frame) + "</name><desc>heading " +
           fixed(k.heading_deg, 3) + " deg</desc></wpt>\n";
  gpx += "<trk><name>" + xml_escape(project.tour.title) + "</name>\n";
  for (const std::vector<GeoFrame>& piece : by_piece(frames)) {
    gpx += "<trkseg>\n";
    for (const GeoFrame& f : piece) gpx += point("trkpt", f) + "</trkpt>\n";
    gpx += "</trkseg>\n";
  }
  gpx += "</trk>\n</gpx>\n";
  return gpx;
}

}  // namespace plenopath
