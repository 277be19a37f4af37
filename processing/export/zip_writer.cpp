#include "processing/export/zip_writer.h"

#include <array>
#include <limits>
#include <sstream>

#include "model/atomic_file.h"
#include "model/error.h"

namespace plenopath {
namespace {

std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}

void put16(std::string& out, std::uint32_t v) {
  out.push_back(static_cast<char>(v & 0xFF));
  out.push_back(static_cast<char>((v >> 8) & 0xFF));
}
void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xFFFF);
  put16(out, v >> 16);
}

}  // namespace

std::uint32_t crc32_of(const std::string& data) {
  static const std::array<std::uint32_t, 256> table = make_crc_table();
  std::uint32_t c = 0xFFFFFFFFu;
  for (unsigned char byte : data) c = table[(c ^ byte) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

bool is_safe_package_path(const std::string& name) {
  if (name.empty() || name.front() == '/' || name.find('\\') != std::string::npos) return false;
  if (name.size() >= 2 && name[1] == ':') return false;
  std::stringstream parts(name);
  std::string part;
  while (std::getline(parts, part, '/'))
    if (part.empty() || part == "." || part == "..") return false;
  return name.back() != '/';
}

void write_zip_file(const std::string& file, const std::vector<ZipEntry>& entries) {
  std::string archive, directory;
  constexpr std::uint32_t kLimit = std::numeric_limits<std::uint32_t>::max();
  // DOS date/time of 2026-01-01 00:00: a fixed stamp keeps packages reproducible.
  constexpr std::uint32_t kDosTime = 0, kDosDate = ((2026 - 1980) << 9) | (1 << 5) | 1;
  for (const ZipEntry& e : entries) {
    if (!is_safe_package_path(e.name))
      throw file_error(file, "unsafe path inside the package: '" + e.name + "'");
    if (e.data.size() >= kLimit || archive.size() >= kLimit - e.data.size() - 1024)
      throw file_error(file, "package larger than 4 GiB (ZIP64 is not supported)");
    const std::uint32_t crc = crc32_of(e.data);
    const std::uint32_t offset = static_cast<std::uint32_t>(archive.size());
    const std::uint32_t size = static_cast<std::uint32_t>(e.data.size());
    // Local file header; flag bit 11: names are UTF-8.
    put32(archive, 0x04034b50);
    put16(archive, 20);
    put16(archive, 1u << 11);
    put16(archive, 0);  // stored
    put16(archive, kDosTime);
    put16(archive, kDosDate);
    put32(archive, crc);
    put32(archive, size);
    put32(archive, size);
    put16(archive, static_cast<std::uint32_t>(e.name.size()));
    put16(archive, 0);
    archive += e.name;
    archive += e.data;
    // Central directory record.
    put32(directory, 0x02014b50);
    put16(directory, 0x0314);  // made by: Unix, 2.0
    put16(directory, 20);
    put16(directory, 1u << 11);
    put16(directory, 0);
    put16(directory, kDosTime);
    put16(directory, kDosDate);
    put32(directory, crc);
    put32(directory, size);
    put32(directory, size);
    put16(directory, static_cast<std::uint32_t>(e.name.size()));
    put16(directory, 0);
    put16(directory, 0);
    put16(directory, 0);
    put16(directory, 0);
    put32(directory, 0100644u << 16);  // external attributes: regular file, rw-r--r--
    put32(directory, offset);
    directory += e.name;
  }
  if (entries.size() >= 0xFFFF) throw file_error(file, "too many files for a ZIP without ZIP64");
  const std::uint32_t directory_offset = static_cast<std::uint32_t>(archive.size());
  archive += directory;
  put32(archive, 0x06054b50);
  put16(archive, 0);
  put16(archive, 0);
  put16(archive, static_cast<std::uint32_t>(entries.size()));
  put16(archive, static_cast<std::uint32_t>(entries.size()));
  put32(archive, static_cast<std::uint32_t>(directory.size()));
  put32(archive, directory_offset);
  put16(archive, 0);
  write_file_atomically(file, archive, false);
}

}  // namespace plenopath
