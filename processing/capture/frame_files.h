#pragma once
// Writing a capture's frames as `render` and `render-scene` lay them out: DIR/frames/NNNNNN.jpg and
// DIR/depth/NNNNNN.png (16-bit millimetres).
#include <opencv2/core.hpp>
#include <string>

namespace plenopath {

// cv::imwrite that throws Error naming the file; JPEG quality applies to .jpg files.
void write_image(const std::string& file, const cv::Mat& image, int jpeg_quality = 92);
// "000042.jpg": the frame files `render` and `render-scene` write.
std::string numbered_file_name(int index, const char* ext);
// Depth in metres (CV_32F) to a 16-bit PNG in millimetres (0 = no hit).
void write_depth_png(const std::string& file, const cv::Mat& depth_m);

}  // namespace plenopath
