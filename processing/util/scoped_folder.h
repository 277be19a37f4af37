#pragma once
// A work folder that goes when its scope ends, however it ends (a render's passes, a failed run).
#include <filesystem>
#include <system_error>

namespace plenopath {

struct RemoveFolderOnExit {
  std::filesystem::path folder;
  explicit RemoveFolderOnExit(std::filesystem::path f) : folder(std::move(f)) {}
  RemoveFolderOnExit(const RemoveFolderOnExit&) = delete;
  RemoveFolderOnExit& operator=(const RemoveFolderOnExit&) = delete;
  ~RemoveFolderOnExit() {
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
  }
};

}  // namespace plenopath
