#pragma once
// The described frames of a capture (loop_closure.h: ORB descriptors at the live tracks' corners, every few
// frames and on both sides of a dropout), kept in an unnamed temporary file rather than in memory: at 100 000
// frames they would take about 700 MB of RAM, and loop closure and joins read only a few of them back at a
// time. Memory per described frame: its index entry (16 bytes). Where no temporary file can be made, the
// store keeps them in memory.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include "processing/egomotion/loop_closure.h"

namespace plenopath {

class DescriptorStore {
 public:
  DescriptorStore();
  ~DescriptorStore();
  DescriptorStore(const DescriptorStore&) = delete;
  DescriptorStore& operator=(const DescriptorStore&) = delete;

  // Frames are added in capture order (increasing frame numbers). Throws Error when the file cannot be
  // written (a full disk).
  void add(const FrameDescriptors& described);
  int size() const { return static_cast<int>(index_.size()); }
  int frame(int i) const { return index_[static_cast<std::size_t>(i)].frame; }
  bool has_descriptors(int i) const { return index_[static_cast<std::size_t>(i)].rows > 0; }
  int last_frame() const { return index_.empty() ? -1 : index_.back().frame; }
  int find(int frame) const;           // the entry of a capture frame, -1 when it was not described
  FrameDescriptors load(int i) const;  // reads entry i back (throws Error when the file cannot be read)
  bool on_disk() const { return file_ != nullptr; }

 private:
  struct Entry {
    std::int64_t offset = 0;
    int frame = 0;
    int rows = 0;
  };
  std::vector<Entry> index_;
  std::FILE* file_ = nullptr;
  int cols_ = 32;                            // ORB: 32 bytes a row
  std::vector<FrameDescriptors> in_memory_;  // when no temporary file could be made
};

}  // namespace plenopath
