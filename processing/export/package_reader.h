#pragma once
// Reads a published tour package: a folder, or a .zip read with libarchive (any zip a tool wrote: stored or
// deflated entries, ZIP64). Only safe package paths are ever opened or written (is_safe_package_path), and
// an entry larger than max_entry_bytes is refused, so an untrusted package cannot escape its folder or fill
// the disk.
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "processing/util/progress.h"

namespace plenopath {

struct PackageReadOptions {
  std::uint64_t max_entry_bytes = std::uint64_t(1) << 31;  // 2 GiB: far above any keyframe or media file
  void check() const;                                      // throws Error naming the bad field
};

class PackageReader {
 public:
  // `package`: a folder holding tour.json, a tour.json file itself (its folder is the package), or a .zip.
  // Throws Error naming the file when it is none of these or cannot be read.
  explicit PackageReader(std::string package, PackageReadOptions options = {});

  bool is_zip() const { return zip_; }
  const std::string& package() const { return package_; }
  // The names of the package's files, '/'-separated, relative to its root.
  std::vector<std::string> names() const;
  // One entry's bytes; nullopt when the package has no such entry. Throws Error on an unsafe name, an
  // entry over the size limit, or a damaged archive.
  std::optional<std::string> read(const std::string& name) const;
  // Copies the named entries into `folder` (created when missing), under their package-relative names.
  // Returns the names it did not find. Reads a zip once, in its own order.
  std::vector<std::string> extract(const std::set<std::string>& wanted, const std::string& folder,
                                   Progress& progress = null_progress()) const;

 private:
  std::string package_;  // the zip file, or the package folder
  bool zip_ = false;
  PackageReadOptions options_;
  std::string root_in_zip_;  // "" or "name/" when every entry of the zip sits in one top folder
};

}  // namespace plenopath
