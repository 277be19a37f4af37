#include "processing/capture/frame_files.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "model/error.h"

namespace plenopath {

namespace fs = std::filesystem;

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

}  // namespace plenopath
