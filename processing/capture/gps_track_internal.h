#pragma once
// Shared by the GPS track readers (gpx_reader.cpp, nmea_reader.cpp, geojson_track.cpp, gps_track.cpp).
#include <string>
#include <vector>

#include "processing/capture/gps_track.h"

namespace plenopath {

struct GpsPoint {
  double lat = 0, lon = 0, ele = 0, time = 0;  // time: Unix seconds
  bool has_time = false;
};

// A whole string as a finite number (surrounding spaces allowed).
double parse_gps_number(const std::string& text, bool* ok);

// Drops points without time (counted), sorts by time, and makes the samples relative to the first.
// Throws Error naming the file when there are no points (`point_names` says which were expected) or none
// has a time.
GpsTrack gps_track_from_points(std::vector<GpsPoint> points, GpsTrack track, const std::string& file,
                               const char* point_names);

}  // namespace plenopath
