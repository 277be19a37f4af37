#include "processing/export/package_writer.h"

#include <archive.h>
#include <archive_entry.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "model/atomic_file.h"
#include "model/error.h"
#include "processing/export/package_path.h"

namespace plenopath {
namespace fs = std::filesystem;

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A temporary name beside `target` that no other process uses.
fs::path temporary_beside(const fs::path& target, const std::string& what) {
  return target.parent_path() / ("." + target.filename().string() + "." + what + std::to_string(::getpid()));
}

bool all_digits(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

// What an export killed mid-way (no destructor ran) left beside `target`: its ".partial<pid>" is removed;
// its ".old<pid>" (killed between the two renames of a folder's replacement) goes back in place when the
// target is missing, and is removed otherwise. Only for writers whose process is gone.
void clean_up_after_killed_writers(const fs::path& target) {
  const std::string prefix = "." + target.filename().string() + ".";
  std::error_code ec;
  std::vector<fs::path> partial, old;
  for (fs::directory_iterator it(target.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    if (entry.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = entry.substr(prefix.size());
    for (const char* kind : {"partial", "old"}) {
      const std::string k = kind;
      if (rest.compare(0, k.size(), k) != 0 || !all_digits(rest.substr(k.size()))) continue;
      const long pid = std::stol(rest.substr(k.size()));
      if (pid <= 0 || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
      (k == "partial" ? partial : old).push_back(it->path());
    }
  }
  for (const fs::path& p : partial) fs::remove_all(p, ec);
  for (const fs::path& p : old) {
    if (!fs::exists(fs::symlink_status(target, ec))) fs::rename(p, target, ec);
    if (fs::exists(fs::symlink_status(p, ec))) fs::remove_all(p, ec);
  }
}

}  // namespace

class PackageWriter::Sink {
 public:
  virtual ~Sink() = default;
  virtual void begin(const std::string& name, std::uintmax_t size, bool text) = 0;
  virtual void write(const void* data, std::size_t size) = 0;
  virtual void end() = 0;
  virtual std::uintmax_t commit() = 0;
};

namespace {

// Entries written into a temporary zip (libarchive) that commit() renames over the target.
class ZipSink : public PackageWriter::Sink {
 public:
  ZipSink(const std::string& output, const PackageWriterOptions& options) : output_(output) {
    target_ = resolve_symlinks(fs::absolute(output).lexically_normal().string());
    std::error_code ec;
    if (fs::is_directory(target_, ec)) throw file_error(output, "is a folder, not a .zip file");
    temp_ = temporary_beside(target_, "partial");
    clean_up_after_killed_writers(target_);
    archive_ = archive_write_new();
    if (!archive_) throw file_error(output, "cannot start the zip archive (out of memory)");
    const std::string level = std::to_string(options.deflate_level);
    if (archive_write_set_format_zip(archive_) != ARCHIVE_OK ||
        archive_write_set_format_option(archive_, "zip", "compression-level", level.c_str()) < ARCHIVE_OK ||
        (options.force_zip64 && archive_write_set_format_option(archive_, "zip", "zip64", "1") < ARCHIVE_OK))
      fail("cannot set up the zip format");
    // No padding to 10 KiB blocks: the zip ends where its central directory does.
    archive_write_set_bytes_in_last_block(archive_, 1);
    if (archive_write_open_filename(archive_, temp_.c_str()) != ARCHIVE_OK) fail("cannot create the file");
    entry_ = archive_entry_new();
  }
  ~ZipSink() override {
    if (entry_) archive_entry_free(entry_);
    if (archive_) archive_write_free(archive_);  // closes the file if commit() did not
    if (!committed_) {
      std::error_code ec;
      fs::remove(temp_, ec);
    }
  }

  void begin(const std::string& name, std::uintmax_t size, bool text) override {
    // Images, video and audio are compressed already: deflating them costs time and saves nothing.
    if ((text ? archive_write_zip_set_compression_deflate(archive_)
              : archive_write_zip_set_compression_store(archive_)) != ARCHIVE_OK)
      fail("cannot set the compression of '" + name + "'");
    archive_entry_clear(entry_);
    archive_entry_set_pathname(entry_, name.c_str());
    archive_entry_set_filetype(entry_, AE_IFREG);
    archive_entry_set_perm(entry_, 0644);
    archive_entry_set_size(entry_, static_cast<la_int64_t>(size));
    archive_entry_set_mtime(entry_, kFixedTime, 0);  // a fixed stamp keeps packages reproducible
    if (archive_write_header(archive_, entry_) != ARCHIVE_OK) fail("cannot write the entry '" + name + "'");
    entry_name_ = name;
  }
  void write(const void* data, std::size_t size) override {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
      const la_ssize_t n = archive_write_data(archive_, p, size);
      if (n <= 0) fail("cannot write the entry '" + entry_name_ + "'");
      p += n;
      size -= static_cast<std::size_t>(n);
    }
  }
  void end() override {
    if (archive_write_finish_entry(archive_) != ARCHIVE_OK)
      fail("cannot finish the entry '" + entry_name_ + "'");
  }
  std::uintmax_t commit() override {
    if (archive_write_close(archive_) != ARCHIVE_OK) fail("cannot finish the archive (disk full?)");
    // On disk before the rename, so that a crash right after it never leaves a truncated package.
    const int fd = ::open(temp_.c_str(), O_RDONLY);
    const bool synced = fd >= 0 && ::fsync(fd) == 0;
    if (fd >= 0) ::close(fd);
    if (!synced) throw file_error(output_, "cannot flush the archive to disk");
    std::error_code ec;
    fs::rename(temp_, target_, ec);  // atomic: readers see the old package or the new one
    if (ec) throw file_error(output_, "cannot move the package into place: " + ec.message());
    committed_ = true;
    return fs::file_size(target_);
  }

 private:
  static constexpr time_t kFixedTime = 1767225600;  // 2026-01-01 00:00 UTC
  [[noreturn]] void fail(const std::string& what) {
    const char* why = archive_ ? archive_error_string(archive_) : nullptr;
    throw file_error(output_, what + (why ? std::string(": ") + why : std::string()));
  }
  std::string output_;
  fs::path target_, temp_;
  struct archive* archive_ = nullptr;
  struct archive_entry* entry_ = nullptr;
  std::string entry_name_;
  bool committed_ = false;
};

// Entries written as files of a temporary folder that commit() renames over the target.
class FolderSink : public PackageWriter::Sink {
 public:
  explicit FolderSink(const std::string& output) : output_(output) {
    target_ = fs::absolute(output).lexically_normal();
    if (target_.filename().empty()) target_ = target_.parent_path();  // "out/" names the folder "out"
    staging_ = temporary_beside(target_, "partial");
    clean_up_after_killed_writers(target_);
    std::error_code ec;
    fs::remove_all(staging_, ec);
    fs::create_directories(staging_, ec);
    if (ec) throw file_error(output, "cannot create the package folder: " + ec.message());
  }
  ~FolderSink() override {
    std::error_code ec;
    if (!committed_) fs::remove_all(staging_, ec);
  }
  void begin(const std::string& name, std::uintmax_t, bool) override {
    file_ = staging_ / name;
    std::error_code ec;
    fs::create_directories(file_.parent_path(), ec);
    out_.open(file_, std::ios::binary | std::ios::trunc);
    if (!out_) throw file_error(file_.string(), "cannot create the file: " + ec.message());
  }
  void write(const void* data, std::size_t size) override {
    out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out_) throw file_error(file_.string(), "write failed (disk full?)");
    total_ += size;
  }
  void end() override {
    out_.close();
    if (!out_) throw file_error(file_.string(), "write failed (disk full?)");
  }
  std::uintmax_t commit() override {
    // The previous package steps aside, the new one takes its place, and only then is the old one removed:
    // no instant without a whole package, and a failed rename puts the old one back.
    std::error_code ec;
    const fs::path old = temporary_beside(target_, "old");
    const bool had_previous = fs::exists(fs::symlink_status(target_, ec));
    if (had_previous) {
      fs::remove_all(old, ec);
      fs::rename(target_, old, ec);
      if (ec) throw file_error(output_, "cannot replace the previous package: " + ec.message());
    }
    fs::rename(staging_, target_, ec);
    if (ec) {
      std::error_code ignored;
      if (had_previous) fs::rename(old, target_, ignored);
      throw file_error(output_, "cannot move the package into place: " + ec.message());
    }
    committed_ = true;
    if (had_previous) fs::remove_all(old, ec);
    return total_;
  }

 private:
  std::string output_;
  fs::path target_, staging_, file_;
  std::ofstream out_;
  std::uintmax_t total_ = 0;
  bool committed_ = false;
};

}  // namespace

void PackageWriterOptions::check() const {
  if (deflate_level < 1 || deflate_level > 9)
    throw Error("package writer: deflate_level must be within 1..9");
}

bool PackageWriter::is_zip(const std::string& output) { return ends_with(lower(output), ".zip"); }

bool PackageWriter::is_text(const std::string& name) {
  const std::string ext = lower(fs::path(name).extension().string());
  for (const char* t : {".json", ".js", ".html", ".css", ".svg", ".geojson", ".kml", ".gpx", ".txt"})
    if (ext == t) return true;
  return false;
}

PackageWriter::PackageWriter(const std::string& output, const PackageWriterOptions& options)
    : output_(output) {
  if (output.empty()) throw Error("export: no output given (a folder or a .zip file)");
  options.check();
  if (is_zip(output))
    sink_ = std::make_unique<ZipSink>(output, options);
  else
    sink_ = std::make_unique<FolderSink>(output);
}

PackageWriter::~PackageWriter() = default;

void PackageWriter::begin_entry(const std::string& name) {
  if (committed_) throw file_error(output_, "the package is finished: cannot add '" + name + "'");
  if (!is_safe_package_path(name))
    throw file_error(output_, "unsafe path inside the package: '" + name + "'");
  if (!names_.insert(name).second) throw file_error(output_, "duplicate file in the package: '" + name + "'");
  files_.push_back(name);
}

void PackageWriter::add(const std::string& name, const std::string& data) {
  add(name, data.data(), data.size());
}

void PackageWriter::add(const std::string& name, const void* data, std::size_t size) {
  begin_entry(name);
  sink_->begin(name, size, is_text(name));
  sink_->write(data, size);
  sink_->end();
}

void PackageWriter::add_file(const std::string& name, const std::string& source) {
  std::ifstream in(source, std::ios::binary);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(source, ec);
  if (!in || ec) throw file_error(source, "cannot open for reading");
  begin_entry(name);
  sink_->begin(name, size, is_text(name));
  std::vector<char> chunk(1 << 20);
  std::uintmax_t left = size;
  while (left > 0) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uintmax_t>(left, chunk.size()));
    if (!in.read(chunk.data(), static_cast<std::streamsize>(n)))
      throw file_error(source, "read failed (the file changed while it was exported?)");
    sink_->write(chunk.data(), n);
    left -= n;
  }
  sink_->end();
}

std::uintmax_t PackageWriter::commit() {
  if (committed_) throw file_error(output_, "the package is already finished");
  const std::uintmax_t bytes = sink_->commit();
  committed_ = true;
  return bytes;
}

}  // namespace plenopath
