#pragma once
// A Marzipano tour of the package: data.js in the shape the Marzipano Tool writes (APP_DATA with scenes,
// levels, faceSize, initialViewParameters, linkHotspots, infoHotspots) on the cube tiles
// (processing/export/cube_tiles.h), and a minimal page and script that load it. Marzipano itself
// (marzipano.js, npm `marzipano`, Apache-2.0) is not bundled: the page loads ./marzipano.js and, when that
// is missing, the same version from unpkg.
#include <string>
#include <vector>

#include "model/project.h"
#include "processing/export/cube_tiles.h"
#include "processing/export/tour_json.h"

namespace plenopath {

constexpr const char* kMarzipanoVersion = "0.10.2";

// "var APP_DATA = {...};": one scene per keyframe (ids as interop_scenes), yaw and pitch in radians as
// Marzipano counts them (yaw to the right, pitch down), each scene's "tiles" folder and "northOffset"
// (degrees), which the page uses to keep the world direction across a scene change. Keyframes without
// tiles are an Error.
std::string marzipano_data_js(const Project& project, const std::vector<KeyframeImageFiles>& images,
                              const CubeTileLayout& tiles);

// The page (marzipano.html) and its script (marzipano-app.js), as files of the package.
struct MarzipanoPageFile {
  const char* name;
  const char* text;
};
const std::vector<MarzipanoPageFile>& marzipano_page_files();

}  // namespace plenopath
