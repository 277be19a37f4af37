// Texturing of the synthetic camera: band-limited (trilinear mip) samples of the procedural textures at a
// hit, the posters on the walls, the people's clothes, a little lighting, and the exposure gain.
#include <algorithm>
#include <cmath>

#include "rig/render_internal.h"
#include "rig/scene_textures.h"

namespace plenopath::render_detail {
namespace {

// Bilinear sample at continuous texel coordinates of one level (texel (i, j) has its centre at
// (i + 0.5, j + 0.5)), in fixed point: 8-bit weights.
inline long long fast_floor(double x) {
  const long long i = static_cast<long long>(x);
  return x < static_cast<double>(i) ? i - 1 : i;
}

inline cv::Vec3f sample_bilinear(const cv::Mat& img, double x, double y, bool periodic) {
  x = std::clamp(x, -1e15, 1e15) - 0.5;
  y = std::clamp(y, -1e15, 1e15) - 0.5;
  const long long xf = fast_floor(x), yf = fast_floor(y);
  const int ax = static_cast<int>((x - static_cast<double>(xf)) * 256.0);
  const int ay = static_cast<int>((y - static_cast<double>(yf)) * 256.0);
  const int w = img.cols, h = img.rows;
  int x0, y0, x1, y1;
  if (periodic) {  // power-of-two sizes
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
  const uchar* p00 = r0 + 3 * x0;
  const uchar* p01 = r0 + 3 * x1;
  const uchar* p10 = r1 + 3 * x0;
  const uchar* p11 = r1 + 3 * x1;
  const int bx = 256 - ax, by = 256 - ay;
  cv::Vec3f out;
  for (int k = 0; k < 3; ++k) {
    const int top = p00[k] * bx + p01[k] * ax;
    const int bottom = p10[k] * bx + p11[k] * ax;
    out[k] = static_cast<float>((top * by + bottom * ay) >> 16);
  }
  return out;
}

// Samples a pyramid at level-0 texel coordinates with a footprint of `footprint` level-0 texels per pixel,
// trilinearly: between the two levels whose texels bracket the footprint, blended by where the footprint
// lies between them. Picking one level per pixel would switch the texture's blur abruptly wherever the
// footprint crosses a power of two; as the camera moves that boundary sweeps over surfaces, and a feature
// tracker sees the corners inside it shift (tracks then drift by tenths of a pixel per frame).
inline cv::Vec3f sample_level(const TexturePyramid& t, int level, double x, double y, bool periodic) {
  // Level L's texel j is centred where level 0's texel 2^L j is (pyrDown centres each output texel on an
  // even input texel), i.e. at level-0 coordinate 2^L j + 0.5; scaling by 2^-L alone would shift the
  // texture by half a finer texel from one level to the next.
  const double scale = 1.0 / static_cast<double>(1 << level);
  return sample_bilinear(t.levels[level], (x - 0.5) * scale + 0.5, (y - 0.5) * scale + 0.5, periodic);
}

}  // namespace

cv::Vec3f sample_texture(const TexturePyramid& t, double x, double y, double footprint, bool periodic) {
  const int top = static_cast<int>(t.levels.size()) - 1;
  if (!(footprint > 1.0)) return sample_level(t, 0, x, y, periodic);
  const double lod = std::log2(footprint);
  if (lod >= top) return sample_level(t, top, x, y, periodic);
  const int level = static_cast<int>(lod);
  const float blend = static_cast<float>(lod - level);
  const cv::Vec3f fine = sample_level(t, level, x, y, periodic);
  if (blend < 1.0f / 64) return fine;
  return fine * (1.0f - blend) + sample_level(t, level + 1, x, y, periodic) * blend;
}

namespace {
const cv::Vec3b kSky(235, 206, 160);

}  // namespace

// Colour of a hit. pixel_angle: the angular size of a pixel (radians), for mip selection; distance: along
// the 3-D ray; cos_e: cosine of the ray's elevation; sin_e: its sine.
cv::Vec3b shade(const FrameContext& ctx, const ColumnRay& ray, const Hit& hit, const RayRow& row,
                double distance, double pixel_angle) {
  const double s = row.s;
  const SyntheticScene& scene = *ctx.scene;
  const SceneTextures& tex = *scene.textures;
  const double tpm = tex.texels_per_metre;
  const double z = ctx.cam_z + s * hit.d;
  const double base_footprint = distance * pixel_angle * tpm;
  cv::Vec3f colour;
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
        const cv::Vec3f c =
            sample_texture(tex.materials[kMaterialFurnitureTop], (p.x() + fp.texture_offset.x()) * tpm,
                           -(p.y() + fp.texture_offset.y()) * tpm, footprint, true);
        colour = c.mul(fp.tint) * 0.97f;
      } else if (hit.kind == SurfaceKind::kFloor) {
        colour =
            sample_texture(tex.materials[kMaterialFloor], p.x() * tpm, -p.y() * tpm, footprint, true) * 0.9f;
      } else {
        colour = sample_texture(tex.materials[kMaterialCeiling], p.x() * tpm, -p.y() * tpm, footprint, true);
      }
      break;
    }
    case SurfaceKind::kPerson: {
      const PersonNow& person =
          ctx.people[hit.crossing ? -1 - hit.crossing->face
                                  : hit.footprint - static_cast<int>(scene.footprints.size())];
      if (!hit.crossing) {  // the top of the head
        colour = cv::Vec3f(60, 70, 90);
        break;
      }
      const double footprint = base_footprint * hit.crossing->spread * row.wall_spread;
      const cv::Vec3f c = sample_texture(tex.materials[kMaterialCloth], hit.crossing->u * tpm,
                                         (2.0 - z) * tpm, footprint, true);
      if (z > 1.5)
        colour = cv::Vec3f(110, 140, 190) + 0.2f * c;  // face and hair
      else if (z > 0.85)
        colour = c.mul(person.shirt);
      else
        colour = c.mul(person.trousers);
      colour *= 0.6f + 0.4f * hit.crossing->cos_incidence;
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
          colour =
              sample_texture(img, (c.u - p.u0) * px_per_m, (p.z1 - z) / (p.z1 - p.z0) * img.levels[0].rows,
                             footprint * px_per_m / tpm, false) *
              f.shade;
          return to_bgr(colour * ctx.gain);
        }
      }
      const cv::Vec3f t =
          sample_texture(tex.materials[f.material], c.u * tpm, (f.top - z) * tpm, footprint, true);
      // A little darker near the floor (a cheap stand-in for ambient occlusion).
      const float occlusion = static_cast<float>(std::min(1.0, 0.8 + z));
      colour = t.mul(f.tint) * (f.shade * occlusion);
      break;
    }
  }
  return to_bgr(colour * ctx.gain);
}

}  // namespace plenopath::render_detail
