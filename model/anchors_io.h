#pragma once
// Anchors files (and the project's "anchors" member): a JSON list of {"index", "x", "y"} in metres with an
// optional "heading_deg".
#include <nlohmann/json.hpp>
#include <string>

#include "model/anchors.h"
#include "model/json_reader.h"

namespace plenopath {

nlohmann::json anchors_to_json(const Anchors& anchors);
Anchors anchors_from_json(const JsonReader& reader);  // throws Error naming the file and JSON path
Anchors read_anchors_file(const std::string& file);
void write_anchors_file(const Anchors& anchors, const std::string& file);

}  // namespace plenopath
