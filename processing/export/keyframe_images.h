#pragma once
// A keyframe's images in the package, each stored once: the full-resolution JPEG, and a small preview as a
// script (asset_script.h) that the player shows at once, from http and file:// alike. Where a browser
// refuses file:// JPEGs as textures, the player stays on the preview (resources/player/src/tour_data.js).
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "processing/export/package_writer.h"
#include "processing/export/tour_json.h"

namespace plenopath {

struct KeyframeImageEncoding {
  int full_width = 4096;     // pixels, even; the image is never upscaled
  int preview_width = 1024;  // pixels, even, <= full_width
  int quality = 85;          // full JPEG quality 1..100
  // The preview's JPEG quality: it is seen for a moment (or, from file://, at its low resolution anyway).
  // Measured on a POV-Ray patio frame and two office renders at 4096 (full JPEG q85: 430, 818, 772 KB), a
  // 1024-wide preview adds to the full JPEG: q85 11.5-13.0%, q70 7.5-9.0%, q60 6.2-7.5% (as base64: x4/3
  // in a folder, x~1.0 deflated in a zip). q60 keeps a 4096 package within 1.1x its full JPEGs both ways.
  int preview_quality = 60;
  void check() const;  // throws Error naming the bad field
};

struct KeyframeImageBytes {
  std::uintmax_t full = 0;     // the full JPEG
  std::uintmax_t preview = 0;  // the preview script (base64 JPEG)
};

// A keyframe's name in the package: "k000123" for frame 123 (images/k000123_full.jpg, tiles/k000123/).
std::string keyframe_stem(int frame);

// Changes the full JPEG's bytes before they are written (e.g. adds its photo tags, keyframe_metadata.h);
// `name` is its package path, for errors.
using JpegEdit =
    std::function<std::vector<unsigned char>(std::vector<unsigned char> jpeg, const std::string& name)>;

// Encodes `image` (BGR, 2:1) and writes images/kNNNNNN_full.jpg and images/kNNNNNN_preview.js; nothing of
// it stays in memory. Returns the names written (for tour.json) and fills `bytes` when given.
KeyframeImageFiles write_keyframe_images(PackageWriter& package, int frame, const cv::Mat& image,
                                         const KeyframeImageEncoding& encoding,
                                         KeyframeImageBytes* bytes = nullptr, const JpegEdit& edit_full = {});

}  // namespace plenopath
