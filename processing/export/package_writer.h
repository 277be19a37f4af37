#pragma once
// Writes a tour package entry by entry as the export produces them, so memory stays bounded whatever the
// tour's size: a .zip (libarchive; text deflated, images and media stored, ZIP64 whenever an entry or the
// archive passes 4 GiB) or a folder. Everything goes to a temporary file or folder beside the output and is
// moved into place by commit(): a failed or cancelled export leaves no partial package and the previous
// package as it was.
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace plenopath {

struct PackageWriterOptions {
  // ZIP64 records on every entry, not only on those that need them (readers of huge packages take the same
  // path as small ones; tests use it to exercise ZIP64 without writing 4 GiB).
  bool force_zip64 = false;
  int deflate_level = 6;  // 1..9, text entries only
  void check() const;     // throws Error naming the bad field
};

class PackageWriter {
 public:
  // `output` is a folder, or a file whose name ends in .zip. Throws Error naming it when the temporary
  // package cannot be created.
  explicit PackageWriter(const std::string& output, const PackageWriterOptions& options = {});
  ~PackageWriter();  // without commit(): the temporary package is removed, the previous one kept
  PackageWriter(const PackageWriter&) = delete;
  PackageWriter& operator=(const PackageWriter&) = delete;

  // Writes one entry now. Throws Error naming the entry when its name is unsafe (is_safe_package_path) or
  // already written, or naming the output when the write fails.
  void add(const std::string& name, const std::string& data);
  void add(const std::string& name, const void* data, std::size_t size);
  // The file `source` as the entry `name`, copied in chunks (hotspot videos can be large).
  void add_file(const std::string& name, const std::string& source);

  // Finishes the package and moves it into place (replacing the previous one); returns its size in bytes:
  // the .zip's, or the sum of the folder's files.
  std::uintmax_t commit();

  const std::vector<std::string>& files() const { return files_; }  // entry names, in the order written
  static bool is_zip(const std::string& output);
  // True for the entries a zip deflates: text (json, js, html, css, svg, geojson, kml, gpx, txt).
  static bool is_text(const std::string& name);

  class Sink;  // a folder or a zip (package_writer.cpp)

 private:
  void begin_entry(const std::string& name);
  std::string output_;
  std::unique_ptr<Sink> sink_;
  std::vector<std::string> files_;
  std::set<std::string> names_;  // for the duplicate check
  bool committed_ = false;
};

}  // namespace plenopath
