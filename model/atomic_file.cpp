#include "model/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
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

bool all_digits(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

// Temporary files are named ".<name>.tmp<pid>-<random>": one whose writer process no longer exists was left
// by a save that was killed. Versions before 0.6 wrote ".<name>.tmp<random>" (no pid): those are removed
// once they are an hour old, which no save takes.
void remove_stale_temporaries(const fs::path& dir, const std::string& name) {
  const std::string prefix = "." + name + ".tmp";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    if (entry.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = entry.substr(prefix.size());
    const std::size_t dash = rest.find('-');
    bool stale = false;
    if (dash != std::string::npos && all_digits(rest.substr(0, dash)) && all_digits(rest.substr(dash + 1))) {
      const long pid = std::stol(rest.substr(0, dash));
      stale = pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
    } else if (all_digits(rest)) {
      std::error_code time_ec;
      const auto written = fs::last_write_time(it->path(), time_ec);
      stale = !time_ec && fs::file_time_type::clock::now() - written > std::chrono::hours(1);
    }
    std::error_code remove_ec;
    if (stale) fs::remove(it->path(), remove_ec);
  }
}

}  // namespace

std::string resolve_symlinks(const std::string& file) {
  fs::path p(file);
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(p, ec))) return p.string();
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) throw file_error(file, "cannot read the symbolic link " + p.string() + ": " + ec.message());
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  throw file_error(file, "too many levels of symbolic links");
}

void write_file_atomically(const std::string& file, const std::string& contents, bool keep_backup) {
  const fs::path target(resolve_symlinks(file));
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  remove_stale_temporaries(dir, target.filename().string());
  std::random_device rd;
  const fs::path temp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                               std::to_string(rd() % 1000000));

  // 0666: a new file gets what the umask allows, like any other program's; an existing one keeps its mode.
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0)
    throw file_error(file, "cannot create a temporary file in " + dir.string() + ": " + errno_text());
  try {
    struct stat existing {};
    if (::stat(target.c_str(), &existing) == 0) {
      if (::fchmod(fd, existing.st_mode & 07777) != 0)
        throw file_error(file, "cannot keep the file's permissions: " + errno_text());
      // Keeping the owner needs privileges we usually lack: then the saver owns the new version.
      const bool owner_kept = ::fchown(fd, existing.st_uid, existing.st_gid) == 0;
      static_cast<void>(owner_kept);
    }
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
    fs::copy_file(target, fs::path(target.string() + ".bak"), fs::copy_options::overwrite_existing, ec);
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
