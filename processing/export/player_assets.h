#pragma once
// The web player's files (resources/player/), compiled into the binary by cmake/EmbedFiles.cmake.
#include <cstddef>
#include <vector>

namespace plenopath {

struct EmbeddedFile {
  const char* name;  // file name inside resources/player/
  const unsigned char* data;
  std::size_t size;
};

const std::vector<EmbeddedFile>& player_assets();

}  // namespace plenopath
