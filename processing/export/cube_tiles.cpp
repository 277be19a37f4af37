#include "processing/export/cube_tiles.h"

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "model/error.h"

namespace plenopath {

CubeTileLayout cube_tile_layout(int equirect_width, int max_tile_size) {
  if (equirect_width < 64)
    throw Error("cube tiles: the equirectangular width must be at least 64 pixels, not " +
                std::to_string(equirect_width));
  if (max_tile_size < 16)
    throw Error("cube tiles: the tile size must be at least 16 pixels, not " + std::to_string(max_tile_size));
  // A face of w/4 px has about the image's own detail at the face centres (w/4 px over 90 deg against
  // w px over 360 deg), less towards the edges, so w/4 is never an upscale.
  const int target = equirect_width / 4;
  int doublings = 0;
  while ((target >> doublings) > max_tile_size) ++doublings;
  const int tile = std::max(8, (target >> doublings) / 8 * 8);
  CubeTileLayout layout;
  layout.equirect_width = equirect_width / 2 * 2;
  layout.levels.push_back({tile / 2, tile / 2, true});
  for (int level = 0; level <= doublings; ++level) layout.levels.push_back({tile << level, tile, false});
  return layout;
}

const std::array<CubeTileFace, 6>& cube_tile_faces() {
  static const std::array<CubeTileFace, 6> faces = {{{"f", CubeFace::kFront},
                                                     {"r", CubeFace::kRight},
                                                     {"b", CubeFace::kBack},
                                                     {"l", CubeFace::kLeft},
                                                     {"u", CubeFace::kUp},
                                                     {"d", CubeFace::kDown}}};
  return faces;
}

std::string cube_tile_path(int level, const char* face, int y, int x) {
  return std::to_string(level) + "/" + face + "/" + std::to_string(y) + "_" + std::to_string(x) + ".jpg";
}

int write_cube_tiles(const cv::Mat& equirect, const CubeTileLayout& layout, int jpeg_quality,
                     const std::function<void(const std::string& path, std::string jpeg)>& sink) {
  if (equirect.empty() || equirect.type() != CV_8UC3)
    throw Error("cube tiles: the keyframe must be an 8-bit colour image");
  if (layout.levels.empty()) throw Error("cube tiles: the layout has no levels");
  cv::Mat source = equirect;
  if (equirect.cols > layout.equirect_width)
    cv::resize(equirect, source, cv::Size(layout.equirect_width, layout.equirect_width / 2), 0, 0,
               cv::INTER_AREA);
  // One wrapped column on each side and one replicated row above and below, so that bilinear sampling
  // crosses the seam at azimuth +-180 deg and stays inside at the poles.
  cv::Mat wrapped, padded;
  cv::copyMakeBorder(source, wrapped, 0, 0, 1, 1, cv::BORDER_WRAP);
  cv::copyMakeBorder(wrapped, padded, 1, 1, 0, 0, cv::BORDER_REPLICATE);

  const int face_size = layout.face_size();
  int tiles = 0;
  cv::Mat mx(face_size, face_size, CV_32F), my(face_size, face_size, CV_32F);
  for (const CubeTileFace& f : cube_tile_faces()) {
    for (int j = 0; j < face_size; ++j)
      for (int i = 0; i < face_size; ++i) {
        const Eigen::Vector2d p = bearing_to_equirect(
            cube_face_to_bearing(f.face, {i + 0.5, j + 0.5}, face_size), source.cols, source.rows);
        mx.at<float>(j, i) = static_cast<float>(p.x() + 0.5);  // -0.5 to the pixel grid, +1 for the border
        my.at<float>(j, i) = static_cast<float>(p.y() + 0.5);
      }
    cv::Mat face;
    cv::remap(padded, face, mx, my, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    // Finest level first; each coarser one averaged down from the one above it.
    for (int level = layout.max_level(); level >= 0; --level) {
      const CubeTileLevel& l = layout.levels[static_cast<std::size_t>(level)];
      if (face.cols != l.size) {
        cv::Mat smaller;
        cv::resize(face, smaller, cv::Size(l.size, l.size), 0, 0, cv::INTER_AREA);
        face = smaller;
      }
      const int n = l.size / l.tile_size;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          std::vector<unsigned char> bytes;
          const cv::Mat tile = face(cv::Rect(x * l.tile_size, y * l.tile_size, l.tile_size, l.tile_size));
          if (!cv::imencode(".jpg", tile, bytes, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality}))
            throw Error("cube tiles: JPEG encoding failed");
          sink(cube_tile_path(level, f.name, y, x), std::string(bytes.begin(), bytes.end()));
          ++tiles;
        }
    }
  }
  return tiles;
}

nlohmann::json cube_tiles_json(const CubeTileLayout& layout) {
  using nlohmann::json;
  json levels = json::array();
  for (const CubeTileLevel& l : layout.levels) {
    json level = {{"size", l.size}, {"tile_size", l.tile_size}};
    if (l.fallback_only) level["fallback_only"] = true;
    levels.push_back(level);
  }
  json faces = json::array();
  for (const CubeTileFace& f : cube_tile_faces()) {
    const CubeFaceAxes a = cube_face_axes(f.face);
    auto v = [](const Eigen::Vector3d& x) { return json::array({x.x(), x.y(), x.z()}); };
    faces.push_back(
        {{"name", f.name}, {"forward", v(a.forward)}, {"right", v(a.right)}, {"down", v(a.down)}});
  }
  return {
      {"projection", "cube"}, {"path", "{level}/{face}/{y}_{x}.jpg"}, {"levels", levels}, {"faces", faces}};
}

}  // namespace plenopath
