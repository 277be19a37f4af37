#include "processing/egomotion/descriptor_store.h"

#include <algorithm>
#include <string>

#include "model/error.h"

namespace plenopath {

DescriptorStore::DescriptorStore() : file_(std::tmpfile()) {}

DescriptorStore::~DescriptorStore() {
  if (file_) std::fclose(file_);
}

void DescriptorStore::add(const FrameDescriptors& d) {
  Entry e;
  e.frame = d.frame;
  e.rows = d.descriptors.empty() ? 0 : d.descriptors.rows;
  if (e.rows > 0 && (d.descriptors.type() != CV_8U || static_cast<int>(d.tracks.size()) != e.rows))
    throw Error("descriptor store: frame " + std::to_string(d.frame) + " has malformed descriptors");
  if (e.rows > 0) cols_ = d.descriptors.cols;
  if (!file_) {
    e.offset = static_cast<std::int64_t>(in_memory_.size());
    in_memory_.push_back(d);
    index_.push_back(e);
    return;
  }
  if (std::fseek(file_, 0, SEEK_END) != 0) throw Error("descriptor store: cannot seek its temporary file");
  e.offset = static_cast<std::int64_t>(std::ftell(file_));
  if (e.rows > 0) {
    const cv::Mat rows = d.descriptors.isContinuous() ? d.descriptors : d.descriptors.clone();
    const std::size_t bytes = static_cast<std::size_t>(e.rows) * static_cast<std::size_t>(cols_);
    if (std::fwrite(d.tracks.data(), sizeof(int), d.tracks.size(), file_) != d.tracks.size() ||
        std::fwrite(rows.data, 1, bytes, file_) != bytes)
      throw Error("descriptor store: cannot write its temporary file (disk full?)");
  }
  index_.push_back(e);
}

int DescriptorStore::find(int frame) const {
  const auto it = std::lower_bound(index_.begin(), index_.end(), frame,
                                   [](const Entry& e, int f) { return e.frame < f; });
  return it != index_.end() && it->frame == frame ? static_cast<int>(it - index_.begin()) : -1;
}

FrameDescriptors DescriptorStore::load(int i) const {
  const Entry& e = index_.at(static_cast<std::size_t>(i));
  if (!file_) return in_memory_[static_cast<std::size_t>(e.offset)];
  FrameDescriptors out;
  out.frame = e.frame;
  if (e.rows == 0) return out;
  out.tracks.resize(static_cast<std::size_t>(e.rows));
  out.descriptors.create(e.rows, cols_, CV_8U);
  const std::size_t bytes = static_cast<std::size_t>(e.rows) * static_cast<std::size_t>(cols_);
  if (std::fseek(file_, static_cast<long>(e.offset), SEEK_SET) != 0 ||
      std::fread(out.tracks.data(), sizeof(int), out.tracks.size(), file_) != out.tracks.size() ||
      std::fread(out.descriptors.data, 1, bytes, file_) != bytes)
    throw Error("descriptor store: cannot read frame " + std::to_string(e.frame) + " back");
  return out;
}

}  // namespace plenopath
