#include "processing/capture/mp4_boxes.h"

#include <cstring>

#include "model/error.h"

namespace plenopath {
namespace {

uint32_t be32(const uint8_t* p) {
  return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | uint32_t(p[3]);
}

// A box type for messages: printable characters as they are, anything else as '?'.
std::string printable_type(const uint8_t* p) {
  std::string t(4, '?');
  for (int k = 0; k < 4; ++k)
    if (p[k] >= 0x20 && p[k] < 0x7f) t[k] = static_cast<char>(p[k]);
  return t;
}

}  // namespace

std::vector<Mp4Box> mp4_child_boxes(const uint8_t* data, std::size_t size, const std::string& where) {
  std::vector<Mp4Box> boxes;
  std::size_t at = 0;
  while (at < size) {
    const std::size_t left = size - at;
    // Fewer than 8 bytes cannot hold a box: padding some writers leave at the end; nothing to read.
    if (left < 8) break;
    if (boxes.size() >= kMaxMp4ChildBoxes)
      throw Error(where + ": more than " + std::to_string(kMaxMp4ChildBoxes) + " boxes");
    const uint8_t* p = data + at;
    Mp4Box box;
    box.type = printable_type(p + 4);
    uint64_t box_size = be32(p);
    std::size_t header = 8;
    if (box_size == 1) {
      if (left < 16) throw Error(where + ": box '" + box.type + "' is cut short in its 64-bit size");
      box_size = (uint64_t(be32(p + 8)) << 32) | be32(p + 12);
      header = 16;
    } else if (box_size == 0) {
      box_size = left;  // extends to the end of its parent
    }
    if (box.type == "uuid") {
      if (left < header + 16) throw Error(where + ": box 'uuid' is cut short in its extended type");
      std::memcpy(box.uuid, p + header, 16);
      header += 16;
    }
    if (box_size < header)
      throw Error(where + ": box '" + box.type + "' says it has " + std::to_string(box_size) +
                  " bytes, fewer than its own header");
    if (box_size > left)
      throw Error(where + ": box '" + box.type + "' says it has " + std::to_string(box_size) +
                  " bytes, only " + std::to_string(left) + " remain");
    box.payload = p + header;
    box.payload_size = static_cast<std::size_t>(box_size) - header;
    boxes.push_back(box);
    at += static_cast<std::size_t>(box_size);
  }
  return boxes;
}

const Mp4Box* find_mp4_box(const std::vector<Mp4Box>& boxes, const char* type) {
  for (const Mp4Box& b : boxes)
    if (b.type == type) return &b;
  return nullptr;
}

void Mp4Reader::need(std::size_t bytes) const {
  if (bytes > size_ - position_)
    throw Error(where_ + ": box ends after " + std::to_string(size_) + " bytes, in the middle of a field");
}
uint8_t Mp4Reader::u8() {
  need(1);
  return data_[position_++];
}
uint16_t Mp4Reader::u16() {
  need(2);
  const uint16_t v = static_cast<uint16_t>((data_[position_] << 8) | data_[position_ + 1]);
  position_ += 2;
  return v;
}
uint32_t Mp4Reader::u32() {
  need(4);
  const uint32_t v = be32(data_ + position_);
  position_ += 4;
  return v;
}
void Mp4Reader::skip(std::size_t bytes) {
  need(bytes);
  position_ += bytes;
}
std::string Mp4Reader::text_until_nul() {
  std::string s;
  while (position_ < size_ && data_[position_] != 0) s.push_back(static_cast<char>(data_[position_++]));
  if (position_ < size_) ++position_;  // the NUL
  return s;
}

}  // namespace plenopath
