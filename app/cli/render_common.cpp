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

}  // namespace plenopath::cli
