#include "processing/export/package_reader.h"

#include <archive.h>
#include <archive_entry.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>

#include "model/error.h"
#include "processing/export/package_path.h"

namespace plenopath {
namespace fs = std::filesystem;

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// One pass over a zip's entries; `visit` gets each entry's name and returns true to have its data read
// through `sink` (chunks), false to skip it.
using ChunkSink = std::function<void(const char* data, std::size_t size)>;
void for_each_zip_entry(const std::string& file,
                        const std::function<bool(const std::string& name, ChunkSink& sink)>& visit,
                        Progress& progress = null_progress()) {
  std::unique_ptr<archive, decltype(&archive_read_free)> a(archive_read_new(), &archive_read_free);
  archive_read_support_format_zip(a.get());
  if (archive_read_open_filename(a.get(), file.c_str(), 1 << 16) != ARCHIVE_OK)
    throw file_error(file, std::string("cannot open as a zip: ") + archive_error_string(a.get()));
  const auto total = fs::file_size(file);
  archive_entry* entry = nullptr;
  for (;;) {
    const int r = archive_read_next_header(a.get(), &entry);
    if (r == ARCHIVE_EOF) break;
    if (r != ARCHIVE_OK && r != ARCHIVE_WARN)
      throw file_error(file, std::string("damaged zip: ") + archive_error_string(a.get()));
    if (total > 0) progress.checkpoint(double(archive_filter_bytes(a.get(), -1)) / double(total));
    if (archive_entry_filetype(entry) != AE_IFREG) continue;
    const char* raw_name = archive_entry_pathname(entry);
    if (!raw_name) continue;
    ChunkSink sink;
    if (!visit(raw_name, sink)) continue;
    const void* buffer = nullptr;
    std::size_t size = 0;
    la_int64_t offset = 0;
    for (;;) {
      const int d = archive_read_data_block(a.get(), &buffer, &size, &offset);
      if (d == ARCHIVE_EOF) break;
      if (d != ARCHIVE_OK && d != ARCHIVE_WARN)
        throw file_error(file, std::string(raw_name) + ": damaged entry: " + archive_error_string(a.get()));
      sink(static_cast<const char*>(buffer), size);
    }
  }
}

}  // namespace

void PackageReadOptions::check() const {
  if (max_entry_bytes == 0) throw Error("package reader: max_entry_bytes must be positive");
}

PackageReader::PackageReader(std::string package, PackageReadOptions options)
    : package_(std::move(package)), options_(options) {
  options_.check();
  std::error_code ec;
  if (fs::is_directory(package_, ec)) {
    if (!fs::is_regular_file(fs::path(package_) / "tour.json", ec))
      throw file_error(package_, "not a tour package: it holds no tour.json");
    return;
  }
  if (!fs::is_regular_file(package_, ec)) throw file_error(package_, "no such file or folder");
  if (fs::path(package_).filename() == "tour.json") {
    package_ = fs::path(package_).parent_path().string();
    if (package_.empty()) package_ = ".";
    return;
  }
  zip_ = true;
  // Zips made by hand from a folder hold everything under that folder's name.
  std::vector<std::string> all;
  for_each_zip_entry(package_, [&](const std::string& name, ChunkSink&) {
    all.push_back(name);
    return false;
  });
  bool at_root = false;
  std::string prefix;
  for (const std::string& n : all) {
    if (n == "tour.json") at_root = true;
    if (ends_with(n, "/tour.json") && n.find('/') == n.size() - 10) prefix = n.substr(0, n.size() - 9);
  }
  if (at_root) return;
  if (prefix.empty()) throw file_error(package_, "not a tour package: the zip holds no tour.json");
  for (const std::string& n : all)
    if (n.compare(0, prefix.size(), prefix) != 0)
      throw file_error(package_, "not a tour package: tour.json is in " + prefix + " but " + n + " is not");
  root_in_zip_ = prefix;
}

std::vector<std::string> PackageReader::names() const {
  std::vector<std::string> out;
  if (!zip_) {
    for (const auto& e : fs::recursive_directory_iterator(package_))
      if (e.is_regular_file()) out.push_back(fs::relative(e.path(), package_).generic_string());
    return out;
  }
  for_each_zip_entry(package_, [&](const std::string& name, ChunkSink&) {
    if (name.compare(0, root_in_zip_.size(), root_in_zip_) == 0)
      out.push_back(name.substr(root_in_zip_.size()));
    return false;
  });
  return out;
}

std::optional<std::string> PackageReader::read(const std::string& name) const {
  if (!is_safe_package_path(name)) throw file_error(package_, "unsafe entry name \"" + name + "\"");
  if (!zip_) {
    const fs::path file = fs::path(package_) / name;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return std::nullopt;
    if (fs::file_size(file) > options_.max_entry_bytes)
      throw file_error(file.string(), "larger than a package entry may be");
    std::ifstream in(file, std::ios::binary);
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw file_error(file.string(), "cannot be read");
    return data;
  }
  std::optional<std::string> out;
  for_each_zip_entry(package_, [&](const std::string& entry_name, ChunkSink& sink) {
    if (out || entry_name != root_in_zip_ + name) return false;
    out.emplace();
    sink = [&](const char* data, std::size_t size) {
      if (out->size() + size > options_.max_entry_bytes)
        throw file_error(package_, name + ": larger than a package entry may be");
      out->append(data, size);
    };
    return true;
  });
  return out;
}

std::vector<std::string> PackageReader::extract(const std::set<std::string>& wanted,
                                                const std::string& folder, Progress& progress) const {
  for (const std::string& n : wanted)
    if (!is_safe_package_path(n)) throw file_error(package_, "unsafe entry name \"" + n + "\"");
  std::set<std::string> missing = wanted;
  auto target_of = [&](const std::string& name) {
    const fs::path target = fs::path(folder) / name;
    fs::create_directories(target.parent_path());
    return target;
  };
  if (!zip_) {
    std::size_t done = 0;
    for (const std::string& n : wanted) {
      progress.checkpoint(double(done++) / std::max<std::size_t>(1, wanted.size()));
      const fs::path source = fs::path(package_) / n;
      std::error_code ec;
      if (!fs::is_regular_file(source, ec)) continue;
      if (fs::file_size(source) > options_.max_entry_bytes)
        throw file_error(source.string(), "larger than a package entry may be");
      const fs::path target = target_of(n);
      fs::copy_file(source, target, fs::copy_options::overwrite_existing, ec);
      if (ec) throw file_error(target.string(), "cannot be written: " + ec.message());
      missing.erase(n);
    }
    return {missing.begin(), missing.end()};
  }
  std::ofstream out;
  std::string current;
  std::uint64_t written = 0;
  auto close_current = [&]() {
    if (!out.is_open()) return;
    out.close();
    if (!out) throw file_error((fs::path(folder) / current).string(), "cannot be written");
  };
  for_each_zip_entry(
      package_,
      [&](const std::string& entry_name, ChunkSink& sink) {
        if (entry_name.compare(0, root_in_zip_.size(), root_in_zip_) != 0) return false;
        const std::string name = entry_name.substr(root_in_zip_.size());
        if (!missing.count(name)) return false;
        close_current();
        missing.erase(name);
        current = name;
        written = 0;
        out.open(target_of(name), std::ios::binary | std::ios::trunc);
        if (!out) throw file_error((fs::path(folder) / name).string(), "cannot be written");
        sink = [&](const char* data, std::size_t size) {
          written += size;
          if (written > options_.max_entry_bytes)
            throw file_error(package_, current + ": larger than a package entry may be");
          out.write(data, static_cast<std::streamsize>(size));
        };
        return true;
      },
      progress);
  close_current();
  return {missing.begin(), missing.end()};
}

}  // namespace plenopath
