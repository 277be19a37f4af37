#pragma once
// Boxes of the ISO base media file format (MP4, MOV) read from untrusted bytes. Every size is checked
// against what encloses it and every read against the box's end, so a damaged or hostile file gives an
// Error saying which box is wrong, never a read out of bounds. Nothing here recurses: callers walk the fixed
// path they need (moov/trak/mdia/...), at most kMaxMp4BoxDepth levels deep.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace plenopath {

constexpr int kMaxMp4BoxDepth = 16;
constexpr std::size_t kMaxMp4ChildBoxes = 100000;  // per parent: far more than any real file has

struct Mp4Box {
  std::string type;                  // the four characters, e.g. "moov"
  uint8_t uuid[16] = {0};            // type "uuid": the extended type
  const uint8_t* payload = nullptr;  // after the header (and the uuid)
  std::size_t payload_size = 0;
};

// The boxes laid out one after another in [data, data + size), as found inside `where` (a path such as
// "moov/trak", for messages). A size of 0 means "to the end". Throws Error on a box that overruns.
std::vector<Mp4Box> mp4_child_boxes(const uint8_t* data, std::size_t size, const std::string& where);

// The first child of the given type, or nullptr.
const Mp4Box* find_mp4_box(const std::vector<Mp4Box>& boxes, const char* type);

// Big-endian fields of one box, each read checked against the box's end (Error naming the box).
class Mp4Reader {
 public:
  Mp4Reader(const uint8_t* data, std::size_t size, std::string where)
      : data_(data), size_(size), where_(std::move(where)) {}
  uint8_t u8();
  uint16_t u16();
  uint32_t u32();
  int32_t i32() { return static_cast<int32_t>(u32()); }
  void skip(std::size_t bytes);
  std::string text_until_nul();  // up to a NUL or the end of the box
  std::size_t position() const { return position_; }
  std::size_t remaining() const { return size_ - position_; }
  const uint8_t* here() const { return data_ + position_; }

 private:
  void need(std::size_t bytes) const;
  const uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
  std::string where_;
};

}  // namespace plenopath
