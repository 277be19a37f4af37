#include "model/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <random>

#include "model/error.h"

namespace plenopath {
namespace fs = std::filesystem;

namespace {

std::string errno_text() { return std::strerror(errno); }

void write_all(int fd, const std::string& contents, const std::string& file) {
  const char* data = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw file_error(file, "write failed: " + errno_text());
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
}

}  // namespace

void write_file_atomically(const std::string& file, const std::string& contents, bool keep_backup) {
  const fs::path target(file);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::random_device rd;
  const fs::path temp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(rd() % 1000000));

  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0)
    throw file_error(file, "cannot create a temporary file in " + dir.string() + ": " + errno_text());
  try {
    write_all(fd, contents, file);
    if (::fsync(fd) != 0) throw file_error(file, "flush to disk failed: " + errno_text());
  } catch (...) {
    ::close(fd);
    ::unlink(temp.c_str());
    throw;
  }
  if (::close(fd) != 0) {
    ::unlink(temp.c_str());
    throw file_error(file, "close failed: " + errno_text());
  }

  std::error_code ec;
  if (keep_backup && fs::exists(target, ec)) {
    // Copy, not rename: `file` must exist at every instant.
    fs::copy_file(target, fs::path(file + ".bak"), fs::copy_options::overwrite_existing, ec);
    if (ec) {
      ::unlink(temp.c_str());
      throw file_error(file, "cannot keep the previous version as .bak: " + ec.message());
    }
  }
  if (::rename(temp.c_str(), target.c_str()) != 0) {
    const std::string why = errno_text();
    ::unlink(temp.c_str());
    throw file_error(file, "cannot replace the file: " + why);
  }
  // Make the rename itself durable.
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
}

std::string path_relative_to(const std::string& absolute, const std::string& base_dir) {
  if (absolute.empty()) return absolute;
  const fs::path p(absolute);
  if (!p.is_absolute() || base_dir.empty()) return p.generic_string();
  const fs::path rel = p.lexically_normal().lexically_relative(fs::absolute(base_dir).lexically_normal());
  return rel.empty() ? p.generic_string() : rel.generic_string();
}

std::string path_resolved_against(const std::string& stored, const std::string& base_dir) {
  if (stored.empty()) return stored;
  const fs::path p(stored);
  if (p.is_absolute() || base_dir.empty()) return p.lexically_normal().string();
  return (fs::absolute(base_dir) / p).lexically_normal().string();
}

}  // namespace plenopath
