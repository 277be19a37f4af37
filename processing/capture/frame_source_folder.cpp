// Folders of frames (FrameSource's image-folder backend): the files listed in natural order, their numbering
// (gaps are missing frames, numbers give time stamps), headers probed for size and corruption, depth maps
// matched by stem or number.
#include <algorithm>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/frame_source_internal.h"
#include "processing/capture/image_header.h"

namespace fs = std::filesystem;

namespace plenopath::frame_source_detail {
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

}  // namespace

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
    // Decoded when asked to, or when the header is of a format not parsed here (to learn the size).
    if (h.ok && (options.verify_by_decoding || h.width <= 0)) {
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

void match_depth(FrameSource::Impl& impl) { match_depth_files(impl); }

}  // namespace plenopath::frame_source_detail
