#include "app/cli/render_common.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "model/error.h"
#include "processing/plan/dxf_import.h"
#include "rig/synthetic_camera.h"

namespace plenopath::cli {

namespace fs = std::filesystem;

FloorPlan load_render_plan(const std::string& plan) {
  if (plan == "office-sample") return make_office_sample_plan();
  return import_dxf(plan);
}

void parse_size(const std::string& text, int* width, int* height, const std::string& option) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 8 ||
      h < 4 || w > 32768 || h > 16384)
    throw Error(option + ": expected WIDTHxHEIGHT such as 2048x1024, got '" + text + "'");
  *width = w;
  *height = h;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

void write_image(const std::string& file, const cv::Mat& image, int jpeg_quality) {
  std::vector<int> params;
  std::string lower = fs::path(file).extension().string();
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower == ".jpg" || lower == ".jpeg") params = {cv::IMWRITE_JPEG_QUALITY, jpeg_quality};
  bool ok = false;
  try {
    ok = cv::imwrite(file, image, params);
  } catch (const cv::Exception& e) {
    throw file_error(file, std::string("cannot write image: ") + e.what());
  }
  if (!ok) throw file_error(file, "cannot write image");
}

std::string numbered_file_name(int index, const char* ext) {
  char name[64];
  std::snprintf(name, sizeof name, "%06d.%s", index, ext);
  return name;
}

void write_depth_png(const std::string& file, const cv::Mat& depth_m) {
  cv::Mat mm;
  depth_m.convertTo(mm, CV_16U, 1000.0);  // rounds and saturates at 65.535 m
  write_image(file, mm);
}

}  // namespace plenopath::cli
