#include "processing/export/keyframe_images.h"

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "model/error.h"
#include "processing/export/asset_script.h"

namespace plenopath {
namespace {

std::vector<unsigned char> encode_jpeg(const cv::Mat& image, int width, int quality) {
  cv::Mat resized;
  if (width < image.cols)
    cv::resize(image, resized, cv::Size(width, width / 2), 0, 0, cv::INTER_AREA);
  else
    resized = image;
  std::vector<unsigned char> bytes;
  if (!cv::imencode(".jpg", resized, bytes,
                    {cv::IMWRITE_JPEG_QUALITY, quality, cv::IMWRITE_JPEG_PROGRESSIVE, 1}))
    throw Error("JPEG encoding failed");
  return bytes;
}

}  // namespace

void KeyframeImageEncoding::check() const {
  if (full_width < 2) throw Error("keyframe images: full_width must be at least 2 pixels");
  if (preview_width < 2 || preview_width > full_width)
    throw Error("keyframe images: preview_width must be within 2..full_width pixels");
  if (quality < 1 || quality > 100) throw Error("keyframe images: quality must be within 1..100");
  if (preview_quality < 1 || preview_quality > 100)
    throw Error("keyframe images: preview_quality must be within 1..100");
}

std::string keyframe_stem(int frame) {
  char stem[32];
  std::snprintf(stem, sizeof stem, "k%06d", frame);
  return stem;
}

KeyframeImageFiles write_keyframe_images(PackageWriter& package, int frame, const cv::Mat& image,
                                         const KeyframeImageEncoding& encoding, KeyframeImageBytes* bytes,
                                         const JpegEdit& edit_full) {
  encoding.check();
  const std::string stem = "images/" + keyframe_stem(frame);
  KeyframeImageFiles files;
  files.frame = frame;
  files.full = std::string(stem) + "_full.jpg";
  files.preview = std::string(stem) + "_preview.js";
  {
    std::vector<unsigned char> full = encode_jpeg(image, encoding.full_width, encoding.quality);
    if (edit_full) full = edit_full(std::move(full), files.full);
    package.add(files.full, full.data(), full.size());
    if (bytes) bytes->full = full.size();
  }
  const std::vector<unsigned char> jpeg =
      encode_jpeg(image, encoding.preview_width, encoding.preview_quality);
  const std::string script = asset_script(files.preview, "image/jpeg", jpeg.data(), jpeg.size());
  package.add(files.preview, script);
  if (bytes) bytes->preview = script.size();
  return files;
}

}  // namespace plenopath
