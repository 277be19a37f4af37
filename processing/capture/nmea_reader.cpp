// NMEA 0183 logs, as phone apps and GPS loggers write them beside a 360 camera.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "model/error.h"
#include "processing/capture/gps_track.h"
#include "processing/capture/gps_track_internal.h"

namespace plenopath {
namespace {

std::vector<std::string> split_fields(const std::string& body) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(body);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!body.empty() && body.back() == ',') fields.emplace_back();
  return fields;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// The sentence between '$' and '*' when its checksum (if it has one) matches; empty otherwise.
bool sentence_body(const std::string& line, std::string* body) {
  const std::size_t start = line.find_first_of("$!");
  if (start == std::string::npos) return false;
  const std::size_t star = line.find('*', start);
  *body = line.substr(start + 1, star == std::string::npos ? std::string::npos : star - start - 1);
  if (star == std::string::npos) return true;  // the checksum is optional in NMEA 0183
  const int hi = star + 1 < line.size() ? hex_digit(line[star + 1]) : -1;
  const int lo = star + 2 < line.size() ? hex_digit(line[star + 2]) : -1;
  if (hi < 0 || lo < 0) return false;
  unsigned char sum = 0;
  for (char c : *body) sum ^= static_cast<unsigned char>(c);
  return sum == hi * 16 + lo;
}

// "hhmmss.ss" as seconds of the day.
bool time_of_day(const std::string& t, double* seconds) {
  if (t.size() < 6) return false;
  for (int i = 0; i < 6; ++i)
    if (!std::isdigit(static_cast<unsigned char>(t[i]))) return false;
  bool ok = true;
  const double s = parse_gps_number(t.substr(4), &ok);
  const int h = std::stoi(t.substr(0, 2)), m = std::stoi(t.substr(2, 2));
  if (!ok || h > 23 || m > 59 || s < 0 || s >= 61) return false;
  *seconds = h * 3600.0 + m * 60.0 + s;
  return true;
}

// "ddmm.mmmm" + "N"/"S" (or "dddmm.mmmm" + "E"/"W") as signed degrees.
bool coordinate(const std::string& value, const std::string& hemisphere, double limit, double* degrees) {
  bool ok = false;
  const double v = parse_gps_number(value, &ok);
  if (!ok || v < 0) return false;
  const double whole = std::floor(v / 100.0);
  const double minutes = v - whole * 100.0;
  if (minutes >= 60.0) return false;
  double d = whole + minutes / 60.0;
  if (hemisphere == "S" || hemisphere == "W")
    d = -d;
  else if (hemisphere != "N" && hemisphere != "E")
    return false;
  if (std::abs(d) > limit) return false;
  *degrees = d;
  return true;
}

// "ddmmyy" as Unix seconds of that day's midnight (years 80-99 are 19xx, as GPS receivers mean them).
bool date_of(const std::string& d, double* midnight) {
  if (d.size() != 6) return false;
  for (char c : d)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  const int yy = std::stoi(d.substr(4, 2));
  char iso[32];
  std::snprintf(iso, sizeof iso, "%04d-%s-%sT00:00:00Z", yy < 80 ? 2000 + yy : 1900 + yy,
                d.substr(2, 2).c_str(), d.substr(0, 2).c_str());
  try {
    *midnight = parse_iso8601_utc(iso);
  } catch (const Error&) {
    return false;
  }
  return true;
}

}  // namespace

GpsTrack parse_nmea(const std::string& text, const std::string& file) {
  struct Fix {
    double time_of_day;
    double lat, lon;
  };
  std::vector<GpsPoint> rmc_points;               // dated
  std::map<long long, double> altitude;           // GGA altitude by time of day in centiseconds
  std::vector<std::pair<Fix, double>> gga_fixes;  // (fix, altitude) in log order
  int bad_checksum = 0, bad_fields = 0, no_fix = 0;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_of("$!") == std::string::npos) continue;
    std::string body;
    if (!sentence_body(line, &body)) {
      ++bad_checksum;
      continue;
    }
    const std::vector<std::string> f = split_fields(body);
    if (f.empty() || f[0].size() != 5) continue;
    const std::string type = f[0].substr(2);  // talker (GP, GN, GL, GA, ...) dropped
    Fix fix{};
    if (type == "RMC") {
      if (f.size() < 10) {
        ++bad_fields;
        continue;
      }
      if (f[2] != "A") {
        ++no_fix;
        continue;
      }
      double midnight = 0;
      if (!time_of_day(f[1], &fix.time_of_day) || !coordinate(f[3], f[4], 90, &fix.lat) ||
          !coordinate(f[5], f[6], 180, &fix.lon) || !date_of(f[9], &midnight)) {
        ++bad_fields;
        continue;
      }
      GpsPoint p;
      p.lat = fix.lat;
      p.lon = fix.lon;
      p.time = midnight + fix.time_of_day;
      p.has_time = true;
      rmc_points.push_back(p);
    } else if (type == "GGA") {
      if (f.size() < 10) {
        ++bad_fields;
        continue;
      }
      if (f[6].empty() || f[6] == "0") {
        ++no_fix;
        continue;
      }
      bool alt_ok = true;
      const double alt = f[9].empty() ? 0.0 : parse_gps_number(f[9], &alt_ok);
      if (!time_of_day(f[1], &fix.time_of_day) || !coordinate(f[2], f[3], 90, &fix.lat) ||
          !coordinate(f[4], f[5], 180, &fix.lon) || !alt_ok) {
        ++bad_fields;
        continue;
      }
      altitude[std::llround(fix.time_of_day * 100.0)] = alt;
      gga_fixes.push_back({fix, alt});
    }
  }

  GpsTrack track;
  std::vector<GpsPoint> points;
  if (!rmc_points.empty()) {
    for (GpsPoint p : rmc_points) {
      const double tod = std::fmod(p.time, 86400.0);
      const auto a = altitude.find(std::llround(tod * 100.0));
      if (a != altitude.end()) p.ele = a->second;
      points.push_back(p);
    }
  } else if (!gga_fixes.empty()) {
    // No dates: times of day, a day added each time the clock runs back by more than half a day.
    double day = 0, previous = -1;
    for (const auto& [fix, alt] : gga_fixes) {
      if (previous >= 0 && fix.time_of_day < previous - 43200.0) day += 86400.0;
      previous = fix.time_of_day;
      GpsPoint p;
      p.lat = fix.lat;
      p.lon = fix.lon;
      p.ele = alt;
      p.time = day + fix.time_of_day;
      p.has_time = true;
      points.push_back(p);
    }
    track.notes.push_back("no $--RMC sentences: the date is unknown, times are times of day");
  }
  if (bad_checksum)
    track.notes.push_back(std::to_string(bad_checksum) + " sentences with a bad checksum skipped");
  if (bad_fields)
    track.notes.push_back(std::to_string(bad_fields) + " sentences with malformed fields skipped");
  if (no_fix) track.notes.push_back(std::to_string(no_fix) + " sentences without a fix skipped");
  if (points.empty()) {
    std::string why = "no position in this NMEA log (no valid $--RMC or $--GGA sentence)";
    for (const std::string& n : track.notes) why += "; " + n;
    throw file_error(file, why);
  }
  return gps_track_from_points(std::move(points), std::move(track), file, "positions");
}

}  // namespace plenopath
