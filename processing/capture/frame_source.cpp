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

namespace {

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
long long trailing_number(const std::string& stem, std::string* pattern = nullptr, int* digits = nullptr) {
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

}  // namespace

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
using frame_source_detail::shrink_to_width;
using frame_source_detail::to_bgr8;

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

}  // namespace

namespace {

struct FolderBackend : Backend {
  const FrameSource::Impl* impl = nullptr;
  fs::path folder;
  cv::Mat read(int i) override {
    const std::string path = (folder / impl->names[i]).string();
    cv::Mat raw;
    try {
      raw = cv::imread(path, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception& e) {
      throw file_error(path, std::string("cannot decode frame: ") + e.what());
    }
    if (raw.empty()) throw file_error(path, "cannot decode frame (corrupt or unreadable image)");
    cv::Mat bgr = to_bgr8(raw);
    if (bgr.cols != impl->width || bgr.rows != impl->height)
      throw file_error(path, "frame is " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
                                 ", the capture's frames are " + std::to_string(impl->width) + "x" +
                                 std::to_string(impl->height));
    return bgr;
  }
  cv::Mat read_thumbnail(int i, int max_width) override {
    const std::string ext = lower(fs::path(impl->names[i]).extension().string());
    if (ext != ".jpg" && ext != ".jpeg") return shrink_to_width(read(i), max_width);
    // JPEG decodes at 1/2, 1/4 or 1/8 size directly: much faster for thumbnails.
    int flag = cv::IMREAD_COLOR;
    if (impl->width >= 8 * max_width)
      flag = cv::IMREAD_REDUCED_COLOR_8;
    else if (impl->width >= 4 * max_width)
      flag = cv::IMREAD_REDUCED_COLOR_4;
    else if (impl->width >= 2 * max_width)
      flag = cv::IMREAD_REDUCED_COLOR_2;
    const std::string path = (folder / impl->names[i]).string();
    cv::Mat small;
    try {
      small = cv::imread(path, flag);
    } catch (const cv::Exception& e) {
      throw file_error(path, std::string("cannot decode frame: ") + e.what());
    }
    if (small.empty()) throw file_error(path, "cannot decode frame (corrupt or unreadable image)");
    return shrink_to_width(small, max_width);
  }
};

struct VideoBackend : Backend {
  const FrameSource::Impl* impl = nullptr;
  std::mutex mutex;
  std::unique_ptr<VideoDecoder> decoder;  // frame-exact: decodes on when reading in order, else seeks

  cv::Mat read(int i) override {
    const long long raw = impl->numbers[i];
    cv::Mat frame;
    {
      std::lock_guard<std::mutex> lock(mutex);
      frame = decoder->read(static_cast<int>(raw));
    }
    if (frame.cols != impl->width || frame.rows != impl->height)
      throw file_error(impl->source, "frame " + std::to_string(raw) + " is " + std::to_string(frame.cols) +
                                         "x" + std::to_string(frame.rows) + ", expected " +
                                         std::to_string(impl->width) + "x" + std::to_string(impl->height));
    return frame;
  }
};

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

// Numbering of a folder's files: the common name pattern and the usual step between numbers, so that gaps
// are reported as missing frames and time stamps follow the numbers.
struct Numbering {
  bool consistent = false;  // every file has a number, one name pattern, unique numbers
  bool counter = false;     // ... and the numbers count frames: few gaps (not clock times or dates)
  long long first = 0;      // number of the first file in sort order
  long long step = 1;       // most common difference between consecutive numbers
  int digits = 0;           // zero-padded width, if all names share it
  std::string pattern;      // stem with the number replaced by '#'
  std::string extension;
};

Numbering analyse_numbering(const std::vector<std::string>& sorted_names) {
  Numbering n;
  if (sorted_names.empty()) return n;
  std::vector<long long> numbers;
  std::map<long long, int> steps;
  for (const std::string& name : sorted_names) {
    std::string pattern;
    int digits = 0;
    const long long v = trailing_number(stem_of(name), &pattern, &digits);
    if (v < 0) return n;
    if (numbers.empty()) {
      n.pattern = pattern;
      n.digits = digits;
      n.extension = fs::path(name).extension().string();
    } else if (pattern != n.pattern) {
      return n;
    }
    if (digits != n.digits) n.digits = 0;
    if (!numbers.empty()) {
      if (v <= numbers.back()) return n;  // duplicates or odd order: no numbering to trust
      ++steps[v - numbers.back()];
    }
    numbers.push_back(v);
  }
  n.consistent = true;
  n.first = numbers.front();
  int best = 0;
  for (const auto& [step, count] : steps)
    if (count > best) best = count, n.step = step;
  // Names like VID_120059, VID_120100 (clock times) leave big "gaps": such numbers are not frame counters,
  // so neither gaps nor time stamps are taken from them.
  const long long span = (numbers.back() - numbers.front()) / n.step + 1;
  const long long missing = span - static_cast<long long>(numbers.size());
  n.counter = 4 * missing <= static_cast<long long>(numbers.size());
  return n;
}

std::string numbered_name(const Numbering& n, long long number) {
  std::string digits = std::to_string(number);
  if (n.digits > static_cast<int>(digits.size()))
    digits = std::string(n.digits - digits.size(), '0') + digits;
  std::string stem = n.pattern;
  stem.replace(stem.find('#'), 1, digits);
  return stem + n.extension;
}

std::vector<std::string> list_files(const fs::path& folder, bool (*accept)(const std::string&)) {
  std::vector<std::string> names;
  std::error_code ec;
  fs::directory_iterator it(folder, ec);
  if (ec) throw file_error(folder.string(), "cannot list folder: " + ec.message());
  for (const fs::directory_entry& entry : it) {
    std::error_code e2;
    if (!entry.is_regular_file(e2)) continue;
    const std::string name = entry.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    if (accept(entry.path().extension().string())) names.push_back(name);
  }
  std::sort(names.begin(), names.end(), natural_less);
  return names;
}

void match_depth_files(FrameSource::Impl& impl) {
  impl.depth_names.assign(impl.names.size(), "");
  impl.depth_matches = 0;
  if (impl.options.depth_folder.empty()) return;
  const fs::path folder(impl.options.depth_folder);
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw file_error(folder.string(), "depth folder does not exist");
  const std::vector<std::string> files = list_files(folder, is_depth_extension);
  std::map<std::string, std::string> by_stem;
  std::map<long long, std::string> by_number;
  std::map<long long, int> number_count;
  for (const std::string& f : files) {
    by_stem.emplace(stem_of(f), f);
    const long long v = trailing_number(stem_of(f));
    if (v >= 0) {
      by_number.emplace(v, f);
      ++number_count[v];
    }
  }
  for (std::size_t i = 0; i < impl.names.size(); ++i) {
    std::string match;
    if (impl.kind == CaptureKind::kImageFolder) {
      auto it = by_stem.find(stem_of(impl.names[i]));
      if (it != by_stem.end()) match = it->second;
    }
    if (match.empty() && impl.numbers[i] >= 0 && number_count[impl.numbers[i]] == 1) {
      auto it = by_number.find(impl.numbers[i]);
      if (it != by_number.end()) match = it->second;
    }
    impl.depth_names[i] = match;
    impl.depth_matches += !match.empty();
  }
}

struct FolderScan {
  std::vector<std::string> all_names;  // natural order
  Numbering numbering;
};

FolderScan scan_folder_names(const fs::path& folder) {
  FolderScan scan;
  scan.all_names = list_files(folder, is_frame_extension);
  scan.numbering = analyse_numbering(scan.all_names);
  return scan;
}

double folder_timestamp(const Numbering& numbering, long long number, int position, double rate) {
  if (numbering.counter && number >= 0)
    return double(number - numbering.first) / double(numbering.step) / rate;
  return position / rate;
}

std::unique_ptr<FrameSource::Impl> open_folder(const fs::path& folder, const FrameSourceOptions& options,
                                               const std::vector<std::string>* given_names) {
  auto impl = std::make_unique<FrameSource::Impl>();
  impl->kind = CaptureKind::kImageFolder;
  impl->source = folder.string();
  impl->options = options;
  impl->frame_rate = options.folder_frame_rate;
  const FolderScan scan = scan_folder_names(folder);
  if (scan.all_names.empty() && !given_names)
    throw file_error(folder.string(), "no frames found (expected JPEG, PNG, TIFF or EXR images)");

  // Which files to look at: the range and stride over the sorted list, or the names a project lists.
  std::vector<std::pair<int, std::string>> candidates;  // (position in sorted list, name)
  std::map<std::string, int> position_of;
  for (std::size_t p = 0; p < scan.all_names.size(); ++p)
    position_of[scan.all_names[p]] = static_cast<int>(p);
  if (given_names) {
    for (const std::string& name : *given_names) {
      auto it = position_of.find(name);
      if (it == position_of.end()) {
        long long v = trailing_number(stem_of(name));
        impl->skipped.push_back(
            {static_cast<int>(v), name, "missing (listed in the project, not in the folder)"});
        continue;
      }
      candidates.emplace_back(it->second, name);
    }
  } else {
    const int last = options.last_frame < 0
                         ? static_cast<int>(scan.all_names.size()) - 1
                         : std::min(options.last_frame, static_cast<int>(scan.all_names.size()) - 1);
    if (options.first_frame > last)
      throw file_error(folder.string(), "first frame " + std::to_string(options.first_frame) +
                                            " is beyond the " + std::to_string(scan.all_names.size()) +
                                            " frames in the folder");
    for (int p = options.first_frame; p <= last; p += options.stride)
      candidates.emplace_back(p, scan.all_names[p]);

    // Gaps in the numbering between kept files: missing frames (listed, never fatal).
    const Numbering& nb = scan.numbering;
    if (nb.counter && options.stride == 1 && candidates.size() > 1) {
      for (std::size_t k = 1; k < candidates.size(); ++k) {
        const long long a = trailing_number(stem_of(candidates[k - 1].second));
        const long long b = trailing_number(stem_of(candidates[k].second));
        if (b - a <= nb.step) continue;
        const long long missing = (b - a) / nb.step - 1;
        if (missing <= 0) continue;
        if (missing <= 100) {
          for (long long v = a + nb.step; v < b; v += nb.step)
            impl->skipped.push_back(
                {static_cast<int>(v), numbered_name(nb, v), "missing (gap in the numbering)"});
        } else {
          impl->skipped.push_back({static_cast<int>(a + nb.step), numbered_name(nb, a + nb.step),
                                   "missing: " + std::to_string(missing) + " frames up to " +
                                       numbered_name(nb, b - nb.step) + " (gap in the numbering)"});
        }
      }
    }
  }

  // Headers: size and obvious corruption; the capture's size is the one most frames have.
  struct Probe {
    int position;
    std::string name;
    ImageHeader header;
  };
  std::vector<Probe> probes;
  probes.reserve(candidates.size());
  std::map<std::pair<int, int>, int> size_votes;
  for (const auto& [position, name] : candidates) {
    const std::string path = (folder / name).string();
    ImageHeader h = read_image_header(path);
    if (h.ok && options.verify_by_decoding) {
      cv::Mat m;
      try {
        m = cv::imread(path, cv::IMREAD_UNCHANGED);
      } catch (const cv::Exception&) {
      }
      if (m.empty())
        h.ok = false, h.problem = "corrupt image (does not decode)";
      else
        h.width = m.cols, h.height = m.rows;
    }
    if (h.ok && h.width <= 0) {  // a format whose header we do not parse: decode once to learn the size
      cv::Mat m;
      try {
        m = cv::imread(path, cv::IMREAD_UNCHANGED);
      } catch (const cv::Exception&) {
      }
      if (m.empty())
        h.ok = false, h.problem = "corrupt image (does not decode)";
      else
        h.width = m.cols, h.height = m.rows;
    }
    if (h.ok) ++size_votes[{h.width, h.height}];
    probes.push_back({position, name, h});
  }
  int best = 0;
  for (const auto& [size, votes] : size_votes)
    if (votes > best) best = votes, impl->width = size.first, impl->height = size.second;

  for (const Probe& p : probes) {
    const long long number = scan.numbering.consistent ? trailing_number(stem_of(p.name)) : -1;
    if (!p.header.ok) {
      impl->skipped.push_back({static_cast<int>(number), p.name, p.header.problem});
      continue;
    }
    if (p.header.width != impl->width || p.header.height != impl->height) {
      impl->skipped.push_back({static_cast<int>(number), p.name,
                               "size " + std::to_string(p.header.width) + "x" +
                                   std::to_string(p.header.height) + " differs from the capture's " +
                                   std::to_string(impl->width) + "x" + std::to_string(impl->height)});
      continue;
    }
    impl->names.push_back(p.name);
    impl->numbers.push_back(number);
    impl->timestamps.push_back(
        folder_timestamp(scan.numbering, number, p.position, options.folder_frame_rate));
  }
  std::sort(impl->skipped.begin(), impl->skipped.end(),
            [](const SkippedFrame& a, const SkippedFrame& b) { return natural_less(a.name, b.name); });
  if (impl->names.empty())
    throw file_error(
        folder.string(),
        "no usable frame among " + std::to_string(candidates.size()) + " images (" +
            (impl->skipped.empty() ? std::string("none listed")
                                   : impl->skipped.front().name + ": " + impl->skipped.front().reason) +
            ")");
  check_aspect(impl->width, impl->height, options.require_2to1, folder.string());
  auto backend = std::make_unique<FolderBackend>();
  backend->impl = impl.get();
  backend->folder = folder;
  impl->backend = std::move(backend);
  return impl;
}

std::unique_ptr<FrameSource::Impl> open_video(const std::string& path, const FrameSourceOptions& options) {
  auto impl = std::make_unique<FrameSource::Impl>();
  impl->kind = CaptureKind::kVideo;
  impl->source = path;
  impl->options = options;
  auto backend = std::make_unique<VideoBackend>();
  backend->impl = impl.get();
  backend->decoder = std::make_unique<VideoDecoder>(path);  // throws Error naming the file
  VideoDecoder& decoder = *backend->decoder;
  double fps = decoder.frame_rate();
  if (!(fps > 0.0) || !std::isfinite(fps) || fps > 1000.0) fps = 30.0;
  impl->frame_rate = fps;

  // The first frame tells the true size (and that the stream decodes at all); the last that the packets
  // keep their promise. If either fails, only decoding every frame tells which frames there are.
  const auto decodes = [&](int frame) {
    try {
      return decoder.read(frame);
    } catch (const Error&) {
      return cv::Mat();
    }
  };
  const long long packet_count = decoder.frame_count();
  cv::Mat first = packet_count > 0 ? decodes(0) : cv::Mat();
  if (packet_count > 0 &&
      (first.empty() || (packet_count > 1 && decodes(decoder.frame_count() - 1).empty()))) {
    decoder.index_by_decoding();
    first = decoder.frame_count() > 0 ? decodes(0) : cv::Mat();
  }
  if (first.empty()) throw file_error(path, "video has no decodable frame");
  impl->width = first.cols;
  impl->height = first.rows;
  const long long count = decoder.frame_count();
  const long long promised =
      std::max(packet_count, decoder.packets_end_early() ? decoder.container_frame_count() : 0);
  if (count < promised)
    impl->skipped.push_back({static_cast<int>(count), "frame " + std::to_string(count),
                             "missing: the stream ends after " + std::to_string(count) +
                                 " frames though the container says " + std::to_string(promised)});
  check_aspect(impl->width, impl->height, options.require_2to1, path);

  const long long last =
      options.last_frame < 0 ? count - 1 : std::min<long long>(options.last_frame, count - 1);
  if (options.first_frame > last)
    throw file_error(path, "first frame " + std::to_string(options.first_frame) + " is beyond the video's " +
                               std::to_string(count) + " frames");
  for (long long raw = options.first_frame; raw <= last; raw += options.stride) {
    impl->names.push_back("frame " + std::to_string(raw));
    impl->numbers.push_back(raw);
    impl->timestamps.push_back(
        decoder.time_s(static_cast<int>(raw)));  // the frame's own PTS: right for variable rates
  }
  impl->backend = std::move(backend);
  return impl;
}

bool looks_like_video(const std::string& path) {
  const std::string e = lower(fs::path(path).extension().string());
  return e == ".mp4" || e == ".mov" || e == ".mkv" || e == ".avi" || e == ".m4v" || e == ".webm" ||
         e == ".insv";
}

}  // namespace

void frame_source_detail::match_depth(FrameSource::Impl& impl) { match_depth_files(impl); }

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
