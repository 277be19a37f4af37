// Cube tiles: the levels against hand-computed figures and against both readers' rules (Pannellum's quadtree,
// Marzipano's CubeGeometry checks), and the face images against the readers' face conventions (read from
// pannellum src/js/libpannellum.js createCube and marzipano src/geometries/Cube.js; seen in the real viewers
// by tests/app/viewer_check.py) on an equirectangular image coloured by hand from ARCHITECTURE.md's formula.
#include "processing/export/cube_tiles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "model/error.h"

namespace plenopath {
namespace {

std::vector<std::array<int, 3>> figures(const CubeTileLayout& l) {
  std::vector<std::array<int, 3>> out;
  for (const CubeTileLevel& v : l.levels) out.push_back({v.size, v.tile_size, v.fallback_only ? 1 : 0});
  return out;
}

TEST(CubeTileLayout, LevelsAsComputedByHand) {
  using F = std::vector<std::array<int, 3>>;
  // 4096 px: faces of 1024 (4096 / 4), tiles of 512, a 256 fallback.
  EXPECT_EQ(figures(cube_tile_layout(4096, 512)), (F{{256, 256, 1}, {512, 512, 0}, {1024, 512, 0}}));
  EXPECT_EQ(figures(cube_tile_layout(2048, 256)), (F{{128, 128, 1}, {256, 256, 0}, {512, 256, 0}}));
  // 3000 px: 750 is one doubling of 375, rounded down to whole JPEG blocks: 368.
  EXPECT_EQ(figures(cube_tile_layout(3000, 512)), (F{{184, 184, 1}, {368, 368, 0}, {736, 368, 0}}));
  EXPECT_EQ(figures(cube_tile_layout(1024, 512)), (F{{128, 128, 1}, {256, 256, 0}}));
  EXPECT_EQ(figures(cube_tile_layout(16384, 512)),
            (F{{256, 256, 1}, {512, 512, 0}, {1024, 512, 0}, {2048, 512, 0}, {4096, 512, 0}}));
  EXPECT_THROW(cube_tile_layout(32, 512), Error);
  EXPECT_THROW(cube_tile_layout(4096, 8), Error);
}

TEST(CubeTileLayout, EveryWidthSatisfiesBothReaders) {
  for (int width = 64; width <= 16384; width += 38)
    for (int tile : {128, 256, 512, 1024}) {
      const CubeTileLayout l = cube_tile_layout(width, tile);
      SCOPED_TRACE(std::to_string(width) + " px, tiles " + std::to_string(tile));
      EXPECT_LE(l.face_size(), width / 4);  // never an upscale
      EXPECT_GT(l.face_size(), width / 4 - 8 * (1 << l.max_level()));
      EXPECT_LE(l.tile_size(), tile);
      for (std::size_t i = 0; i < l.levels.size(); ++i) {
        const CubeTileLevel& v = l.levels[i];
        // Marzipano: a level's size is a multiple of its tile size and of its parent's size, its tile count a
        // multiple of its parent's.
        EXPECT_EQ(v.size % v.tile_size, 0);
        if (i > 0) {
          const CubeTileLevel& p = l.levels[i - 1];
          EXPECT_EQ(v.size % p.size, 0);
          EXPECT_EQ((v.size / v.tile_size) % (p.size / p.tile_size), 0);
        }
        // Pannellum: level i (1..maxLevel) is cubeResolution / 2^(maxLevel - i) with one tileResolution,
        // level 1 one tile.
        if (i >= 1) {
          EXPECT_EQ(v.size, l.face_size() >> (l.max_level() - static_cast<int>(i)));
          EXPECT_EQ(v.tile_size, l.tile_size());
        }
      }
      EXPECT_EQ(l.levels[1].size, l.tile_size());
      EXPECT_TRUE(l.levels[0].fallback_only);
    }
}

// The colour of a direction: red for up, green grows with azimuth, blue for the front half. Drawn from
// ARCHITECTURE.md's pixel formula alone.
cv::Vec3b colour_of(double azimuth_deg, double elevation_deg) {
  const unsigned char up = elevation_deg > 0 ? 255 : 0;
  const unsigned char green = static_cast<unsigned char>((azimuth_deg + 180.0) / 360.0 * 255.0);
  const unsigned char front = std::abs(azimuth_deg) < 90 ? 255 : 0;
  return {front, green, up};  // BGR
}

cv::Mat coloured_equirect(int width) {
  cv::Mat image(width / 2, width, CV_8UC3);
  for (int v = 0; v < image.rows; ++v)
    for (int u = 0; u < image.cols; ++u)
      image.at<cv::Vec3b>(v, u) =
          colour_of((u + 0.5) / width * 360.0 - 180.0, 90.0 - (v + 0.5) / image.rows * 180.0);
  return image;
}

TEST(CubeTiles, FacesRunAsTheReadersDrawThem) {
  const CubeTileLayout layout = cube_tile_layout(2048, 256);
  std::map<std::string, cv::Mat> tiles;
  const int count =
      write_cube_tiles(coloured_equirect(2048), layout, 95, [&](const std::string& path, std::string jpeg) {
        tiles[path] = cv::imdecode(std::vector<unsigned char>(jpeg.begin(), jpeg.end()), cv::IMREAD_COLOR);
      });
  EXPECT_EQ(count, 6 * (1 + 1 + 4));
  ASSERT_EQ(tiles.size(), 36u);
  for (const auto& [path, tile] : tiles) EXPECT_EQ(tile.cols, path[0] == '0' ? 128 : 256) << path;
  ASSERT_TRUE(tiles.count("2/u/1_0.jpg") && tiles.count("2/d/0_1.jpg") && tiles.count("0/b/0_0.jpg"));

  // Level 2 (512 px, 2 x 2 tiles): a face pixel (x, y) of tile (tx, ty) is face pixel (256 tx + x, 256 ty +
  // y).
  auto face_pixel = [&](const char* face, int x, int y) {
    const std::string key =
        "2/" + std::string(face) + "/" + std::to_string(y / 256) + "_" + std::to_string(x / 256) + ".jpg";
    return tiles.at(key).at<cv::Vec3b>(y % 256, x % 256);
  };
  auto near = [](cv::Vec3b a, cv::Vec3b b) { return cv::norm(cv::Vec3i(a) - cv::Vec3i(b)) < 30; };
  // Beside the face centres (away from the colour's edges at +-90 and 180 deg): f azimuth 0, r +90 (right),
  // b 180, l -90. 44 px off a 512 px face's centre is atan(88 / 512) = 9.9 deg.
  EXPECT_TRUE(near(face_pixel("f", 256, 300), colour_of(0, -5)));
  EXPECT_TRUE(near(face_pixel("r", 212, 300), colour_of(80.1, -5)));
  EXPECT_TRUE(near(face_pixel("l", 300, 300), colour_of(-80.1, -5)));
  EXPECT_TRUE(near(face_pixel("b", 300, 300), colour_of(-175, -5)));  // right of b's centre: past 180, -175
  // Side faces run left to right with azimuth: f's right edge is at +45 deg, its left edge at -45.
  EXPECT_TRUE(near(face_pixel("f", 500, 300), colour_of(44, -5)));
  EXPECT_TRUE(near(face_pixel("f", 12, 300), colour_of(-44, -5)));
  // u: its top edge is towards the back, its right edge to the right; d: its top edge towards the front.
  EXPECT_TRUE(near(face_pixel("u", 300, 20), colour_of(169.3, 47)));  // back, a little to the right
  EXPECT_TRUE(near(face_pixel("u", 256, 492), colour_of(0, 50)));
  EXPECT_TRUE(near(face_pixel("u", 492, 300), colour_of(79.3, 50)));
  EXPECT_TRUE(near(face_pixel("d", 256, 20), colour_of(0, -50)));
  EXPECT_TRUE(near(face_pixel("d", 492, 212), colour_of(79.3, -50)));
  EXPECT_TRUE(near(face_pixel("d", 20, 212), colour_of(-79.3, -50)));
  // Coarser levels are the same picture: the 128 px fallback of f at its centre.
  EXPECT_TRUE(near(tiles.at("0/f/0_0.jpg").at<cv::Vec3b>(70, 64), colour_of(0, -5)));
}

TEST(CubeTiles, TourJsonDescribesTheFaces) {
  const nlohmann::json j = cube_tiles_json(cube_tile_layout(4096, 512));
  EXPECT_EQ(j["path"], "{level}/{face}/{y}_{x}.jpg");
  ASSERT_EQ(j["levels"].size(), 3u);
  EXPECT_EQ(j["levels"][0]["fallback_only"], true);
  EXPECT_EQ(j["levels"][2]["size"], 1024);
  ASSERT_EQ(j["faces"].size(), 6u);
  // Pannellum's order f r b l u d; u looks up (+z) with its image's "down" towards the front (+x).
  std::string order;
  for (const auto& f : j["faces"]) order += f["name"].get<std::string>();
  EXPECT_EQ(order, "frblud");
  EXPECT_EQ(j["faces"][4]["forward"], nlohmann::json::array({0.0, 0.0, 1.0}));
  EXPECT_EQ(j["faces"][4]["down"], nlohmann::json::array({1.0, 0.0, 0.0}));
  EXPECT_EQ(j["faces"][1]["forward"], nlohmann::json::array({0.0, -1.0, 0.0}));  // r: the camera's right, -y
}

}  // namespace
}  // namespace plenopath
