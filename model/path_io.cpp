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
    if (f.piece != 0) j["piece"] = f.piece;
    frames.push_back(std::move(j));
  }
  nlohmann::json j = {{"units", "m"}, {"frames", std::move(frames)}};
  if (!path.scale_source.empty()) j["scale_source"] = path.scale_source;
  if (!path.pieces.empty()) {
    nlohmann::json pieces = nlohmann::json::array();
    for (const PathPiece& p : path.pieces) {
      nlohmann::json q = {{"first_index", p.first_index},
                          {"last_index", p.last_index},
                          {"placed", p.placed},
                          {"scale_factor", p.scale_factor}};
      if (!p.scale_source.empty()) q["scale_source"] = p.scale_source;
      if (!p.break_reason.empty()) q["break_reason"] = p.break_reason;
      pieces.push_back(std::move(q));
    }
    j["pieces"] = std::move(pieces);
  }
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
    frame.heading = radians_of_written(f.number("heading_deg"));
    frame.confidence = f.number_or("confidence", 1.0);
    if (auto flags = f.find("flags")) {
      const int v = flags->integer();
      if (v < 0) flags->fail("flags must be >= 0");
      frame.flags = static_cast<std::uint32_t>(v);
    }
    frame.reason = f.string_or("reason", "");
    if (auto piece = f.find("piece")) {
      frame.piece = piece->integer();
      if (frame.piece < 0) piece->fail("piece must be >= 0");
    }
    path.frames.push_back(std::move(frame));
  }
  std::sort(path.frames.begin(), path.frames.end(),
            [](const PathFrame& a, const PathFrame& b) { return a.index < b.index; });
  if (auto pieces = reader.find("pieces")) {
    for (std::size_t k = 0; k < pieces->size(); ++k) {
      const JsonReader q = pieces->at(k);
      PathPiece p;
      p.first_index = q.integer("first_index");
      p.last_index = q.integer("last_index");
      if (p.last_index < p.first_index) q.at("last_index").fail("last_index must be >= first_index");
      p.placed = q.boolean_or("placed", true);
      p.scale_source = q.string_or("scale_source", "");
      p.scale_factor = q.number_or("scale_factor", 1.0);
      p.break_reason = q.string_or("break_reason", "");
      path.pieces.push_back(std::move(p));
    }
  }
  // Every frame's piece must be described, and pieces follow each other in capture order.
  const int piece_count = static_cast<int>(path.pieces.size());
  int previous_piece = 0;
  for (const PathFrame& f : path.frames) {
    if (f.piece != 0 && f.piece >= piece_count)
      frames.fail("frame " + std::to_string(f.index) + " is in piece " + std::to_string(f.piece) +
                  " but the path describes " + std::to_string(piece_count) + " pieces");
    if (f.piece < previous_piece)
      frames.fail("frame " + std::to_string(f.index) + " goes back to piece " + std::to_string(f.piece) +
                  ": pieces must follow each other in capture order");
    previous_piece = f.piece;
  }
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
