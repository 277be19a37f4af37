#pragma once
// Writing files so that a crash never leaves a half-written document behind.
#include <string>

namespace plenopath {

// Writes contents to a temporary file in the same folder, flushes it to disk and renames it over `file`.
// With keep_backup, the previous `file` (if any) is kept as `file + ".bak"`. Throws Error naming the file.
// A symlinked `file` is followed: its target is replaced and the link stays. The file keeps its mode (and
// owner, where permitted); a new file gets 0666 minus the umask. Temporary files that an earlier, killed
// save left beside the file (their writer process is gone) are removed.
void write_file_atomically(const std::string& file, const std::string& contents, bool keep_backup);

// The file a write to `file` lands in: `file` itself, or the final target of a chain of symlinks (also a
// dangling one). Throws Error naming the file on a symlink loop.
std::string resolve_symlinks(const std::string& file);

// `absolute` expressed relative to `base_dir` (generic separators); empty stays empty.
std::string path_relative_to(const std::string& absolute, const std::string& base_dir);
// `stored` resolved against `base_dir` unless it is already absolute; empty stays empty.
std::string path_resolved_against(const std::string& stored, const std::string& base_dir);

}  // namespace plenopath
