// Texturing of the synthetic camera: band-limited (trilinear mip) samples of the procedural textures at a
// hit, the posters on the walls, the people's clothes, a little lighting, and the exposure gain.
#include <emmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "rig/render_internal.h"
#include "rig/scene_textures.h"

namespace plenopath::render_detail {
namespace {

// The samplers work on four float lanes (B, G, R and a spare) with SSE2, which every x86-64 has; each lane
// computes exactly what a scalar per-channel loop would (integer arithmetic, then float products and sums of
// float values without fused multiply-adds), so the pictures do not depend on the vector code.
inline long long fast_floor(double x) {
  const long long i = static_cast<long long>(x);
  return x < static_cast<double>(i) ? i - 1 : i;
}

// A texel's three bytes as the low 24 bits of a 4-byte load (the 4th byte is the next texel's or the next
// row's, and is never used).
inline __m128i load_texel(const uchar* p) {
  std::uint32_t v;
  std::memcpy(&v, p, sizeof v);
  return _mm_cvtsi32_si128(static_cast<int>(v));
}
// The same in an image's last row, whose last texel is loaded from one byte earlier and shifted down, so
// that no load reaches past the image.
inline __m128i load_texel_in_last_row(const uchar* row, int x, int last) {
  const int back = x == last ? 1 : 0;
  std::uint32_t v;
  std::memcpy(&v, row + 3 * x - back, sizeof v);
  return _mm_cvtsi32_si128(static_cast<int>(v >> (8 * back)));
}

// The texel coordinates x and y shifted by half a texel, split into integer parts (floors) and 8-bit
// fractions: both at once in double lanes while they fit an int comfortably, otherwise (far off, or NaN)
// one by one in 64 bits. Both ways give the same numbers.
struct TexelSplit {
  long long xf, yf;
  int ax, ay;
};
[[gnu::always_inline]] inline TexelSplit split_texel_coordinates(double x, double y) {
  const __m128d v = _mm_sub_pd(_mm_set_pd(y, x), _mm_set1_pd(0.5));
  const __m128d magnitude = _mm_andnot_pd(_mm_set1_pd(-0.0), v);
  if (_mm_movemask_pd(_mm_cmplt_pd(magnitude, _mm_set1_pd(1073741824.0))) == 3) {
    const __m128d truncated = _mm_cvtepi32_pd(_mm_cvttpd_epi32(v));
    const __m128d floor = _mm_add_pd(truncated, _mm_and_pd(_mm_cmplt_pd(v, truncated), _mm_set1_pd(-1.0)));
    const __m128i whole = _mm_cvttpd_epi32(floor);
    const __m128i fraction = _mm_cvttpd_epi32(_mm_mul_pd(_mm_sub_pd(v, floor), _mm_set1_pd(256.0)));
    return {_mm_cvtsi128_si32(whole), _mm_cvtsi128_si32(_mm_srli_si128(whole, 4)),
            _mm_cvtsi128_si32(fraction), _mm_cvtsi128_si32(_mm_srli_si128(fraction, 4))};
  }
  x = std::clamp(x, -1e15, 1e15) - 0.5;
  y = std::clamp(y, -1e15, 1e15) - 0.5;
  const long long xf = fast_floor(x), yf = fast_floor(y);
  return {xf, yf, static_cast<int>((x - static_cast<double>(xf)) * 256.0),
          static_cast<int>((y - static_cast<double>(yf)) * 256.0)};
}

template <bool periodic>
[[gnu::always_inline]] inline __m128 sample_bilinear(const cv::Mat& img, double x, double y) {
  const auto [xf, yf, ax, ay] = split_texel_coordinates(x, y);
  const int w = img.cols, h = img.rows;
  int x0, y0, x1, y1;
  if constexpr (periodic) {  // power-of-two sizes
    x0 = static_cast<int>(xf & (w - 1));
    x1 = static_cast<int>((xf + 1) & (w - 1));
    y0 = static_cast<int>(yf & (h - 1));
    y1 = static_cast<int>((yf + 1) & (h - 1));
  } else {
    x0 = static_cast<int>(std::clamp<long long>(xf, 0, w - 1));
    x1 = static_cast<int>(std::clamp<long long>(xf + 1, 0, w - 1));
    y0 = static_cast<int>(std::clamp<long long>(yf, 0, h - 1));
    y1 = static_cast<int>(std::clamp<long long>(yf + 1, 0, h - 1));
  }
  const uchar* r0 = img.data + static_cast<std::size_t>(y0) * img.step[0];
  const uchar* r1 = img.data + static_cast<std::size_t>(y1) * img.step[0];
  const __m128i zero = _mm_setzero_si128();
  // 16-bit lanes p0[k], p1[k] side by side; the weights (256 - ax, ax) in each pair.
  const __m128i weights = _mm_set1_epi32(((ax << 16) | (256 - ax)));
  __m128i p00, p01, p10, p11;
  if (y0 != h - 1 && y1 != h - 1) {
    p00 = load_texel(r0 + 3 * x0);
    p01 = load_texel(r0 + 3 * x1);
    p10 = load_texel(r1 + 3 * x0);
    p11 = load_texel(r1 + 3 * x1);
  } else {
    p00 = load_texel_in_last_row(r0, x0, w - 1);
    p01 = load_texel_in_last_row(r0, x1, w - 1);
    p10 = load_texel_in_last_row(r1, x0, w - 1);
    p11 = load_texel_in_last_row(r1, x1, w - 1);
  }
  const __m128i top = _mm_madd_epi16(_mm_unpacklo_epi8(_mm_unpacklo_epi8(p00, p01), zero), weights);
  const __m128i bottom = _mm_madd_epi16(_mm_unpacklo_epi8(_mm_unpacklo_epi8(p10, p11), zero), weights);
  const __m128 sum = _mm_add_ps(_mm_mul_ps(_mm_cvtepi32_ps(top), _mm_set1_ps(static_cast<float>(256 - ay))),
                                _mm_mul_ps(_mm_cvtepi32_ps(bottom), _mm_set1_ps(static_cast<float>(ay))));
  return _mm_cvtepi32_ps(_mm_cvttps_epi32(_mm_mul_ps(sum, _mm_set1_ps(1.0f / 65536.0f))));  // >> 16
}

// Samples a pyramid at level-0 texel coordinates with a footprint of `footprint` level-0 texels per pixel,
// trilinearly: between the two levels whose texels bracket the footprint, blended by where the footprint
// lies between them. Picking one level per pixel would switch the texture's blur abruptly wherever the
// footprint crosses a power of two; as the camera moves that boundary sweeps over surfaces, and a feature
// tracker sees the corners inside it shift (tracks then drift by tenths of a pixel per frame).
// 2^-L, exactly (a division per sample was a tenth of the sampler's time).
struct LevelScales {
  double value[31];
  constexpr LevelScales() : value() {
    double v = 1.0;
    for (double& x : value) {
      x = v;
      v *= 0.5;
    }
  }
  constexpr double operator[](int level) const { return value[level]; }
};
constexpr LevelScales kLevelScale;

template <bool periodic>
[[gnu::always_inline]] inline __m128 sample_level(const TexturePyramid& t, int level, double x, double y) {
  // Level L's texel j is centred where level 0's texel 2^L j is (pyrDown centres each output texel on an
  // even input texel), i.e. at level-0 coordinate 2^L j + 0.5; scaling by 2^-L alone would shift the
  // texture by half a finer texel from one level to the next.
  const double scale = kLevelScale[level];
  return sample_bilinear<periodic>(t.levels[level], (x - 0.5) * scale + 0.5, (y - 0.5) * scale + 0.5);
}

template <bool periodic>
inline __m128 sample_pyramid(const TexturePyramid& t, double x, double y, double footprint,
                             Log2Memo* memo = nullptr) {
  const int top = static_cast<int>(t.levels.size()) - 1;
  if (!(footprint > 1.0)) return sample_level<periodic>(t, 0, x, y);
  const double lod = memo ? (*memo)(footprint) : std::log2(footprint);
  if (lod >= top) return sample_level<periodic>(t, top, x, y);
  const int level = static_cast<int>(lod);
  const float blend = static_cast<float>(lod - level);
  const __m128 fine = sample_level<periodic>(t, level, x, y);
  if (blend < 1.0f / 64) return fine;
  return _mm_add_ps(_mm_mul_ps(fine, _mm_set1_ps(1.0f - blend)),
                    _mm_mul_ps(sample_level<periodic>(t, level + 1, x, y), _mm_set1_ps(blend)));
}

inline __m128 vec(const cv::Vec3f& c) { return _mm_setr_ps(c[0], c[1], c[2], 0.0f); }

// saturate_cast<uchar> of each lane: round to nearest even (as cvRound), then clamp to [0, 255].
inline cv::Vec3b to_bgr(__m128 c) {
  const __m128i i = _mm_cvtps_epi32(c);
  const int packed = _mm_cvtsi128_si32(_mm_packus_epi16(_mm_packs_epi32(i, i), _mm_setzero_si128()));
  return {static_cast<uchar>(packed), static_cast<uchar>(packed >> 8), static_cast<uchar>(packed >> 16)};
}

}  // namespace

cv::Vec3f sample_texture(const TexturePyramid& t, double x, double y, double footprint, bool periodic) {
  alignas(16) float v[4];
  _mm_store_ps(
      v, periodic ? sample_pyramid<true>(t, x, y, footprint) : sample_pyramid<false>(t, x, y, footprint));
  return {v[0], v[1], v[2]};
}

namespace {
const cv::Vec3b kSky(235, 206, 160);

}  // namespace

// Colour of a hit. pixel_angle: the angular size of a pixel (radians), for mip selection; distance: along
// the 3-D ray; cos_e: cosine of the ray's elevation; sin_e: its sine.
cv::Vec3b shade(const FrameContext& ctx, const ColumnRay& ray, const Hit& hit, const RayRow& row,
                double distance, double pixel_angle, Log2Memo* memo) {
  const double s = row.s;
  const SyntheticScene& scene = *ctx.scene;
  const SceneTextures& tex = *scene.textures;
  const double tpm = tex.texels_per_metre;
  const double z = ctx.cam_z + s * hit.d;
  const double base_footprint = distance * pixel_angle * tpm;
  __m128 colour;
  switch (hit.kind) {
    case SurfaceKind::kNone:
      return kSky;
    case SurfaceKind::kFloor:
    case SurfaceKind::kCeiling:
    case SurfaceKind::kFurnitureTop: {
      const Eigen::Vector2d p = ray.origin + hit.d * ray.dir;
      const double footprint = base_footprint * row.floor_spread;
      if (hit.kind == SurfaceKind::kFurnitureTop) {
        const SceneFootprint& fp = scene.footprints[hit.footprint];
        const __m128 c =
            sample_pyramid<true>(tex.materials[kMaterialFurnitureTop], (p.x() + fp.texture_offset.x()) * tpm,
                                 -(p.y() + fp.texture_offset.y()) * tpm, footprint, memo);
        colour = _mm_mul_ps(_mm_mul_ps(c, vec(fp.tint)), _mm_set1_ps(0.97f));
      } else if (hit.kind == SurfaceKind::kFloor) {
        colour = _mm_mul_ps(
            sample_pyramid<true>(tex.materials[kMaterialFloor], p.x() * tpm, -p.y() * tpm, footprint, memo),
            _mm_set1_ps(0.9f));
      } else {
        colour =
            sample_pyramid<true>(tex.materials[kMaterialCeiling], p.x() * tpm, -p.y() * tpm, footprint, memo);
      }
      break;
    }
    case SurfaceKind::kPerson: {
      const PersonNow& person =
          ctx.people[hit.crossing ? -1 - hit.crossing->face
                                  : hit.footprint - static_cast<int>(scene.footprints.size())];
      if (!hit.crossing) {  // the top of the head
        colour = _mm_setr_ps(60, 70, 90, 0);
        break;
      }
      const double footprint = base_footprint * hit.crossing->spread * row.wall_spread;
      const __m128 c = sample_pyramid<true>(tex.materials[kMaterialCloth], hit.crossing->u * tpm,
                                            (2.0 - z) * tpm, footprint);
      if (z > 1.5)
        colour = _mm_add_ps(_mm_setr_ps(110, 140, 190, 0), _mm_mul_ps(c, _mm_set1_ps(0.2f)));  // face, hair
      else if (z > 0.85)
        colour = _mm_mul_ps(c, vec(person.shirt));
      else
        colour = _mm_mul_ps(c, vec(person.trousers));
      colour = _mm_mul_ps(colour, _mm_set1_ps(0.6f + 0.4f * hit.crossing->cos_incidence));
      break;
    }
    default: {  // walls, pillars, furniture sides
      const Crossing& c = *hit.crossing;
      const SceneFace& f = scene.faces[c.face];
      const double footprint = base_footprint * c.spread * row.wall_spread;
      for (int i = f.poster_begin; i < f.poster_end; ++i) {
        const ScenePoster& p = scene.posters[i];
        if (c.u >= p.u0 && c.u <= p.u1 && z >= p.z0 && z <= p.z1) {
          const TexturePyramid& img = tex.posters[p.image];
          const double px_per_m = img.levels[0].cols / (p.u1 - p.u0);
          colour = _mm_mul_ps(sample_pyramid<false>(img, (c.u - p.u0) * px_per_m,
                                                    (p.z1 - z) / (p.z1 - p.z0) * img.levels[0].rows,
                                                    footprint * px_per_m / tpm),
                              _mm_set1_ps(f.shade));
          return to_bgr(_mm_mul_ps(colour, _mm_set1_ps(ctx.gain)));
        }
      }
      const __m128 t =
          sample_pyramid<true>(tex.materials[f.material], c.u * tpm, (f.top - z) * tpm, footprint);
      // A little darker near the floor (a cheap stand-in for ambient occlusion).
      const float occlusion = static_cast<float>(std::min(1.0, 0.8 + z));
      colour = _mm_mul_ps(_mm_mul_ps(t, vec(f.tint)), _mm_set1_ps(f.shade * occlusion));
      break;
    }
  }
  return to_bgr(_mm_mul_ps(colour, _mm_set1_ps(ctx.gain)));
}

}  // namespace plenopath::render_detail
