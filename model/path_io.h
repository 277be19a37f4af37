#pragma once
// Path files, also the renderer's ground truth:
// {"units":"m","frames":[{"index":0,"file":"frames/000000.jpg","x":1.0,"y":2.0,"heading_deg":35.0}, ...]}
#include <nlohmann/json.hpp>
#include <string>

#include "model/camera_path.h"
#include "model/json_reader.h"

namespace plenopath {

CameraPath read_path_file(const std::string& file);
void write_path_file(const CameraPath& path, const std::string& file);

nlohmann::json path_to_json(const CameraPath& path);
// Accepts "units" m, cm, mm, in, ft (converted to metres); frames are sorted by index, duplicates rejected.
CameraPath path_from_json(const JsonReader& reader);

}  // namespace plenopath
