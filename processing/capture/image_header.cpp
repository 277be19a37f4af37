#include "processing/capture/image_header.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace plenopath {
namespace {

using Bytes = std::vector<unsigned char>;

bool read_at(std::istream& in, std::uint64_t offset, std::size_t n, Bytes& out) {
  out.assign(n, 0);
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  if (!in) return false;
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(n));
  out.resize(static_cast<std::size_t>(in.gcount()));
  return out.size() == n;
}

ImageHeader fail(const std::string& format, const std::string& problem) {
  ImageHeader h;
  h.format = format;
  h.problem = problem;
  return h;
}

int be16(const unsigned char* p) { return (p[0] << 8) | p[1]; }
std::uint32_t be32(const unsigned char* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

ImageHeader read_jpeg(std::istream& in, std::uint64_t size) {
  // Walk the marker segments up to the frame header (SOFn) and the scan (SOS).
  std::uint64_t pos = 2;
  ImageHeader h;
  h.format = "jpeg";
  std::uint64_t sos = 0;
  Bytes b;
  for (int guard = 0; guard < 10000 && sos == 0; ++guard) {
    if (!read_at(in, pos, 4, b)) return fail("jpeg", "corrupt JPEG (truncated in its header)");
    if (b[0] != 0xFF) return fail("jpeg", "corrupt JPEG (bad marker in its header)");
    const int marker = b[1];
    if (marker == 0xFF) {  // fill byte
      ++pos;
      continue;
    }
    if (marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {  // no length
      pos += 2;
      continue;
    }
    const int length = be16(&b[2]);
    if (length < 2) return fail("jpeg", "corrupt JPEG (bad segment length)");
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      Bytes f;
      if (!read_at(in, pos + 4, 5, f)) return fail("jpeg", "corrupt JPEG (truncated frame header)");
      h.height = be16(&f[1]);
      h.width = be16(&f[3]);
    }
    if (marker == 0xDA) sos = pos;
    if (marker == 0xD9) return fail("jpeg", "corrupt JPEG (ends before any image data)");
    pos += 2 + static_cast<std::uint64_t>(length);
    if (pos > size) return fail("jpeg", "corrupt JPEG (truncated in its header)");
  }
  if (sos == 0) return fail("jpeg", "corrupt JPEG (no image data)");
  if (h.width <= 0 || h.height <= 0) return fail("jpeg", "corrupt JPEG (no frame size in its header)");
  // A complete JPEG ends with FF D9; cameras sometimes append data after it, so look back a little.
  if (!read_at(in, size - 2, 2, b)) return fail("jpeg", "unreadable file");
  if (!(b[0] == 0xFF && b[1] == 0xD9)) {
    const std::uint64_t from = std::max<std::uint64_t>(sos, size > (1u << 20) ? size - (1u << 20) : 0);
    Bytes tail;
    read_at(in, from, static_cast<std::size_t>(size - from), tail);
    bool found = false;
    for (std::size_t k = 0; k + 1 < tail.size() && !found; ++k)
      found = tail[k] == 0xFF && tail[k + 1] == 0xD9;
    if (!found) return fail("jpeg", "corrupt JPEG (truncated: no end-of-image marker)");
  }
  h.ok = true;
  return h;
}

ImageHeader read_png(std::istream& in, std::uint64_t size) {
  Bytes b;
  if (size < 33 || !read_at(in, 8, 16, b)) return fail("png", "corrupt PNG (truncated header)");
  if (std::memcmp(&b[4], "IHDR", 4) != 0) return fail("png", "corrupt PNG (no IHDR chunk)");
  ImageHeader h;
  h.format = "png";
  const std::uint32_t width = be32(&b[8]), height = be32(&b[12]);
  if (width == 0 || height == 0 || width > 1u << 30 || height > 1u << 30)
    return fail("png", "corrupt PNG (bad size)");
  h.width = static_cast<int>(width);
  h.height = static_cast<int>(height);
  Bytes tail;
  if (!read_at(in, size - 8, 4, tail) || std::memcmp(tail.data(), "IEND", 4) != 0)
    return fail("png", "corrupt PNG (truncated: no IEND chunk)");
  h.ok = true;
  return h;
}

ImageHeader read_tiff(std::istream& in, std::uint64_t size, bool little) {
  auto u16 = [little](const unsigned char* p) { return little ? (p[0] | (p[1] << 8)) : be16(p); };
  auto u32 = [little](const unsigned char* p) {
    return little ? (std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
                     (std::uint32_t(p[3]) << 24))
                  : be32(p);
  };
  Bytes b;
  if (!read_at(in, 4, 4, b)) return fail("tiff", "corrupt TIFF (truncated header)");
  const std::uint32_t ifd = u32(b.data());
  if (ifd < 8 || ifd + 2 > size || !read_at(in, ifd, 2, b))
    return fail("tiff", "corrupt TIFF (bad directory offset)");
  const int entries = u16(b.data());
  if (entries <= 0 || !read_at(in, ifd + 2, static_cast<std::size_t>(entries) * 12, b))
    return fail("tiff", "corrupt TIFF (truncated directory)");
  ImageHeader h;
  h.format = "tiff";
  for (int e = 0; e < entries; ++e) {
    const unsigned char* p = &b[static_cast<std::size_t>(e) * 12];
    const int tag = u16(p), type = u16(p + 2);
    const std::uint32_t value = type == 3 ? static_cast<std::uint32_t>(u16(p + 8)) : u32(p + 8);
    if ((tag == 256 || tag == 257) && value > 1u << 30) return fail("tiff", "corrupt TIFF (bad size)");
    if (tag == 256) h.width = static_cast<int>(value);
    if (tag == 257) h.height = static_cast<int>(value);
  }
  h.ok = true;  // size 0 = not in the directory: the caller decodes to learn it
  return h;
}

ImageHeader read_exr(std::istream& in, std::uint64_t size) {
  Bytes b;
  read_at(in, 8, static_cast<std::size_t>(std::min<std::uint64_t>(size - 8, 1u << 16)), b);
  ImageHeader h;
  h.format = "exr";
  std::size_t p = 0;
  auto read_string = [&](std::string& s) {
    s.clear();
    while (p < b.size() && b[p] != 0) s += static_cast<char>(b[p++]);
    if (p >= b.size()) return false;
    ++p;
    return true;
  };
  while (p < b.size()) {
    std::string name, type;
    if (!read_string(name)) return fail("exr", "corrupt EXR (truncated header)");
    if (name.empty()) break;  // end of header
    if (!read_string(type) || p + 4 > b.size()) return fail("exr", "corrupt EXR (truncated header)");
    const std::uint32_t n = std::uint32_t(b[p]) | (std::uint32_t(b[p + 1]) << 8) |
                            (std::uint32_t(b[p + 2]) << 16) | (std::uint32_t(b[p + 3]) << 24);
    p += 4;
    if (p + n > b.size()) return fail("exr", "corrupt EXR (truncated header)");
    if (name == "dataWindow" && type == "box2i" && n == 16) {
      std::int32_t box[4];
      std::memcpy(box, &b[p], 16);  // little-endian on every machine we build for
      // In 64 bits: a hostile window's extent overflows 32.
      const std::int64_t width = std::int64_t(box[2]) - box[0] + 1,
                         height = std::int64_t(box[3]) - box[1] + 1;
      if (width <= 0 || height <= 0 || width > 1 << 30 || height > 1 << 30)
        return fail("exr", "corrupt EXR (bad data window)");
      h.width = static_cast<int>(width);
      h.height = static_cast<int>(height);
    }
    p += n;
  }
  if (h.width <= 0 || h.height <= 0) return fail("exr", "corrupt EXR (no data window)");
  h.ok = true;
  return h;
}

}  // namespace

ImageHeader read_image_header(std::istream& in) {
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (end <= 0) return fail("", "empty file");
  const auto size = static_cast<std::uint64_t>(end);
  Bytes magic;
  if (!read_at(in, 0, static_cast<std::size_t>(std::min<std::uint64_t>(size, 8)), magic) || magic.size() < 4)
    return fail("", "too short to be an image");
  try {
    if (magic[0] == 0xFF && magic[1] == 0xD8) return read_jpeg(in, size);
    if (magic.size() == 8 && std::memcmp(magic.data(), "\x89PNG\r\n\x1a\n", 8) == 0)
      return read_png(in, size);
    if (magic[0] == 'I' && magic[1] == 'I' && magic[2] == 42 && magic[3] == 0)
      return read_tiff(in, size, true);
    if (magic[0] == 'M' && magic[1] == 'M' && magic[2] == 0 && magic[3] == 42)
      return read_tiff(in, size, false);
    if (magic[0] == 0x76 && magic[1] == 0x2F && magic[2] == 0x31 && magic[3] == 0x01)
      return read_exr(in, size);
  } catch (const std::exception& e) {
    return fail("", std::string("unreadable header: ") + e.what());
  }
  return fail("", "not a JPEG, PNG, TIFF or EXR image (unknown content)");
}

ImageHeader read_image_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("", "unreadable file");
  return read_image_header(static_cast<std::istream&>(in));
}

ImageHeader read_image_header_from_memory(const std::string& bytes) {
  std::istringstream in(bytes, std::ios::binary);
  return read_image_header(static_cast<std::istream&>(in));
}

}  // namespace plenopath
