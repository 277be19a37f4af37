#pragma once
// A minimal ZIP writer (stored entries, no compression): tour packages are mostly JPEG, which does not
// compress further, and stored entries keep the writer small and the archive readable by any unzip.
#include <cstdint>
#include <string>
#include <vector>

namespace plenopath {

struct ZipEntry {
  std::string name;  // path inside the archive, '/'-separated, relative, no ".."
  std::string data;
};

// Writes `entries` to `file` atomically. Throws Error naming the file, or the entry whose name is unsafe.
void write_zip_file(const std::string& file, const std::vector<ZipEntry>& entries);

// CRC-32 (IEEE 802.3) as ZIP uses it.
std::uint32_t crc32_of(const std::string& data);

// True when `name` is a relative path that stays inside the package: no "..", no leading '/', no '\\',
// no drive letter, no empty component.
bool is_safe_package_path(const std::string& name);

}  // namespace plenopath
