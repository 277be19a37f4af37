#pragma once
// GPS tracks (GPX 1.0/1.1) read, matched to frames by time, and placed in the plan frame through the
// project's geo-anchor: WGS84 -> local east/north/up at the anchor (GeographicLib LocalCartesian) ->
// GeoAnchor::plan_from_enu. The refinement uses the matched positions as weak priors.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/capture.h"
#include "model/geo_anchor.h"

namespace plenopath {

struct GpsTrack {
  std::vector<GpsSample> samples;  // time_s relative to epoch_unix_s, sorted by time
  double epoch_unix_s = 0.0;       // UTC time of the first sample, seconds since 1970-01-01
  std::string name;                // <trk><name> or the GeoJSON feature's name, if any
  int samples_without_time = 0;    // points dropped because they had no time
  std::vector<std::string> notes;  // what was skipped and why, for the author
};
using GpxTrack = GpsTrack;

// A GPS track in any format the studio reads, recognised by content (not by the file name): GPX 1.0/1.1,
// NMEA 0183 logs, GeoJSON. Throws Error naming the file when it is none of them or cannot be read.
GpsTrack read_gps_track(const std::string& file);
GpsTrack parse_gps_track(const std::string& text, const std::string& file_name_for_errors);

// GPX through expat: <trkpt> (all tracks and segments), or <rtept> when there are no track points; any
// encoding expat knows plus windows-1252. Throws Error naming the file (and line) when it is not
// well-formed XML, not GPX, or a point has a bad latitude/longitude/time.
GpsTrack read_gpx(const std::string& file);
GpsTrack parse_gpx(const std::string& text, const std::string& file_name_for_errors);

// NMEA 0183: $--RMC (date, time, position; status A only) and $--GGA (altitude, matched to the RMC of the
// same second; a log of GGA alone has times of day on 1970-01-01, days counted across midnight). Sentences
// with a bad checksum or fields are skipped and counted in notes. Throws Error when no position is left.
GpsTrack parse_nmea(const std::string& text, const std::string& file_name_for_errors);

// GeoJSON: a LineString (or MultiLineString) Feature with per-vertex times in properties.coordTimes or
// properties.times (togeojson's convention, ISO 8601 or Unix milliseconds), or Point Features with
// properties.time. Coordinates are [lon, lat, (alt)]. Throws Error naming the file otherwise.
GpsTrack parse_geojson_track(const std::string& text, const std::string& file_name_for_errors);

// ISO 8601 UTC time ("2024-05-01T10:20:30.5Z", offsets like "+02:00" honoured) as Unix seconds.
// Throws Error on malformed text.
double parse_iso8601_utc(const std::string& text);

struct GpsMatchOptions {
  double time_offset_s = 0.0;  // GPS-track time of the capture's time stamp 0 (Capture::gps_time_offset_s)
  double max_gap_s = 5.0;      // no position for a frame whose neighbouring samples are farther apart
  double max_extrapolation_s = 0.5;  // frames this far before the first / after the last sample, or from a
                                     // sample at the edge of a gap, still match
  void check() const;
};

struct FrameGps {
  bool valid = false;  // false: the frame's time is outside the track or in a gap
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double altitude_m = 0.0;
};

// Position at track time t (seconds, the samples' clock), linearly interpolated between neighbours.
FrameGps gps_at_time(const std::vector<GpsSample>& samples, double t, const GpsMatchOptions& options = {});
// One entry per frame time stamp (frame time + options.time_offset_s on the track's clock).
std::vector<FrameGps> match_gps_to_frames(const std::vector<GpsSample>& samples,
                                          const std::vector<double>& frame_timestamps_s,
                                          const GpsMatchOptions& options = {});

// Plan position of a WGS84 point (metres in the plan frame), via local ENU at the anchor.
// Throws Error when the anchor is not valid.
Eigen::Vector2d plan_from_wgs84(const GeoAnchor& anchor, double latitude_deg, double longitude_deg,
                                double altitude_m = 0.0);
// Local east/north/up (metres) of a WGS84 point at the anchor's position.
Eigen::Vector3d enu_from_wgs84(const GeoAnchor& anchor, double latitude_deg, double longitude_deg,
                               double altitude_m = 0.0);

// A weak position prior for the refinement.
struct GpsPrior {
  int frame = 0;
  Eigen::Vector2d plan_xy = Eigen::Vector2d::Zero();
  double sigma_m = 5.0;  // 1-sigma horizontal uncertainty
};
// Priors for every frame that has a matched GPS position (frames without one are left out).
std::vector<GpsPrior> gps_priors(const std::vector<GpsSample>& samples,
                                 const std::vector<double>& frame_timestamps_s, const GeoAnchor& anchor,
                                 const GpsMatchOptions& options = {}, double sigma_m = 5.0);

}  // namespace plenopath
