// GPX through expat: a real XML parser (encodings, character references, CDATA, namespaces), where the
// reader before 0.6 was a hand-written scanner that turned non-ASCII references into '?'.
#include <expat.h>

#include <cctype>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "model/error.h"
#include "processing/capture/gps_track.h"
#include "processing/capture/gps_track_internal.h"

namespace plenopath {
namespace {

constexpr char kNamespaceSeparator = '\x01';

// "uri\x01local" (namespaced) or "local": the local name only, so GPX 1.0, 1.1 and unqualified files read
// alike.
std::string local_name(const XML_Char* name) {
  const char* sep = std::strrchr(name, kNamespaceSeparator);
  return sep ? std::string(sep + 1) : std::string(name);
}

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t' || s[b] == '\n' || s[b] == '\r')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == '\n' || s[e - 1] == '\r')) --e;
  return s.substr(b, e - b);
}

// windows-1252, which Windows GPS tools declare, is not among expat's built-in encodings.
int unknown_encoding(void*, const XML_Char* name, XML_Encoding* info) {
  std::string n(name);
  for (char& c : n) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (n != "windows-1252" && n != "cp1252" && n != "x-cp1252") return XML_STATUS_ERROR;
  static const int high[32] = {0x20AC, -1,     0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021,
                               0x02C6, 0x2030, 0x0160, 0x2039, 0x0152, -1,     0x017D, -1,
                               -1,     0x2018, 0x2019, 0x201C, 0x201D, 0x2022, 0x2013, 0x2014,
                               0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, -1,     0x017E, 0x0178};
  for (int i = 0; i < 256; ++i) info->map[i] = i >= 0x80 && i < 0xA0 ? high[i - 0x80] : i;
  info->data = nullptr;
  info->convert = nullptr;
  info->release = nullptr;
  return XML_STATUS_OK;
}

struct GpxParse {
  XML_Parser parser = nullptr;
  std::string file;
  std::string error;  // set by a handler, which then stops the parser (C code cannot be thrown through)
  std::vector<std::string> stack;
  std::string text;  // character data of the innermost open element
  bool saw_root = false;
  bool in_point = false;
  std::string point_kind;
  GpsPoint current;
  std::vector<GpsPoint> track_points, route_points;
  GpsTrack track;

  void fail(const std::string& what) {
    if (!error.empty()) return;
    error = "line " + std::to_string(XML_GetCurrentLineNumber(parser)) + ": " + what;
    XML_StopParser(parser, XML_FALSE);
  }
};

const char* attribute(const XML_Char** attributes, const char* wanted) {
  for (int i = 0; attributes[i]; i += 2)
    if (local_name(attributes[i]) == wanted) return attributes[i + 1];
  return nullptr;
}

void XMLCALL on_start(void* data, const XML_Char* qualified, const XML_Char** attributes) {
  auto& g = *static_cast<GpxParse*>(data);
  const std::string name = local_name(qualified);
  if (!g.saw_root) {
    if (name != "gpx") return g.fail("not a GPX file (the root element is <" + name + ">, expected <gpx>)");
    g.saw_root = true;
  }
  g.stack.push_back(name);
  g.text.clear();
  if (name != "trkpt" && name != "rtept") return;
  if (g.in_point) return g.fail("<" + name + "> inside another point");
  g.current = GpsPoint{};
  const char* lat = attribute(attributes, "lat");
  const char* lon = attribute(attributes, "lon");
  if (!lat || !lon) return g.fail("<" + name + "> without lat and lon");
  bool ok_lat = false, ok_lon = false;
  g.current.lat = parse_gps_number(lat, &ok_lat);
  g.current.lon = parse_gps_number(lon, &ok_lon);
  if (!ok_lat || g.current.lat < -90 || g.current.lat > 90)
    return g.fail("bad latitude '" + std::string(lat) + "'");
  if (!ok_lon || g.current.lon < -180 || g.current.lon > 360)
    return g.fail("bad longitude '" + std::string(lon) + "'");
  if (g.current.lon > 180) g.current.lon -= 360;
  g.in_point = true;
  g.point_kind = name;
}

void XMLCALL on_end(void* data, const XML_Char* qualified) {
  auto& g = *static_cast<GpxParse*>(data);
  const std::string name = local_name(qualified);
  const std::string value = trim(g.text);
  g.text.clear();
  const std::string parent = g.stack.size() >= 2 ? g.stack[g.stack.size() - 2] : "";
  if (g.in_point && parent == g.point_kind) {
    if (name == "ele") {
      bool ok = true;
      g.current.ele = parse_gps_number(value, &ok);
      if (!ok) return g.fail("bad <ele> '" + value + "'");
    } else if (name == "time") {
      try {
        g.current.time = parse_iso8601_utc(value);
      } catch (const Error& e) {
        return g.fail(e.what());
      }
      g.current.has_time = true;
    }
  }
  if (name == "name" && parent == "trk" && g.track.name.empty()) g.track.name = value;
  if (g.in_point && name == g.point_kind) {
    (g.point_kind == "trkpt" ? g.track_points : g.route_points).push_back(g.current);
    g.in_point = false;
  }
  if (!g.stack.empty()) g.stack.pop_back();
}

void XMLCALL on_text(void* data, const XML_Char* s, int length) {
  auto& g = *static_cast<GpxParse*>(data);
  if (g.text.size() < 4096) g.text.append(s, static_cast<std::size_t>(length));  // values are short
}

}  // namespace

GpsTrack parse_gpx(const std::string& text, const std::string& file) {
  GpxParse g;
  g.file = file;
  g.parser = XML_ParserCreateNS(nullptr, kNamespaceSeparator);
  if (!g.parser) throw file_error(file, "out of memory for the XML parser");
  struct Free {
    XML_Parser p;
    ~Free() { XML_ParserFree(p); }
  } free_parser{g.parser};
  XML_SetUserData(g.parser, &g);
  XML_SetElementHandler(g.parser, on_start, on_end);
  XML_SetCharacterDataHandler(g.parser, on_text);
  XML_SetUnknownEncodingHandler(g.parser, unknown_encoding, nullptr);
  // External entities and DTDs are never fetched: expat does not load them unless asked.
  if (text.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw file_error(file, "GPS track larger than 2 GB");
  const XML_Status status = XML_Parse(g.parser, text.data(), static_cast<int>(text.size()), XML_TRUE);
  if (!g.error.empty()) throw file_error(file, g.error);
  if (status != XML_STATUS_OK) {
    const XML_Error code = XML_GetErrorCode(g.parser);
    const std::string what =
        code == XML_ERROR_NO_ELEMENTS && !g.saw_root ? "not a GPX file (no XML elements)"
        : code == XML_ERROR_NO_ELEMENTS || code == XML_ERROR_UNCLOSED_TOKEN
            ? std::string("ends inside <") + (g.stack.empty() ? "gpx" : g.stack.back()) + "> (truncated?)"
            : XML_ErrorString(code);
    throw file_error(file, "line " + std::to_string(XML_GetCurrentLineNumber(g.parser)) + ": " + what);
  }
  const bool tracks = !g.track_points.empty();
  return gps_track_from_points(tracks ? g.track_points : g.route_points, g.track, file,
                               "track points (<trkpt>) or route points (<rtept>)");
}

}  // namespace plenopath
