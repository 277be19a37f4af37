// Multi-head captures: one image folder per pinhole head plus the rig calibration, stitched to an
// equirectangular panorama on the fly by rig/multi_head_rig.h.
#include <filesystem>
#include <map>

#include "processing/capture/frame_source.h"
#include "processing/capture/frame_source_internal.h"
#include "rig/multi_head_rig.h"

namespace fs = std::filesystem;

namespace plenopath {
namespace {

using frame_source_detail::Backend;

struct MultiHeadBackend : Backend {
  std::vector<std::unique_ptr<FrameSource>> heads;
  std::vector<std::vector<int>> head_index;  // per kept frame: the frame index in each head's source
  StitchMaps maps;

  cv::Mat read(int i) override {
    std::vector<cv::Mat> images(heads.size());
    for (std::size_t k = 0; k < heads.size(); ++k) images[k] = heads[k]->read(head_index[i][k]);
    return stitch_heads(maps, images);
  }
};

// What ties a head's frame to the same instant in the other heads: the number in its name, else its stem.
std::string frame_key(const FrameSource& head, int i) {
  const int number = head.frame_number(i);
  if (number >= 0) return "#" + std::to_string(number);
  return fs::path(head.frame_name(i)).stem().string();
}

std::unique_ptr<FrameSource::Impl> open_heads(const std::string& rig_file,
                                              const std::vector<std::string>& head_folders,
                                              const std::string& source_name,
                                              const FrameSourceOptions& options,
                                              const std::vector<std::string>* given_names) {
  const MultiHeadRig rig = read_rig_file(rig_file);
  try {
    rig.check();
  } catch (const Error& e) {
    throw file_error(rig_file, e.what());
  }
  if (head_folders.size() != rig.heads.size())
    throw file_error(rig_file, "the rig has " + std::to_string(rig.heads.size()) + " heads but " +
                                   std::to_string(head_folders.size()) + " head folders were given");
  if (options.stitch_width < 8 || options.stitch_width % 2 != 0)
    throw Error("capture options: stitch_width must be an even number of at least 8 pixels");

  auto backend = std::make_unique<MultiHeadBackend>();
  auto impl = std::make_unique<FrameSource::Impl>();
  impl->kind = CaptureKind::kImageFolder;
  impl->source = source_name;
  impl->options = options;
  impl->width = options.stitch_width;
  impl->height = options.stitch_width / 2;
  impl->frame_rate = options.folder_frame_rate;
  impl->head_count = static_cast<int>(rig.heads.size());

  // Every head's folder, whole (range and stride are applied to the matched frames below).
  FrameSourceOptions head_options;
  head_options.require_2to1 = false;
  head_options.folder_frame_rate = options.folder_frame_rate;
  head_options.verify_by_decoding = options.verify_by_decoding;
  std::vector<std::map<std::string, int>> index_by_key(rig.heads.size());
  for (std::size_t k = 0; k < rig.heads.size(); ++k) {
    const PinholeHead& head = rig.heads[k];
    std::unique_ptr<FrameSource> source = FrameSource::open(head_folders[k], head_options);
    if (source->width() != head.width || source->height() != head.height)
      throw file_error(head_folders[k], "frames are " + std::to_string(source->width()) + "x" +
                                            std::to_string(source->height()) + " but the rig calibration " +
                                            rig_file + " says " + std::to_string(head.width) + "x" +
                                            std::to_string(head.height) + " for head '" + head.name + "'");
    const std::string prefix = fs::path(head_folders[k]).filename().string() + "/";
    for (const SkippedFrame& s : source->skipped()) {
      // Gaps in other heads' numbering show up below as frames "missing from head(s) ..."; list them once.
      if (k > 0 && s.reason.rfind("missing", 0) == 0) continue;
      impl->skipped.push_back({s.number, prefix + s.name, s.reason});
    }
    for (int i = 0; i < source->frame_count(); ++i) index_by_key[k].emplace(frame_key(*source, i), i);
    backend->heads.push_back(std::move(source));
  }

  // Head 0's frames, in order, that every head has.
  const FrameSource& first = *backend->heads[0];
  std::vector<int> candidates;
  if (given_names) {
    std::map<std::string, int> by_name;
    for (int i = 0; i < first.frame_count(); ++i) by_name.emplace(first.frame_name(i), i);
    for (const std::string& name : *given_names) {
      auto it = by_name.find(name);
      if (it == by_name.end())
        impl->skipped.push_back(
            {-1, name, "missing from head '" + rig.heads[0].name + "' (listed in the project)"});
      else
        candidates.push_back(it->second);
    }
  } else {
    const int n = first.frame_count();
    const int last = options.last_frame < 0 ? n - 1 : std::min(options.last_frame, n - 1);
    if (options.first_frame > last)
      throw file_error(head_folders[0], "first frame " + std::to_string(options.first_frame) +
                                            " is beyond the " + std::to_string(n) + " frames of head '" +
                                            rig.heads[0].name + "'");
    for (int i = options.first_frame; i <= last; i += options.stride) candidates.push_back(i);
  }
  for (int i0 : candidates) {
    const std::string key = frame_key(first, i0);
    std::vector<int> indices{i0};
    std::string lacking;
    for (std::size_t k = 1; k < rig.heads.size(); ++k) {
      auto it = index_by_key[k].find(key);
      if (it == index_by_key[k].end()) {
        lacking += (lacking.empty() ? "" : ", ") + rig.heads[k].name;
        continue;
      }
      indices.push_back(it->second);
    }
    if (!lacking.empty()) {
      impl->skipped.push_back(
          {first.frame_number(i0), first.frame_name(i0), "missing from head(s) " + lacking});
      continue;
    }
    impl->names.push_back(first.frame_name(i0));
    impl->numbers.push_back(first.frame_number(i0));
    impl->timestamps.push_back(first.timestamp_s(i0));
    backend->head_index.push_back(std::move(indices));
  }
  if (impl->names.empty())
    throw file_error(source_name, "no frame is present in every head's folder (" +
                                      std::to_string(impl->skipped.size()) + " skipped)");

  StitchOptions stitch;
  stitch.width = impl->width;
  stitch.height = impl->height;
  backend->maps = make_stitch_maps(rig, stitch);
  impl->backend = std::move(backend);
  return impl;
}

// Head folders of a capture folder: sub-folders named after the heads, else head0, head1, ...
std::vector<std::string> head_folders_of(const fs::path& folder, const MultiHeadRig& rig) {
  std::vector<std::string> folders;
  std::error_code ec;
  for (std::size_t k = 0; k < rig.heads.size(); ++k) {
    const fs::path by_name = folder / rig.heads[k].name;
    const fs::path by_number = folder / ("head" + std::to_string(k));
    if (!rig.heads[k].name.empty() && fs::is_directory(by_name, ec))
      folders.push_back(by_name.string());
    else if (fs::is_directory(by_number, ec))
      folders.push_back(by_number.string());
    else
      throw file_error(folder.string(), "multi-head capture: no folder for head '" + rig.heads[k].name +
                                            "' (expected " + by_name.filename().string() + "/ or " +
                                            by_number.filename().string() + "/)");
  }
  return folders;
}

}  // namespace

std::unique_ptr<FrameSource> FrameSource::open_multi_head(const std::string& rig_file,
                                                          const std::vector<std::string>& head_folders,
                                                          const FrameSourceOptions& options) {
  options.check();
  auto impl = open_heads(rig_file, head_folders, fs::path(rig_file).parent_path().string(), options, nullptr);
  frame_source_detail::match_depth(*impl);
  return std::unique_ptr<FrameSource>(new FrameSource(std::move(impl)));
}

std::unique_ptr<FrameSource> FrameSource::open_multi_head_folder(
    const std::string& capture_folder, const FrameSourceOptions& options,
    const std::vector<std::string>* given_names) {
  options.check();
  const fs::path folder(capture_folder);
  const std::string rig_file = (folder / kRigFileName).string();
  const MultiHeadRig rig = read_rig_file(rig_file);
  auto impl = open_heads(rig_file, head_folders_of(folder, rig), capture_folder, options, given_names);
  frame_source_detail::match_depth(*impl);
  return std::unique_ptr<FrameSource>(new FrameSource(std::move(impl)));
}

}  // namespace plenopath
