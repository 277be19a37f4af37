#pragma once
// Multi-resolution cube tiles of a keyframe: the six cube faces (rig/spherical.h's geometry) at a few
// levels, each cut into square JPEG tiles, laid out so that one set of files serves Pannellum's multiRes
// (levels 1..n, path "%l/%s/%y_%x") and Marzipano's cube geometry (levels 0..n, "{z}/{f}/{y}_{x}.jpg") and
// our player (tour.json "tiles", resources/schema/tour.schema.json).
//
// Both readers draw a face as seen from inside the cube, upright for the four side faces, with the top of
// "u" towards the back and the top of "d" towards the front: exactly rig/spherical.h's cube_face_axes, so
// the tiles are cut from those faces unchanged.
#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rig/spherical.h"

namespace plenopath {

struct CubeTileLevel {
  int size = 0;       // face width and height, pixels
  int tile_size = 0;  // tile width and height, pixels; size is a multiple of it
  bool fallback_only = false;
};

// Level 0: one small tile per face, shown while the rest loads (Marzipano's fallbackOnly level; Pannellum's
// fallbackPath). Levels 1..n: each twice the previous, level 1 one tile per face, all of one tile size, so
// that Pannellum's quadtree (one tileResolution) and Marzipano's rule (a level's size a multiple of its
// tile size and of its parent's) hold at once.
struct CubeTileLayout {
  int equirect_width = 0;  // the equirectangular width the faces are cut from (height: half)
  std::vector<CubeTileLevel> levels;
  int max_level() const { return static_cast<int>(levels.size()) - 1; }
  int face_size() const { return levels.back().size; }
  int tile_size() const { return levels.back().tile_size; }
};

// The levels for an equirectangular image of `equirect_width` pixels: the largest face about a quarter of
// that width (never more: the cube then holds no more detail than the image), tiles at most
// `max_tile_size` pixels, sizes multiples of 8 (whole JPEG blocks). Throws Error for widths under 64 or
// tile sizes under 16.
CubeTileLayout cube_tile_layout(int equirect_width, int max_tile_size);

// The faces in Pannellum's order, with their one-letter names (as both readers spell them).
struct CubeTileFace {
  const char* name;
  CubeFace face;
};
const std::array<CubeTileFace, 6>& cube_tile_faces();

// A tile's file below the keyframe's tiles folder: "<level>/<face>/<y>_<x>.jpg".
std::string cube_tile_path(int level, const char* face, int y, int x);

// Cuts `equirect` (8-bit BGR, 2:1; resized to layout.equirect_width first when larger) into the layout's
// tiles, one face at a time (memory: one face of the largest level), and hands each JPEG to `sink` with its
// path from cube_tile_path. Returns the number of tiles.
int write_cube_tiles(const cv::Mat& equirect, const CubeTileLayout& layout, int jpeg_quality,
                     const std::function<void(const std::string& path, std::string jpeg)>& sink);

// tour.json's "tiles" object (resources/schema/tour.schema.json).
nlohmann::json cube_tiles_json(const CubeTileLayout& layout);

}  // namespace plenopath
