#pragma once
// The project file `*.plenopath`: JSON with "format":"plenopath-project" and "version".
// Media paths are stored relative to the project file and resolved to absolute paths when loaded.
#include <nlohmann/json.hpp>
#include <string>

#include "model/project.h"

namespace plenopath {

// 2: keyframes record the visibility rule and the sampler's settings; enums are checked by name. Version 1
// files still load.
constexpr int kProjectFormatVersion = 2;
constexpr const char* kProjectFormatName = "plenopath-project";

// Throws Error naming the file and, for bad content, the JSON path of the bad value.
Project load_project(const std::string& file);
// Atomic: a temporary file, flushed, renamed; the previous file is kept as FILE.bak.
void save_project(const Project& project, const std::string& file);

// The JSON forms, for autosave, snapshots and tests. base_dir: folder that relative paths refer to.
nlohmann::json project_to_json(const Project& project, const std::string& base_dir);
Project project_from_json(const nlohmann::json& json, const std::string& base_dir,
                          const std::string& file_for_errors);

}  // namespace plenopath
