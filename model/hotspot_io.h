#pragma once
// One hotspot as JSON, shared by the project file and the exported tour.json: corners in degrees,
// "media" written and read exactly as stored (callers make it relative, absolute or package-relative).
#include <nlohmann/json.hpp>

#include "model/hotspots.h"
#include "model/json_reader.h"

namespace plenopath {

nlohmann::json hotspot_to_json(const Hotspot& hotspot);
Hotspot hotspot_from_json(const JsonReader& reader);  // throws Error naming the file and JSON path

}  // namespace plenopath
