#pragma once
// The path on a map: KML (Google Earth, QGIS) and GPX (every GPS tool) of the camera path in WGS84, each
// keyframe a placemark / waypoint, placed through the project's geo-anchor with GeographicLib's
// LocalCartesian (ARCHITECTURE.md: plan -> ENU by scale, rotation, translation, then Reverse).
#include <Eigen/Core>
#include <string>

#include "model/project.h"

namespace plenopath {

// Whether the package gets path.kml and path.gpx. kAuto writes them when the project has a valid
// geo-anchor and leaves them out without a word otherwise; kOn asks for them, so a project without an
// anchor is an Error.
enum class GeoTrackFiles { kOff, kAuto, kOn };

struct Wgs84Position {
  double latitude_deg = 0.0, longitude_deg = 0.0;
  // In the anchor's own altitude datum (EXIF and KML read it as above sea level); LocalCartesian treats it
  // as ellipsoidal, which over a building differs from adding the height by well under a millimetre.
  double altitude_m = 0.0;
};

// A point `height_m` above the plan point (x, y) (the floor), on Earth through the anchor.
Wgs84Position wgs84_of_plan_point(const GeoAnchor& anchor, const Eigen::Vector2d& plan, double height_m);

// Compass heading, degrees clockwise from north in [0, 360), of the direction at plan angle `heading`
// (radians CCW from plan +X). Without a valid anchor, plan +Y is taken as north.
double compass_heading_deg(const GeoAnchor& anchor, double heading);

// True when the package should hold path.kml and path.gpx; throws Error (naming what is missing) when
// they were asked for (kOn) and the project has no valid geo-anchor.
bool wants_geo_tracks(GeoTrackFiles choice, const Project& project);

// KML 2.2: a Document with the path as one LineString per piece (lon,lat,alt; camera height above the
// anchor's altitude) and a Folder of keyframe Points named "Keyframe <frame>" with frame and heading as
// ExtendedData. Throws Error without a valid geo-anchor.
std::string path_kml(const Project& project);

// GPX 1.1: the keyframes as waypoints (<wpt>, named as in the KML) and the path as one track with a
// segment per piece. Throws Error without a valid geo-anchor.
std::string path_gpx(const Project& project);

}  // namespace plenopath
