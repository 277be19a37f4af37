#include "processing/capture/gps_track.h"

#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "model/error.h"
#include "processing/capture/gps_track_internal.h"

namespace plenopath {
namespace {

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

// Days from 1970-01-01 to a proleptic Gregorian date (the usual era-based formula).
long long days_from_civil(long long y, int m, int d) {
  y -= m <= 2;
  const long long era = (y >= 0 ? y : y - 399) / 400;
  const long long yoe = y - era * 400;
  const long long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const long long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

}  // namespace

double parse_iso8601_utc(const std::string& text_in) {
  const std::string text = trim(text_in);
  auto bad = [&]() {
    return Error("bad time '" + text + "' (expected ISO 8601, e.g. 2024-05-01T10:20:30Z)");
  };
  int year = 0, month = 0, day = 0, hour = 0, minute = 0;
  double second = 0.0;
  std::size_t p = 0;
  auto digits = [&](int n) {
    if (p + n > text.size()) throw bad();
    int v = 0;
    for (int k = 0; k < n; ++k) {
      const char c = text[p + k];
      if (!std::isdigit(static_cast<unsigned char>(c))) throw bad();
      v = v * 10 + (c - '0');
    }
    p += n;
    return v;
  };
  auto expect = [&](char c) {
    if (p >= text.size() || text[p] != c) throw bad();
    ++p;
  };
  year = digits(4);
  expect('-');
  month = digits(2);
  expect('-');
  day = digits(2);
  if (p < text.size() && (text[p] == 'T' || text[p] == 't' || text[p] == ' ')) {
    ++p;
    hour = digits(2);
    expect(':');
    minute = digits(2);
    if (p < text.size() && text[p] == ':') {
      ++p;
      second = digits(2);
      if (p < text.size() && (text[p] == '.' || text[p] == ',')) {
        ++p;
        double scale = 0.1;
        if (p >= text.size() || !std::isdigit(static_cast<unsigned char>(text[p]))) throw bad();
        while (p < text.size() && std::isdigit(static_cast<unsigned char>(text[p]))) {
          second += (text[p] - '0') * scale;
          scale *= 0.1;
          ++p;
        }
      }
    }
  }
  double offset_s = 0.0;  // no zone: UTC, as GPX requires
  if (p < text.size()) {
    if (text[p] == 'Z' || text[p] == 'z') {
      ++p;
    } else if (text[p] == '+' || text[p] == '-') {
      const double sign = text[p] == '+' ? 1.0 : -1.0;
      ++p;
      const int oh = digits(2);
      if (p < text.size() && text[p] == ':') ++p;
      const int om = p < text.size() ? digits(2) : 0;
      offset_s = sign * (oh * 3600.0 + om * 60.0);
    }
  }
  if (p != text.size()) throw bad();
  if (month < 1 || month > 12 || day < 1 || day > 31 || hour > 24 || minute > 59 || second >= 61.0)
    throw bad();
  return double(days_from_civil(year, month, day)) * 86400.0 + hour * 3600.0 + minute * 60.0 + second -
         offset_s;
}

double parse_gps_number(const std::string& text, bool* ok) {
  const std::string t = trim(text);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  *ok = !t.empty() && end == t.c_str() + t.size() && std::isfinite(v);
  return v;
}

GpsTrack gps_track_from_points(std::vector<GpsPoint> points, GpsTrack track, const std::string& file,
                               const char* point_names) {
  if (points.empty()) throw file_error(file, std::string("no ") + point_names);
  std::vector<GpsPoint> timed;
  for (const GpsPoint& p : points) {
    if (p.has_time)
      timed.push_back(p);
    else
      ++track.samples_without_time;
  }
  if (timed.empty())
    throw file_error(
        file, "its " + std::to_string(points.size()) + " points have no <time>; frames are matched by time");
  std::stable_sort(timed.begin(), timed.end(),
                   [](const GpsPoint& a, const GpsPoint& b) { return a.time < b.time; });
  track.epoch_unix_s = timed.front().time;
  for (const GpsPoint& p : timed) {
    GpsSample s;
    s.time_s = p.time - track.epoch_unix_s;
    s.latitude_deg = p.lat;
    s.longitude_deg = p.lon;
    s.altitude_m = p.ele;
    track.samples.push_back(s);
  }
  if (track.samples_without_time > 0)
    track.notes.push_back(std::to_string(track.samples_without_time) + " points without a time skipped");
  return track;
}

std::string read_gps_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw file_error(file, "cannot open GPS track");
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw file_error(file, "cannot read GPS track");
  return buffer.str();
}

GpsTrack read_gpx(const std::string& file) { return parse_gpx(read_gps_file(file), file); }

GpsTrack parse_gps_track(const std::string& text, const std::string& file) {
  // By content, not by name: loggers write NMEA as .txt, .log or .nmea, and GeoJSON as .json.
  std::size_t first = 0;
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) first = 3;  // UTF-8 byte order mark
  while (first < text.size() && std::isspace(static_cast<unsigned char>(text[first]))) ++first;
  const char c = first < text.size() ? text[first] : '\0';
  if (c == '$' || c == '!') return parse_nmea(text, file);
  if (c == '{') return parse_geojson_track(text, file);
  if (c == '<' || text.compare(0, 2, "\xFF\xFE") == 0 || text.compare(0, 2, "\xFE\xFF") == 0)
    return parse_gpx(text, file);
  throw file_error(file,
                   "not a GPS track: expected GPX (XML), NMEA 0183 sentences ($GPRMC, $GPGGA) or GeoJSON");
}

GpsTrack read_gps_track(const std::string& file) { return parse_gps_track(read_gps_file(file), file); }

void GpsMatchOptions::check() const {
  if (!std::isfinite(time_offset_s))
    throw Error("GPS matching: time_offset_s must be a finite number of seconds");
  if (!(max_gap_s > 0.0)) throw Error("GPS matching: max_gap_s must be positive");
  if (!(max_extrapolation_s >= 0.0)) throw Error("GPS matching: max_extrapolation_s must be >= 0");
}

FrameGps gps_at_time(const std::vector<GpsSample>& samples, double t, const GpsMatchOptions& options) {
  FrameGps out;
  if (samples.empty() || !std::isfinite(t)) return out;
  auto from = [&](const GpsSample& s) {
    out.valid = true;
    out.latitude_deg = s.latitude_deg;
    out.longitude_deg = s.longitude_deg;
    out.altitude_m = s.altitude_m;
    return out;
  };
  if (t <= samples.front().time_s)
    return samples.front().time_s - t <= options.max_extrapolation_s ? from(samples.front()) : out;
  if (t >= samples.back().time_s)
    return t - samples.back().time_s <= options.max_extrapolation_s ? from(samples.back()) : out;
  const auto after = std::upper_bound(samples.begin(), samples.end(), t,
                                      [](double value, const GpsSample& s) { return value < s.time_s; });
  const GpsSample& b = *after;
  const GpsSample& a = *(after - 1);
  const double dt = b.time_s - a.time_s;
  if (dt > options.max_gap_s) {
    // In a gap, a frame next to a sample still takes it: tripod stills carry one sample each, minutes apart.
    if (t - a.time_s <= options.max_extrapolation_s) return from(a);
    if (b.time_s - t <= options.max_extrapolation_s) return from(b);
    return out;
  }
  if (dt <= 0.0) return from(b);
  const double w = (t - a.time_s) / dt;
  double dlon = b.longitude_deg - a.longitude_deg;
  if (dlon > 180) dlon -= 360;  // across the antimeridian
  if (dlon < -180) dlon += 360;
  out.valid = true;
  out.latitude_deg = a.latitude_deg + w * (b.latitude_deg - a.latitude_deg);
  out.longitude_deg = a.longitude_deg + w * dlon;
  if (out.longitude_deg > 180) out.longitude_deg -= 360;
  if (out.longitude_deg < -180) out.longitude_deg += 360;
  out.altitude_m = a.altitude_m + w * (b.altitude_m - a.altitude_m);
  return out;
}

std::vector<FrameGps> match_gps_to_frames(const std::vector<GpsSample>& samples,
                                          const std::vector<double>& frame_timestamps_s,
                                          const GpsMatchOptions& options) {
  options.check();
  std::vector<FrameGps> out;
  out.reserve(frame_timestamps_s.size());
  for (double t : frame_timestamps_s) out.push_back(gps_at_time(samples, t + options.time_offset_s, options));
  return out;
}

Eigen::Vector3d enu_from_wgs84(const GeoAnchor& anchor, double latitude_deg, double longitude_deg,
                               double altitude_m) {
  if (!anchor.valid) throw Error("the project has no geo-anchor: GPS positions cannot be placed on the plan");
  if (!(std::abs(latitude_deg) <= 90.0) || !std::isfinite(longitude_deg))
    throw Error("bad GPS position (" + std::to_string(latitude_deg) + ", " + std::to_string(longitude_deg) +
                ")");
  const GeographicLib::LocalCartesian local(anchor.latitude_deg, anchor.longitude_deg, anchor.altitude_m);
  double east = 0, north = 0, up = 0;
  local.Forward(latitude_deg, longitude_deg, altitude_m, east, north, up);
  return {east, north, up};
}

Eigen::Vector2d plan_from_wgs84(const GeoAnchor& anchor, double latitude_deg, double longitude_deg,
                                double altitude_m) {
  const Eigen::Vector3d enu = enu_from_wgs84(anchor, latitude_deg, longitude_deg, altitude_m);
  return anchor.plan_from_enu(enu.head<2>());
}

std::vector<GpsPrior> gps_priors(const std::vector<GpsSample>& samples,
                                 const std::vector<double>& frame_timestamps_s, const GeoAnchor& anchor,
                                 const GpsMatchOptions& options, double sigma_m) {
  if (!(sigma_m > 0.0)) throw Error("GPS priors: sigma_m must be positive");
  if (!anchor.valid) throw Error("the project has no geo-anchor: GPS positions cannot be placed on the plan");
  const GeographicLib::LocalCartesian local(anchor.latitude_deg, anchor.longitude_deg, anchor.altitude_m);
  const std::vector<FrameGps> matched = match_gps_to_frames(samples, frame_timestamps_s, options);
  std::vector<GpsPrior> priors;
  for (std::size_t i = 0; i < matched.size(); ++i) {
    if (!matched[i].valid) continue;
    double east = 0, north = 0, up = 0;
    local.Forward(matched[i].latitude_deg, matched[i].longitude_deg, matched[i].altitude_m, east, north, up);
    priors.push_back({static_cast<int>(i), anchor.plan_from_enu({east, north}), sigma_m});
  }
  return priors;
}

}  // namespace plenopath
