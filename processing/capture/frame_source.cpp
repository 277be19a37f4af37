#include "processing/capture/frame_source.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "processing/capture/frame_source_internal.h"
#include "processing/capture/image_header.h"
#include "processing/capture/video_decoder.h"

namespace fs = std::filesystem;

namespace plenopath {

void FrameSourceOptions::check() const {
  if (first_frame < 0)
    throw Error("capture options: first_frame must be >= 0 (is " + std::to_string(first_frame) + ")");
  if (last_frame < -1)
    throw Error("capture options: last_frame must be >= 0, or -1 for the end (is " +
                std::to_string(last_frame) + ")");
  if (last_frame >= 0 && last_frame < first_frame)
    throw Error("capture options: last_frame " + std::to_string(last_frame) + " is before first_frame " +
                std::to_string(first_frame));
  if (stride < 1) throw Error("capture options: stride must be >= 1 (is " + std::to_string(stride) + ")");
  if (!(folder_frame_rate > 0.0) || !std::isfinite(folder_frame_rate))
    throw Error("capture options: folder_frame_rate must be a positive number of frames per second");
  if (stitch_width < 8 || stitch_width % 2 != 0)
    throw Error("capture options: stitch_width must be an even number of at least 8 pixels (is " +
                std::to_string(stitch_width) + ")");
}

bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const bool da = std::isdigit(static_cast<unsigned char>(a[i])),
               db = std::isdigit(static_cast<unsigned char>(b[j]));
    if (da && db) {
      std::size_t ei = i, ej = j;
      while (ei < a.size() && std::isdigit(static_cast<unsigned char>(a[ei]))) ++ei;
      while (ej < b.size() && std::isdigit(static_cast<unsigned char>(b[ej]))) ++ej;
      // Compare digit runs as numbers of any length: skip leading zeros, then longer is larger.
      std::size_t si = i, sj = j;
      while (si + 1 < ei && a[si] == '0') ++si;
      while (sj + 1 < ej && b[sj] == '0') ++sj;
      if (ei - si != ej - sj) return ei - si < ej - sj;
      const int c = a.compare(si, ei - si, b, sj, ej - sj);
      if (c != 0) return c < 0;
      i = ei;
      j = ej;
    } else {
      const int ca = std::tolower(static_cast<unsigned char>(a[i])),
                cb = std::tolower(static_cast<unsigned char>(b[j]));
      if (ca != cb) return ca < cb;
      ++i;
      ++j;
    }
  }
  if ((a.size() - i) != (b.size() - j)) return (a.size() - i) < (b.size() - j);
  return a < b;
}

namespace frame_source_detail {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool is_frame_extension(const std::string& ext) {
  const std::string e = lower(ext);
  return e == ".jpg" || e == ".jpeg" || e == ".png" || e == ".tif" || e == ".tiff" || e == ".exr";
}
bool is_depth_extension(const std::string& ext) {
  const std::string e = lower(ext);
  return e == ".png" || e == ".exr" || e == ".tif" || e == ".tiff";
}

// The last run of digits in a file stem, as a number (-1 if none or absurdly long).
long long trailing_number(const std::string& stem, std::string* pattern, int* digits) {
  std::size_t end = stem.size();
  while (end > 0 && !std::isdigit(static_cast<unsigned char>(stem[end - 1]))) --end;
  if (end == 0) return -1;
  std::size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  if (end - begin > 15) return -1;
  if (pattern) *pattern = stem.substr(0, begin) + "#" + stem.substr(end);
  if (digits) *digits = static_cast<int>(end - begin);
  return std::stoll(stem.substr(begin, end - begin));
}

std::string stem_of(const std::string& name) { return fs::path(name).stem().string(); }

void check_aspect(int width, int height, bool require_2to1, const std::string& where) {
  if (width <= 0 || height <= 0) throw file_error(where, "frames have no size");
  if (require_2to1 && std::abs(width - 2 * height) > 1) {
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.3g", double(width) / height);
    throw file_error(where, "frames are " + std::to_string(width) + "x" + std::to_string(height) +
                                " (aspect " + ratio +
                                ":1), not 2:1; equirectangular 360° frames must be twice as wide as high "
                                "(import anyway with require_2to1 = false / --any-aspect)");
  }
}

}  // namespace frame_source_detail

namespace frame_source_detail {

// Any decoded image -> 8-bit BGR: grey and alpha handled, 16-bit scaled, float (EXR) clamped and
// gamma-encoded.
cv::Mat to_bgr8(const cv::Mat& image) {
  cv::Mat m = image;
  if (m.depth() == CV_16U) {
    m.convertTo(m, CV_8U, 1.0 / 257.0);
  } else if (m.depth() == CV_32F || m.depth() == CV_64F) {
    cv::Mat f;
    m.convertTo(f, CV_32F);
    cv::patchNaNs(f, 0.0);
    cv::min(cv::max(f, 0.0), 1.0, f);
    cv::pow(f, 1.0 / 2.2, f);
    f.convertTo(m, CV_8U, 255.0);
  } else if (m.depth() != CV_8U) {
    m.convertTo(m, CV_8U);
  }
  if (m.channels() == 1)
    cv::cvtColor(m, m, cv::COLOR_GRAY2BGR);
  else if (m.channels() == 4)
    cv::cvtColor(m, m, cv::COLOR_BGRA2BGR);
  else if (m.channels() == 2) {
    std::vector<cv::Mat> planes;
    cv::split(m, planes);
    cv::cvtColor(planes[0], m, cv::COLOR_GRAY2BGR);
  }
  return m;
}

cv::Mat shrink_to_width(const cv::Mat& image, int max_width) {
  if (image.cols <= max_width) return image;
  const int h = std::max(1, static_cast<int>(std::lround(double(image.rows) * max_width / image.cols)));
  cv::Mat out;
  cv::resize(image, out, cv::Size(max_width, h), 0, 0, cv::INTER_AREA);
  return out;
}

}  // namespace frame_source_detail

namespace {

using frame_source_detail::Backend;
using frame_source_detail::is_frame_extension;
using frame_source_detail::looks_like_video;
using frame_source_detail::open_folder;
using frame_source_detail::open_video;
using frame_source_detail::to_bgr8;

struct GeneratorBackend : Backend {
  const FrameSource::Impl* impl = nullptr;
  std::function<cv::Mat(int)> generate;
  cv::Mat read(int i) override {
    cv::Mat m;
    try {
      m = generate(i);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw file_error(impl->source, "frame " + std::to_string(i) + " could not be generated: " + e.what());
    }
    if (m.empty()) throw file_error(impl->source, "frame " + std::to_string(i) + " could not be generated");
    m = to_bgr8(m);
    if (m.cols != impl->width || m.rows != impl->height)
      throw file_error(impl->source, "generated frame " + std::to_string(i) + " has the wrong size");
    return m;
  }
};

}  // namespace

// ---------------------------------------------------------------------------------------------------------

FrameSource::FrameSource(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FrameSource::~FrameSource() = default;

std::unique_ptr<FrameSource> FrameSource::open(const std::string& folder_or_video,
                                               const FrameSourceOptions& options) {
  options.check();
  std::error_code ec;
  const fs::path path(folder_or_video);
  if (!fs::exists(path, ec)) throw file_error(folder_or_video, "does not exist");
  std::unique_ptr<Impl> impl;
  if (fs::is_directory(path, ec)) {
    if (fs::exists(path / kRigFileName, ec)) return open_multi_head_folder(folder_or_video, options, nullptr);
    impl = open_folder(path, options, nullptr);
  } else {
    if (is_frame_extension(path.extension().string()))
      throw file_error(folder_or_video, "is a single image; open the folder that holds the frames");
    if (!looks_like_video(folder_or_video) && path.extension().string().empty())
      throw file_error(folder_or_video, "is neither a folder of frames nor a video file");
    impl = open_video(folder_or_video, options);
  }
  frame_source_detail::match_depth(*impl);
  return std::unique_ptr<FrameSource>(new FrameSource(std::move(impl)));
}

std::unique_ptr<FrameSource> FrameSource::open_capture(const Capture& capture) {
  FrameSourceOptions options;
  options.first_frame = capture.first_frame;
  options.stride = std::max(1, capture.stride);
  options.depth_folder = capture.depth_folder;
  options.require_2to1 = false;  // the project already holds this capture; do not refuse it now
  switch (capture.kind) {
    case CaptureKind::kNone:
      throw Error("the project has no capture");
    case CaptureKind::kVideo: {
      if (capture.frame_count > 0) options.last_frame = capture.frame_index_of_kept(capture.frame_count - 1);
      return open(capture.source, options);
    }
    case CaptureKind::kImageFolder: {
      options.folder_frame_rate = capture.frame_rate > 0 ? capture.frame_rate : 30.0;
      std::error_code ec;
      if (!fs::is_directory(capture.source, ec))
        throw file_error(capture.source, "capture folder does not exist");
      if (fs::exists(fs::path(capture.source) / kRigFileName, ec)) {
        if (capture.width > 0) options.stitch_width = capture.width;
        if (capture.frame_names.empty()) options.first_frame = 0;
        return open_multi_head_folder(capture.source, options,
                                      capture.frame_names.empty() ? nullptr : &capture.frame_names);
      }
      std::unique_ptr<Impl> impl;
      if (capture.frame_names.empty()) {
        options.first_frame = 0;  // no list: take the folder as it is
        impl = open_folder(capture.source, options, nullptr);
      } else {
        impl = open_folder(capture.source, options, &capture.frame_names);
      }
      frame_source_detail::match_depth(*impl);
      return std::unique_ptr<FrameSource>(new FrameSource(std::move(impl)));
    }
  }
  throw Error("unknown capture kind");
}

std::unique_ptr<FrameSource> FrameSource::from_generator(int frame_count, int width, int height,
                                                         double frame_rate,
                                                         std::function<cv::Mat(int)> generate,
                                                         const std::string& description) {
  if (frame_count <= 0 || width <= 0 || height <= 0 || !(frame_rate > 0.0) || !generate)
    throw Error(description + ": a generated capture needs frames, a size, a frame rate and a generator");
  auto impl = std::make_unique<Impl>();
  impl->kind = CaptureKind::kNone;
  impl->source = description;
  impl->width = width;
  impl->height = height;
  impl->frame_rate = frame_rate;
  impl->options.require_2to1 = false;
  // Names and times are computed, not stored per frame, when the capture is large? Keep it simple: a
  // 100 000-frame capture costs a few MB here, far below one decoded frame cache.
  impl->names.reserve(frame_count);
  impl->numbers.reserve(frame_count);
  impl->timestamps.reserve(frame_count);
  for (int i = 0; i < frame_count; ++i) {
    impl->names.push_back("frame " + std::to_string(i));
    impl->numbers.push_back(i);
    impl->timestamps.push_back(i / frame_rate);
  }
  impl->depth_names.assign(frame_count, "");
  auto backend = std::make_unique<GeneratorBackend>();
  backend->impl = impl.get();
  backend->generate = std::move(generate);
  impl->backend = std::move(backend);
  return std::unique_ptr<FrameSource>(new FrameSource(std::move(impl)));
}

CaptureKind FrameSource::kind() const { return impl_->kind; }
const std::string& FrameSource::source() const { return impl_->source; }
int FrameSource::frame_count() const { return static_cast<int>(impl_->names.size()); }
int FrameSource::width() const { return impl_->width; }
int FrameSource::height() const { return impl_->height; }
double FrameSource::frame_rate() const { return impl_->frame_rate; }
const FrameSourceOptions& FrameSource::options() const { return impl_->options; }
int FrameSource::head_count() const { return impl_->head_count; }

std::string FrameSource::frame_name(int i) const {
  impl_->check_index(i);
  return impl_->names[i];
}
int FrameSource::frame_number(int i) const {
  impl_->check_index(i);
  return static_cast<int>(impl_->numbers[i]);
}
double FrameSource::timestamp_s(int i) const {
  impl_->check_index(i);
  return impl_->timestamps[i];
}

cv::Mat FrameSource::read(int i) {
  impl_->check_index(i);
  return impl_->backend->read(i);
}

cv::Mat FrameSource::read_thumbnail(int i, int max_width) {
  impl_->check_index(i);
  if (max_width < 1) throw Error("thumbnail width must be positive");
  return impl_->backend->read_thumbnail(i, max_width);
}

std::vector<SkippedFrame> FrameSource::skipped() const { return impl_->skipped; }

bool FrameSource::has_depth(int i) const {
  impl_->check_index(i);
  return !impl_->depth_names[i].empty();
}
int FrameSource::depth_match_count() const { return impl_->depth_matches; }
std::string FrameSource::depth_name(int i) const {
  impl_->check_index(i);
  return impl_->depth_names[i];
}

cv::Mat FrameSource::read_depth(int i) {
  impl_->check_index(i);
  if (impl_->depth_names[i].empty())
    throw file_error(impl_->options.depth_folder.empty() ? impl_->source : impl_->options.depth_folder,
                     "no depth map for frame " + impl_->names[i]);
  const std::string path = (fs::path(impl_->options.depth_folder) / impl_->depth_names[i]).string();
  cv::Mat raw;
  try {
    raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw file_error(path, std::string("cannot read depth map: ") + e.what());
  }
  if (raw.empty()) throw file_error(path, "cannot read depth map (corrupt or unreadable)");
  if (raw.channels() > 1) {
    std::vector<cv::Mat> planes;
    cv::split(raw, planes);
    raw = planes[0];
  }
  cv::Mat metres;
  if (raw.depth() == CV_16U) {
    raw.convertTo(metres, CV_32F, 0.001);  // millimetres; 0 stays 0 = no hit
  } else if (raw.depth() == CV_32F || raw.depth() == CV_64F) {
    raw.convertTo(metres, CV_32F);
    cv::patchNaNs(metres, 0.0);
    cv::Mat bad = (metres < 0) | (metres > 1e7);  // infinities and negatives mean "no hit"
    metres.setTo(0.0f, bad);
  } else {
    throw file_error(path, "depth map must be a 16-bit PNG in millimetres or a 32-bit float EXR in metres");
  }
  if (metres.cols != impl_->width || metres.rows != impl_->height)
    throw file_error(path, "depth map is " + std::to_string(metres.cols) + "x" + std::to_string(metres.rows) +
                               ", the frames are " + std::to_string(impl_->width) + "x" +
                               std::to_string(impl_->height));
  return metres;
}

Capture capture_from_frame_source(const FrameSource& source, Capture capture) {
  constexpr double kEvenlySpacedToleranceS = 1e-4;
  if (source.kind() == CaptureKind::kNone)
    throw Error(source.source() + ": a generated capture cannot be stored in a project");
  capture.kind = source.kind();
  capture.source = source.source();
  capture.frame_count = source.frame_count();
  capture.width = source.width();
  capture.height = source.height();
  capture.frame_rate = source.frame_rate();
  capture.first_frame = source.options().first_frame;
  capture.stride = source.options().stride;
  capture.frame_names.clear();
  if (source.kind() == CaptureKind::kImageFolder) {
    capture.frame_names.reserve(source.frame_count());
    for (int i = 0; i < source.frame_count(); ++i) capture.frame_names.push_back(source.frame_name(i));
  }
  // Real time stamps only where they differ from the nominal rate (variable-rate video, phones): a
  // constant-rate capture keeps its project file small.
  capture.frame_times_s.clear();
  if (source.kind() == CaptureKind::kVideo) {
    // The nominal times: the capture's own (frame_times_s is empty so far).
    bool even = true;
    for (int i = 0; i < source.frame_count() && even; ++i)
      even = std::abs(source.timestamp_s(i) - capture.frame_time_s(i)) <= kEvenlySpacedToleranceS;
    if (!even)
      for (int i = 0; i < source.frame_count(); ++i) capture.frame_times_s.push_back(source.timestamp_s(i));
  }
  capture.depth_folder = source.options().depth_folder;
  return capture;
}

}  // namespace plenopath
