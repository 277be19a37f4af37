#pragma once
// Cheap checks of an image file without decoding it: the format from its magic bytes, the size from its
// header (JPEG, PNG, TIFF, OpenEXR) and signs of truncation (JPEG end-of-image marker, PNG IEND chunk).
// Lets a 100 000-frame folder be scanned in seconds; decoding finds the rest.
#include <iosfwd>
#include <string>

namespace plenopath {

struct ImageHeader {
  bool ok = false;
  std::string format;  // "jpeg", "png", "tiff", "exr"
  int width = 0;       // 0 if the header did not say (then decode to learn it)
  int height = 0;
  std::string problem;  // why !ok, e.g. "empty file", "corrupt JPEG (truncated: no end-of-image marker)"
};

ImageHeader read_image_header(const std::string& path);
// The same checks on bytes in memory (for the fuzz target and for archives).
ImageHeader read_image_header_from_memory(const std::string& bytes);
ImageHeader read_image_header(std::istream& in);

}  // namespace plenopath
