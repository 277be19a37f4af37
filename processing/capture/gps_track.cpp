#include "processing/capture/gps_track.h"

#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "model/error.h"

namespace plenopath {
namespace {

// ---- a small, forgiving XML reader: enough for GPX (elements, attributes, text; skips the rest) ----

struct Tag {
  std::string name;  // local name, namespace prefix dropped
  std::map<std::string, std::string> attributes;
  bool closing = false;
  bool self_closing = false;
};

std::string local_name(const std::string& qualified) {
  const std::size_t colon = qualified.rfind(':');
  return colon == std::string::npos ? qualified : qualified.substr(colon + 1);
}

std::string decode_entities(const std::string& s) {
  if (s.find('&') == std::string::npos) return s;
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '&') {
      out += s[i];
      continue;
    }
    const std::size_t semi = s.find(';', i);
    if (semi == std::string::npos) {
      out += s[i];
      continue;
    }
    const std::string e = s.substr(i + 1, semi - i - 1);
    if (e == "amp")
      out += '&';
    else if (e == "lt")
      out += '<';
    else if (e == "gt")
      out += '>';
    else if (e == "quot")
      out += '"';
    else if (e == "apos")
      out += '\'';
    else if (!e.empty() && e[0] == '#') {
      long code = 0;
      try {
        code = e.size() > 1 && (e[1] == 'x' || e[1] == 'X') ? std::stol(e.substr(2), nullptr, 16)
                                                            : std::stol(e.substr(1));
      } catch (...) {
        code = '?';
      }
      out += code > 0 && code < 128 ? static_cast<char>(code) : '?';
    } else {
      out += s.substr(i, semi - i + 1);
    }
    i = semi;
  }
  return out;
}

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

class XmlScanner {
 public:
  XmlScanner(const std::string& text, const std::string& file) : text_(text), file_(file) {}

  // Next tag; text between the previous tag and this one goes to *text. False at the end.
  bool next(Tag& tag, std::string& text) {
    text.clear();
    while (pos_ < text_.size()) {
      const std::size_t lt = text_.find('<', pos_);
      if (lt == std::string::npos) {
        text += text_.substr(pos_);
        pos_ = text_.size();
        return false;
      }
      text += text_.substr(pos_, lt - pos_);
      pos_ = lt;
      if (text_.compare(pos_, 4, "<!--") == 0) {
        skip_past("-->", "comment");
      } else if (text_.compare(pos_, 9, "<![CDATA[") == 0) {
        const std::size_t end = text_.find("]]>", pos_ + 9);
        if (end == std::string::npos) error("unterminated CDATA section");
        text += text_.substr(pos_ + 9, end - pos_ - 9);
        pos_ = end + 3;
      } else if (text_.compare(pos_, 2, "<?") == 0) {
        skip_past("?>", "processing instruction");
      } else if (text_.compare(pos_, 2, "<!") == 0) {
        skip_past(">", "declaration");
      } else {
        parse_tag(tag);
        return true;
      }
    }
    return false;
  }

  [[noreturn]] void error(const std::string& what) const {
    const long line =
        1 + std::count(text_.begin(), text_.begin() + static_cast<long>(std::min(pos_, text_.size())), '\n');
    throw file_error(file_, "line " + std::to_string(line) + ": " + what);
  }
  std::size_t position() const { return pos_; }

 private:
  void skip_past(const char* end, const char* what) {
    const std::size_t e = text_.find(end, pos_ + 2);
    if (e == std::string::npos) error(std::string("unterminated ") + what);
    pos_ = e + std::char_traits<char>::length(end);
  }

  void parse_tag(Tag& tag) {
    tag = Tag{};
    std::size_t p = pos_ + 1;
    if (p < text_.size() && text_[p] == '/') tag.closing = true, ++p;
    const std::size_t name_begin = p;
    while (p < text_.size() && !std::isspace(static_cast<unsigned char>(text_[p])) && text_[p] != '>' &&
           text_[p] != '/')
      ++p;
    tag.name = local_name(text_.substr(name_begin, p - name_begin));
    if (tag.name.empty()) error("malformed tag");
    while (true) {
      while (p < text_.size() && std::isspace(static_cast<unsigned char>(text_[p]))) ++p;
      if (p >= text_.size()) error("unterminated tag <" + tag.name + ">");
      if (text_[p] == '>') {
        ++p;
        break;
      }
      if (text_[p] == '/' && p + 1 < text_.size() && text_[p + 1] == '>') {
        tag.self_closing = true;
        p += 2;
        break;
      }
      const std::size_t an = p;
      while (p < text_.size() && text_[p] != '=' && text_[p] != '>' &&
             !std::isspace(static_cast<unsigned char>(text_[p])))
        ++p;
      const std::string attribute = local_name(text_.substr(an, p - an));
      while (p < text_.size() && std::isspace(static_cast<unsigned char>(text_[p]))) ++p;
      if (p >= text_.size() || text_[p] != '=')
        error("attribute '" + attribute + "' of <" + tag.name + "> has no value");
      ++p;
      while (p < text_.size() && std::isspace(static_cast<unsigned char>(text_[p]))) ++p;
      if (p >= text_.size() || (text_[p] != '"' && text_[p] != '\''))
        error("attribute '" + attribute + "' of <" + tag.name + "> is not quoted");
      const char quote = text_[p++];
      const std::size_t close = text_.find(quote, p);
      if (close == std::string::npos) error("unterminated attribute '" + attribute + "'");
      tag.attributes[attribute] = decode_entities(text_.substr(p, close - p));
      p = close + 1;
    }
    pos_ = p;
  }

  const std::string& text_;
  std::string file_;
  std::size_t pos_ = 0;
};

double parse_number(const std::string& text, bool* ok) {
  const std::string t = trim(text);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  *ok = !t.empty() && end == t.c_str() + t.size() && std::isfinite(v);
  return v;
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

GpxTrack parse_gpx(const std::string& text, const std::string& file) {
  XmlScanner scanner(text, file);
  GpxTrack track;
  struct Point {
    double lat = 0, lon = 0, ele = 0, time = 0;
    bool has_time = false;
  };
  std::vector<Point> track_points, route_points;
  std::vector<std::string> stack;
  Tag tag;
  std::string between;
  bool saw_root = false;
  Point current;
  bool in_point = false;
  std::string point_kind;
  while (scanner.next(tag, between)) {
    if (!saw_root) {
      if (tag.closing || tag.name != "gpx")
        scanner.error("not a GPX file (the root element is <" + tag.name + ">, expected <gpx>)");
      saw_root = true;
    }
    if (tag.closing) {
      if (stack.empty() || stack.back() != tag.name)
        scanner.error("</" + tag.name + "> does not close " +
                      (stack.empty() ? std::string("anything") : "<" + stack.back() + ">"));
      const std::string value = trim(decode_entities(between));
      const std::string parent = stack.size() >= 2 ? stack[stack.size() - 2] : "";
      if (in_point && parent == point_kind) {
        bool ok = true;
        if (tag.name == "ele") {
          current.ele = parse_number(value, &ok);
          if (!ok) scanner.error("bad <ele> '" + value + "'");
        } else if (tag.name == "time") {
          try {
            current.time = parse_iso8601_utc(value);
          } catch (const Error& e) {
            scanner.error(e.what());
          }
          current.has_time = true;
        }
      }
      if (tag.name == "name" && parent == "trk" && track.name.empty()) track.name = value;
      if (in_point && tag.name == point_kind) {
        (point_kind == "trkpt" ? track_points : route_points).push_back(current);
        in_point = false;
      }
      stack.pop_back();
      continue;
    }
    if (tag.name == "trkpt" || tag.name == "rtept") {
      if (in_point) scanner.error("<" + tag.name + "> inside another point");
      current = Point{};
      auto lat = tag.attributes.find("lat"), lon = tag.attributes.find("lon");
      if (lat == tag.attributes.end() || lon == tag.attributes.end())
        scanner.error("<" + tag.name + "> without lat and lon");
      bool ok1 = false, ok2 = false;
      current.lat = parse_number(lat->second, &ok1);
      current.lon = parse_number(lon->second, &ok2);
      if (!ok1 || current.lat < -90 || current.lat > 90) scanner.error("bad latitude '" + lat->second + "'");
      if (!ok2 || current.lon < -180 || current.lon > 360)
        scanner.error("bad longitude '" + lon->second + "'");
      if (current.lon > 180) current.lon -= 360;
      point_kind = tag.name;
      if (tag.self_closing) {
        (point_kind == "trkpt" ? track_points : route_points).push_back(current);
        continue;
      }
      in_point = true;
    }
    if (!tag.self_closing) stack.push_back(tag.name);
  }
  if (!saw_root) throw file_error(file, "not a GPX file (no XML elements)");
  if (!stack.empty()) throw file_error(file, "ends inside <" + stack.back() + "> (truncated?)");
  const std::vector<Point>& points = track_points.empty() ? route_points : track_points;
  if (points.empty()) throw file_error(file, "no track points (<trkpt>) or route points (<rtept>)");
  std::vector<Point> timed;
  for (const Point& p : points) {
    if (p.has_time)
      timed.push_back(p);
    else
      ++track.samples_without_time;
  }
  if (timed.empty())
    throw file_error(
        file, "its " + std::to_string(points.size()) + " points have no <time>; frames are matched by time");
  std::stable_sort(timed.begin(), timed.end(),
                   [](const Point& a, const Point& b) { return a.time < b.time; });
  track.epoch_unix_s = timed.front().time;
  for (const Point& p : timed) {
    GpsSample s;
    s.time_s = p.time - track.epoch_unix_s;
    s.latitude_deg = p.lat;
    s.longitude_deg = p.lon;
    s.altitude_m = p.ele;
    track.samples.push_back(s);
  }
  return track;
}

GpxTrack read_gpx(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw file_error(file, "cannot open GPS track");
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw file_error(file, "cannot read GPS track");
  return parse_gpx(buffer.str(), file);
}

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
  if (dt > options.max_gap_s) return out;
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
