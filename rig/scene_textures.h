#pragma once
// Procedural textures of the synthetic scene (internal to the renderer): deterministic functions of a seed,
// periodic, with corners and blobs at several scales so that corner trackers find features everywhere.
// Each is kept as a mip pyramid for band-limited sampling.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace plenopath {

enum TextureMaterial : int {
  kMaterialWall0 = 0,  // four plaster variants
  kMaterialWallCount = 4,
  kMaterialPillar = 4,
  kMaterialFurnitureSide = 5,
  kMaterialFurnitureTop = 6,
  kMaterialFloor = 7,
  kMaterialCeiling = 8,
  kMaterialCloth = 9,
  kMaterialPaint = 10,  // plain painted plaster: near-uniform, faint noise (SceneOptions::wall_finish)
  kMaterialCount = 11,
};

struct TexturePyramid {
  std::vector<cv::Mat> levels;  // CV_8UC3; level 0 is the full size, each next level half of it
};

struct SceneTextures {
  std::vector<TexturePyramid> materials;  // indexed by TextureMaterial; square, power-of-two, periodic
  std::vector<TexturePyramid> posters;    // framed posters (not periodic)
  double texels_per_metre = 256.0;
};

// Cached per (seed, size, texels_per_metre): scenes built with the same options share their textures.
std::shared_ptr<const SceneTextures> make_scene_textures(std::uint32_t seed, int size,
                                                         double texels_per_metre);

// A well-mixed 64-bit hash (splitmix64), for per-surface seeds.
std::uint64_t mix_hash(std::uint64_t x);
inline double hash_unit(std::uint64_t x) { return (mix_hash(x) >> 11) * (1.0 / 9007199254740992.0); }

}  // namespace plenopath
