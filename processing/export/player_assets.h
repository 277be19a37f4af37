#pragma once
// The web player's files, compiled into the binary by cmake/EmbedFiles.cmake: index.html and player.css from
// resources/player/, player.js joined from resources/player/src/ and tour.schema.json filled from
// resources/schema/ (processing/CMakeLists.txt).
#include <cstddef>
#include <vector>

namespace plenopath {

struct EmbeddedFile {
  const char* name;  // file name in the exported package
  const unsigned char* data;
  std::size_t size;
};

const std::vector<EmbeddedFile>& player_assets();

}  // namespace plenopath
