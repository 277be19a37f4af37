#pragma once
// Helpers shared by `plenopath render`, `stitch` and `sample`: plan loading, sizes, image writing.
#include <opencv2/core.hpp>
#include <string>

#include "model/floor_plan.h"

namespace plenopath::cli {

// "office-sample" = the built-in sample plan; otherwise a DXF file (processing/plan/dxf_import.h).
FloorPlan load_render_plan(const std::string& plan);
// "2048x1024" -> width, height; throws Error for anything else.
void parse_size(const std::string& text, int* width, int* height, const std::string& option);
// Comma-separated list, empty items dropped.
std::vector<std::string> split_list(const std::string& text);
// cv::imwrite that throws Error naming the file; JPEG quality applies to .jpg files.
void write_image(const std::string& file, const cv::Mat& image, int jpeg_quality = 92);
// "000042.jpg": the frame files `render` and `render-scene` write.
std::string numbered_file_name(int index, const char* ext);
// Depth in metres (CV_32F) to a 16-bit PNG in millimetres (0 = no hit).
void write_depth_png(const std::string& file, const cv::Mat& depth_m);

}  // namespace plenopath::cli
