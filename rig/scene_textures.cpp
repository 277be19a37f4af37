#include "rig/scene_textures.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <tuple>

namespace plenopath {

std::uint64_t mix_hash(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

namespace {

// Periodic value noise: a g x g random grid, wrapped, smoothly resized to n x n. Values in [-1, 1].
cv::Mat periodic_noise(cv::RNG& rng, int n, int g) {
  cv::Mat grid(g, g, CV_32F);
  rng.fill(grid, cv::RNG::UNIFORM, -1.0f, 1.0f);
  const int pad = 2;
  cv::Mat padded;
  cv::copyMakeBorder(grid, padded, pad, pad, pad, pad, cv::BORDER_WRAP);
  const int cell = n / g;
  cv::Mat big;
  cv::resize(padded, big, cv::Size((g + 2 * pad) * cell, (g + 2 * pad) * cell), 0, 0, cv::INTER_CUBIC);
  return big(cv::Rect(pad * cell, pad * cell, n, n)).clone();
}

// Adds noise at several scales to every channel, with a per-channel weight.
void add_noise(cv::Mat& img, cv::RNG& rng, const std::vector<std::pair<int, float>>& octaves,
               cv::Vec3f weight) {
  const int n = img.rows;
  cv::Mat acc = cv::Mat::zeros(n, n, CV_32F);
  for (const auto& [g, amplitude] : octaves) acc += amplitude * periodic_noise(rng, n, std::min(g, n));
  cv::Mat f;
  img.convertTo(f, CV_32FC3);
  std::vector<cv::Mat> ch;
  cv::split(f, ch);
  for (int k = 0; k < 3; ++k) ch[k] += weight[k] * acc;
  cv::merge(ch, f);
  f.convertTo(img, CV_8UC3);
}

// A light blur that keeps the texture periodic (filters do not all accept BORDER_WRAP).
void wrap_blur(cv::Mat& img) {
  cv::Mat padded, blurred;
  cv::copyMakeBorder(img, padded, 2, 2, 2, 2, cv::BORDER_WRAP);
  cv::GaussianBlur(padded, blurred, cv::Size(3, 3), 0.7, 0.7);
  img = blurred(cv::Rect(2, 2, img.cols, img.rows)).clone();
}

// Draws a shape at its position and at its periodic copies so the texture tiles seamlessly.
template <typename Draw>
void draw_wrapped(int n, Draw draw) {
  for (int oy = -n; oy <= n; oy += n)
    for (int ox = -n; ox <= n; ox += n) draw(cv::Point(ox, oy));
}

// Mostly a change of brightness (what corner detectors see), with a little change of hue.
cv::Scalar jitter(cv::RNG& rng, cv::Vec3b base, int amount) {
  const int light = rng.uniform(-amount, amount + 1);
  const int hue = std::max(1, amount / 4);
  return cv::Scalar(cv::saturate_cast<uchar>(base[0] + light + rng.uniform(-hue, hue + 1)),
                    cv::saturate_cast<uchar>(base[1] + light + rng.uniform(-hue, hue + 1)),
                    cv::saturate_cast<uchar>(base[2] + light + rng.uniform(-hue, hue + 1)));
}

// Rectangles (corners) and discs (blobs) from large to small.
void scatter_shapes(cv::Mat& img, cv::RNG& rng, cv::Vec3b base, int count, int max_size, int contrast) {
  const int n = img.rows;
  for (int i = 0; i < count; ++i) {
    const double scale = std::pow(0.5, rng.uniform(0.0, 4.0));  // several octaves of sizes
    const int size = std::max(3, static_cast<int>(max_size * scale));
    const cv::Point p(rng.uniform(0, n), rng.uniform(0, n));
    const cv::Scalar colour = jitter(rng, base, contrast);
    if (rng.uniform(0, 2) == 0) {
      const cv::Size s(size, std::max(3, static_cast<int>(size * rng.uniform(0.3, 1.5))));
      draw_wrapped(
          n, [&](cv::Point o) { cv::rectangle(img, cv::Rect(p + o, s), colour, cv::FILLED, cv::LINE_8); });
    } else {
      draw_wrapped(n,
                   [&](cv::Point o) { cv::circle(img, p + o, size / 2, colour, cv::FILLED, cv::LINE_AA); });
    }
  }
}

cv::Mat plaster(cv::RNG& rng, int n, cv::Vec3b base) {
  cv::Mat img(n, n, CV_8UC3, cv::Scalar(base[0], base[1], base[2]));
  add_noise(img, rng, {{4, 18.f}, {16, 10.f}, {64, 6.f}}, {1.f, 0.95f, 0.9f});
  scatter_shapes(img, rng, base, n / 4, n / 5, 70);
  add_noise(img, rng, {{n / 8, 6.f}, {n / 2, 5.f}}, {1.f, 1.f, 1.f});
  wrap_blur(img);
  return img;
}

// Emulsion paint on smooth plaster: a near-uniform colour with faint mottling (about 1.5 grey levels at a
// few centimetres to a metre) and a fainter fine grain; nothing a corner detector would call a corner.
cv::Mat paint(cv::RNG& rng, int n) {
  const cv::Vec3b base(200, 208, 214);
  cv::Mat img(n, n, CV_8UC3, cv::Scalar(base[0], base[1], base[2]));
  add_noise(img, rng, {{4, 1.5f}, {16, 1.0f}, {64, 0.7f}, {n / 2, 0.8f}}, {1.f, 1.f, 1.f});
  wrap_blur(img);
  return img;
}

cv::Mat concrete(cv::RNG& rng, int n) {
  const cv::Vec3b base(150, 155, 160);
  cv::Mat img(n, n, CV_8UC3, cv::Scalar(base[0], base[1], base[2]));
  add_noise(img, rng, {{8, 20.f}, {32, 12.f}, {128, 8.f}}, {1.f, 1.f, 1.f});
  for (int i = 0; i < n / 2; ++i) {  // pores
    const cv::Point p(rng.uniform(0, n), rng.uniform(0, n));
    const int r = rng.uniform(1, 6);
    const cv::Scalar c = jitter(rng, cv::Vec3b(80, 85, 90), 25);
    draw_wrapped(n, [&](cv::Point o) { cv::circle(img, p + o, r, c, cv::FILLED, cv::LINE_AA); });
  }
  // Formwork joints.
  for (int y = 0; y < n; y += n / 4) cv::line(img, {0, y}, {n, y}, cv::Scalar(95, 100, 105), 3);
  wrap_blur(img);
  return img;
}

cv::Mat wood(cv::RNG& rng, int n, cv::Vec3b base) {
  cv::Mat img(n, n, CV_8UC3, cv::Scalar(base[0], base[1], base[2]));
  add_noise(img, rng, {{2, 20.f}, {8, 14.f}, {64, 8.f}}, {0.7f, 0.9f, 1.f});
  // Grain: horizontal streaks.
  for (int i = 0; i < n / 3; ++i) {
    const int y = rng.uniform(0, n), x = rng.uniform(0, n), len = rng.uniform(n / 16, n / 3);
    const cv::Scalar c = jitter(rng, cv::Vec3b(base[0] / 2, base[1] / 2, base[2] / 2), 20);
    draw_wrapped(n, [&](cv::Point o) {
      cv::line(img, cv::Point(x, y) + o, cv::Point(x + len, y) + o, c, rng.uniform(1, 4));
    });
  }
  scatter_shapes(img, rng, base, n / 10, n / 6, 60);  // knots, stickers, scratches
  wrap_blur(img);
  return img;
}

cv::Mat floor_tiles(cv::RNG& rng, int n, double texels_per_metre) {
  cv::Mat img(n, n, CV_8UC3);
  const int tile = std::max(8, static_cast<int>(0.5 * texels_per_metre));
  const int tiles = std::max(1, n / tile);
  const int step = n / tiles;
  for (int ty = 0; ty < tiles; ++ty)
    for (int tx = 0; tx < tiles; ++tx) {
      const cv::Scalar c = jitter(rng, cv::Vec3b(120, 135, 150), 30);
      cv::rectangle(img, cv::Rect(tx * step, ty * step, step, step), c, cv::FILLED);
    }
  add_noise(img, rng, {{8, 10.f}, {32, 8.f}, {256, 10.f}}, {1.f, 1.f, 1.f});
  scatter_shapes(img, rng, cv::Vec3b(110, 125, 140), n / 6, step / 2, 60);
  for (int k = 0; k <= tiles; ++k) {  // grout
    cv::line(img, {k * step, 0}, {k * step, n}, cv::Scalar(60, 65, 70), 3);
    cv::line(img, {0, k * step}, {n, k * step}, cv::Scalar(60, 65, 70), 3);
  }
  wrap_blur(img);
  return img;
}

cv::Mat ceiling(cv::RNG& rng, int n, double texels_per_metre) {
  cv::Mat img(n, n, CV_8UC3, cv::Scalar(225, 228, 230));
  add_noise(img, rng, {{16, 6.f}, {128, 6.f}}, {1.f, 1.f, 1.f});
  for (int i = 0; i < n * 2; ++i) {  // acoustic tile pits
    const cv::Point p(rng.uniform(0, n), rng.uniform(0, n));
    cv::circle(img, p, rng.uniform(1, 4), jitter(rng, cv::Vec3b(170, 172, 175), 20), cv::FILLED, cv::LINE_AA);
  }
  const int cell = std::max(8, static_cast<int>(0.5 * texels_per_metre));
  const int cells = std::max(1, n / cell);
  const int step = n / cells;
  for (int cy = 0; cy < cells; ++cy)
    for (int cx = 0; cx < cells; ++cx)
      if ((cx % 4 == 1 && cy % 3 == 1) || rng.uniform(0, 12) == 0) {  // light panels
        cv::rectangle(img, cv::Rect(cx * step + 4, cy * step + 4, step - 8, step - 8),
                      cv::Scalar(252, 253, 255), cv::FILLED);
        cv::line(img, {cx * step + step / 2, cy * step + 4}, {cx * step + step / 2, cy * step + step - 4},
                 cv::Scalar(210, 212, 215), 2);
      }
  for (int k = 0; k <= cells; ++k) {  // suspended grid
    cv::line(img, {k * step, 0}, {k * step, n}, cv::Scalar(150, 150, 150), 2);
    cv::line(img, {0, k * step}, {n, k * step}, cv::Scalar(150, 150, 150), 2);
  }
  wrap_blur(img);
  return img;
}

cv::Mat cloth(cv::RNG& rng, int n) {
  cv::Mat img(n, n, CV_8UC3, cv::Scalar(200, 200, 200));
  const int stripe = std::max(4, n / 32);
  for (int y = 0; y < n; y += 2 * stripe)
    cv::rectangle(img, cv::Rect(0, y, n, stripe), cv::Scalar(120, 120, 120), cv::FILLED);
  add_noise(img, rng, {{8, 12.f}, {64, 10.f}}, {1.f, 1.f, 1.f});
  scatter_shapes(img, rng, cv::Vec3b(160, 160, 160), n / 8, n / 8, 80);
  return img;
}

cv::Mat poster(cv::RNG& rng, int w, int h) {
  const cv::Vec3b paper(rng.uniform(40, 256), rng.uniform(40, 256), rng.uniform(40, 256));
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(paper[0], paper[1], paper[2]));
  for (int i = 0; i < 12; ++i) {  // bold shapes
    const cv::Scalar c(rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 256));
    const cv::Point p(rng.uniform(0, w), rng.uniform(0, h * 2 / 3));
    const int s = rng.uniform(w / 10, w / 3);
    if (i % 3 == 0)
      cv::circle(img, p, s / 2, c, cv::FILLED, cv::LINE_AA);
    else if (i % 3 == 1)
      cv::rectangle(img, cv::Rect(p.x, p.y, s, s / 2), c, cv::FILLED);
    else {
      const cv::Point tri[3] = {p, p + cv::Point(s, 0), p + cv::Point(s / 2, -s)};
      cv::fillConvexPoly(img, tri, 3, c, cv::LINE_AA);
    }
  }
  for (int y = h * 3 / 4; y < h - 24; y += 14) {  // "text" lines
    int x = 20;
    while (x < w - 30) {
      const int word = rng.uniform(8, 40);
      cv::rectangle(img, cv::Rect(x, y, std::min(word, w - 20 - x), 7), cv::Scalar(30, 30, 30), cv::FILLED);
      x += word + 6;
    }
  }
  cv::rectangle(img, cv::Rect(0, 0, w, h), cv::Scalar(25, 25, 25), 10);  // frame
  cv::GaussianBlur(img, img, cv::Size(3, 3), 0.7);
  return img;
}

TexturePyramid pyramid(const cv::Mat& level0, bool periodic) {
  TexturePyramid p;
  p.levels.push_back(level0);
  while (p.levels.back().rows > 4 && p.levels.back().cols > 4) {
    const cv::Mat& prev = p.levels.back();
    cv::Mat next;
    if (periodic) {
      cv::Mat padded, down;
      cv::copyMakeBorder(prev, padded, 4, 4, 4, 4, cv::BORDER_WRAP);
      cv::pyrDown(padded, down);
      next = down(cv::Rect(2, 2, prev.cols / 2, prev.rows / 2)).clone();
    } else {
      cv::pyrDown(prev, next, cv::Size(prev.cols / 2, prev.rows / 2));
    }
    p.levels.push_back(next);
  }
  return p;
}

std::shared_ptr<const SceneTextures> build(std::uint32_t seed, int n, double tpm) {
  auto t = std::make_shared<SceneTextures>();
  t->texels_per_metre = tpm;
  t->materials.resize(kMaterialCount);
  auto rng_for = [seed](int what) {
    return cv::RNG(mix_hash(seed * 1000003ull + static_cast<std::uint64_t>(what)));
  };
  const cv::Vec3b wall_bases[kMaterialWallCount] = {
      {200, 210, 220}, {170, 200, 215}, {215, 205, 190}, {190, 215, 200}};
  for (int i = 0; i < kMaterialWallCount; ++i) {
    cv::RNG rng = rng_for(i);
    t->materials[kMaterialWall0 + i] = pyramid(plaster(rng, n, wall_bases[i]), true);
  }
  {
    cv::RNG rng = rng_for(kMaterialPillar);
    t->materials[kMaterialPillar] = pyramid(concrete(rng, n), true);
  }
  {
    cv::RNG rng = rng_for(kMaterialFurnitureSide);
    t->materials[kMaterialFurnitureSide] = pyramid(wood(rng, n, cv::Vec3b(60, 100, 150)), true);
  }
  {
    cv::RNG rng = rng_for(kMaterialFurnitureTop);
    t->materials[kMaterialFurnitureTop] = pyramid(wood(rng, n, cv::Vec3b(120, 160, 190)), true);
  }
  {
    cv::RNG rng = rng_for(kMaterialFloor);
    t->materials[kMaterialFloor] = pyramid(floor_tiles(rng, n, tpm), true);
  }
  {
    cv::RNG rng = rng_for(kMaterialCeiling);
    t->materials[kMaterialCeiling] = pyramid(ceiling(rng, n, tpm), true);
  }
  {
    cv::RNG rng = rng_for(kMaterialCloth);
    t->materials[kMaterialCloth] = pyramid(cloth(rng, std::min(n, 256)), true);
  }
  {
    cv::RNG rng = rng_for(kMaterialPaint);
    t->materials[kMaterialPaint] = pyramid(paint(rng, n), true);
  }
  for (int i = 0; i < 8; ++i) {
    cv::RNG rng = rng_for(100 + i);
    t->posters.push_back(pyramid(poster(rng, 256, 352), false));
  }
  return t;
}

}  // namespace

std::shared_ptr<const SceneTextures> make_scene_textures(std::uint32_t seed, int size,
                                                         double texels_per_metre) {
  static std::mutex mutex;
  static std::map<std::tuple<std::uint32_t, int, double>, std::shared_ptr<const SceneTextures>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{seed, size, texels_per_metre}];
  if (!slot) slot = build(seed, size, texels_per_metre);
  return slot;
}

}  // namespace plenopath
