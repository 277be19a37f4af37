#pragma once
// An asset as a script: `plenopathAsset("name","data:<mime>;base64,...");`. Browsers refuse file:// images
// as WebGL textures and fetch() of file:// URLs, but load scripts from anywhere; the player
// (resources/player/src/tour_data.js) waits for the call naming the asset it asked for.
#include <cstddef>
#include <string>

namespace plenopath {

std::string base64(const unsigned char* bytes, std::size_t size);

// The script that hands `bytes` (of type `mime`) to the player under `name`.
std::string asset_script(const std::string& name, const std::string& mime, const unsigned char* bytes,
                         std::size_t size);

}  // namespace plenopath
