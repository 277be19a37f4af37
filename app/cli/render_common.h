#pragma once
// Helpers shared by `plenopath render`, `stitch` and `sample`: plan loading, sizes, image writing.
#include <opencv2/core.hpp>
#include <string>

#include "model/floor_plan.h"
#include "processing/capture/frame_files.h"

namespace plenopath::cli {

// "office-sample" = the built-in sample plan; otherwise a DXF file (processing/plan/dxf_import.h).
FloorPlan load_render_plan(const std::string& plan);
// "2048x1024" -> width, height; throws Error for anything else.
void parse_size(const std::string& text, int* width, int* height, const std::string& option);
// Comma-separated list, empty items dropped.
std::vector<std::string> split_list(const std::string& text);
// write_image, numbered_file_name, write_depth_png: processing/capture/frame_files.h.

}  // namespace plenopath::cli
