#include "model/path_io.h"

#include <algorithm>
#include <set>

#include "model/atomic_file.h"
#include "model/error.h"

namespace plenopath {
namespace {

double metres_per_path_unit(const JsonReader& units) {
  const std::string u = units.string();
  if (u == "m") return 1.0;
  if (u == "cm") return 0.01;
  if (u == "mm") return 0.001;
  if (u == "in") return 0.0254;
  if (u == "ft") return 0.3048;
  units.fail("unknown units '" + u + "' (expected m, cm, mm, in or ft)");
}

}  // namespace

nlohmann::json path_to_json(const CameraPath& path) {
  nlohmann::json frames = nlohmann::json::array();
  for (const auto& f : path.frames) {
    nlohmann::json j = {{"index", f.index}, {"x", f.x}, {"y", f.y}, {"heading_deg", degrees(f.heading)}};
    if (!f.file.empty()) j["file"] = f.file;
    if (f.confidence != 1.0) j["confidence"] = f.confidence;
    if (f.flags != kFrameOk) j["flags"] = f.flags;
    if (!f.reason.empty()) j["reason"] = f.reason;
    frames.push_back(std::move(j));
  }
  nlohmann::json j = {{"units", "m"}, {"frames", std::move(frames)}};
  if (!path.scale_source.empty()) j["scale_source"] = path.scale_source;
  return j;
}

CameraPath path_from_json(const JsonReader& reader) {
  CameraPath path;
  const double scale = reader.has("units") ? metres_per_path_unit(reader.at("units")) : 1.0;
  path.scale_source = reader.string_or("scale_source", "");
  const JsonReader frames = reader.at("frames");
  std::set<int> seen;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const JsonReader f = frames.at(i);
    PathFrame frame;
    frame.index = f.integer("index");
    if (frame.index < 0) f.at("index").fail("frame index must be >= 0");
    if (!seen.insert(frame.index).second)
      f.at("index").fail("duplicate frame index " + std::to_string(frame.index));
    frame.file = f.string_or("file", "");
    frame.x = f.number("x") * scale;
    frame.y = f.number("y") * scale;
    frame.heading = radians(f.number("heading_deg"));
    frame.confidence = f.number_or("confidence", 1.0);
    if (auto flags = f.find("flags")) {
      const int v = flags->integer();
      if (v < 0) flags->fail("flags must be >= 0");
      frame.flags = static_cast<std::uint32_t>(v);
    }
    frame.reason = f.string_or("reason", "");
    path.frames.push_back(std::move(frame));
  }
  std::sort(path.frames.begin(), path.frames.end(),
            [](const PathFrame& a, const PathFrame& b) { return a.index < b.index; });
  return path;
}

CameraPath read_path_file(const std::string& file) {
  const nlohmann::json json = read_json_file(file);
  return path_from_json(JsonReader(json, file));
}

void write_path_file(const CameraPath& path, const std::string& file) {
  write_file_atomically(
      file, path_to_json(path).dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n", false);
}

}  // namespace plenopath
