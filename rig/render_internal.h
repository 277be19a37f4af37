#pragma once
// Internal to the synthetic camera (rig/synthetic_camera.h): what the scene builder, the ray caster, the
// shader, the people, the nuisances and the panorama loop share. Not for use outside rig/.
//
// The scene is 2.5-D, so a level panorama is rendered in two passes: one 2-D ray cast per column collects
// every vertical face the column's rays can meet (sorted by horizontal distance, up to the first full-height
// wall), then each pixel of the column walks that short list with its own slope to find the first face,
// floor, ceiling or furniture top (first_hit). A tilted camera's pixel rays do not share vertical planes:
// each pixel then intersects, exactly, the faces met by the two cast columns bracketing its own horizontal
// direction (cast_from_candidates).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

#include "rig/scene_textures.h"
#include "rig/synthetic_camera.h"

namespace plenopath {

// Which faces each cell of a uniform grid over the floor rectangle touches (built by build_synthetic_scene).
struct SceneGrid {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell = 1.0;
  int nx = 0, ny = 0;
  std::vector<int> start;  // faces of cell c: faces[start[c] .. start[c + 1])
  std::vector<int> faces;
};

namespace render_detail {

constexpr double kPi = M_PI;

inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}
bool point_in_polygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p);
inline bool is_full_height(SurfaceKind k) { return k == SurfaceKind::kWall || k == SurfaceKind::kPillar; }

// ---- people (scene_people.cpp)
struct PersonNow {
  PersonPose pose;
  cv::Vec3f shirt, trousers;
};
std::vector<PersonNow> people_now(const SyntheticScene& scene, const RenderOptions& o, int frame_index);

// ---- the per-column ray cast (ray_casting.cpp)
struct Crossing {
  double d;             // horizontal distance from the origin, metres
  double u;             // texture coordinate along the surface, metres
  float top;            // height of the face's top
  float cos_incidence;  // |normal . horizontal ray direction|
  float spread;         // 1 / sqrt(cos_incidence), clamped: how much wider a pixel's footprint is on the face
  int face;             // index into scene.faces, or -1 - person
  int footprint;  // footprint toggled by crossing this face (furniture: index; person: nfoot + p), -1 none
  SurfaceKind kind;
};

struct ColumnRay {
  Eigen::Vector2d origin, dir;
  std::vector<Crossing> crossings;
  double d_exit = 0.0;  // where the ray leaves the floor rectangle
};

// What a frame needs besides the scene.
struct FrameContext {
  const SyntheticScene* scene = nullptr;
  std::vector<PersonNow> people;
  std::vector<float> footprint_tops;  // furniture footprints, then people
  int start_footprint = -1;           // footprint containing the origin
  double cam_z = 1.6;
  Eigen::Vector2d origin;
  float gain = 1.0f;  // exposure (capture_nuisances.cpp)
};

FrameContext make_context(const SyntheticScene& scene, const RenderOptions& o, const Eigen::Vector3d& origin,
                          int frame_index);

// Faces already tested for the current ray (a face spans several cells).
struct FaceStamps {
  std::vector<std::uint32_t> stamp;
  std::uint32_t current = 0;
  bool first_visit(int face) {
    if (stamp[face] == current) return false;
    stamp[face] = current;
    return true;
  }
  void next_ray(std::size_t faces) {
    if (stamp.size() != faces) stamp.assign(faces, 0);
    if (++current == 0) {
      std::fill(stamp.begin(), stamp.end(), 0);
      current = 1;
    }
  }
};

// Casts the horizontal ray from ctx.origin along the unit `dir`.
void cast_column(const FrameContext& ctx, const Eigen::Vector2d& dir, ColumnRay& ray, FaceStamps& stamps);
// The same ray, but testing only the faces listed in `candidates` (indices into scene.faces; repeats are
// allowed) and the people: exact for every face a candidate list of a neighbouring direction contains.
void cast_from_candidates(const FrameContext& ctx, const Eigen::Vector2d& dir,
                          const std::vector<int>& candidates, ColumnRay& ray);

// What every ray of one panorama row (one elevation) shares.
struct RayRow {
  double s = 0.0;      // tan(elevation): height gained per horizontal metre
  double inv_s = 0.0;  // 1 / s (0 when s == 0)
  double cos_e = 1.0, sin_e = 0.0, sec_e = 1.0;
  double floor_spread = 1.0;  // 1 / sqrt(|sin e|), clamped: footprint growth on horizontal surfaces
  double wall_spread = 1.0;   // 1 / sqrt(cos e), clamped: footprint growth on vertical surfaces
  explicit RayRow(double slope, double cos_elevation, double sin_elevation)
      : s(slope),
        inv_s(slope != 0.0 ? 1.0 / slope : 0.0),
        cos_e(cos_elevation),
        sin_e(sin_elevation),
        sec_e(1.0 / std::max(cos_elevation, 1e-300)),
        floor_spread(1.0 / std::sqrt(std::max(std::abs(sin_elevation), 0.02))),
        wall_spread(1.0 / std::sqrt(std::max(cos_elevation, 0.02))) {}
};

struct Hit {
  double d = 0.0;  // horizontal distance
  SurfaceKind kind = SurfaceKind::kNone;
  const Crossing* crossing = nullptr;  // for vertical faces
  int footprint = -1;                  // for tops
};

// The first surface met by the ray of slope s (= tan elevation) along the column.
[[gnu::always_inline]] inline Hit first_hit(const FrameContext& ctx, const ColumnRay& ray,
                                            const RayRow& row) {
  const double s = row.s;
  const double cam_z = ctx.cam_z;
  const double ceiling_z = ctx.scene->options.wall_height;
  int inside = ctx.start_footprint;
  auto horizontal = [&](double limit, Hit& hit) {
    if (s < 0) {
      const double level = inside >= 0 ? ctx.footprint_tops[inside] : 0.0;
      const double dh = (level - cam_z) * row.inv_s;
      if (dh < limit) {
        hit.d = dh;
        hit.footprint = inside;
        hit.kind = inside >= 0
                       ? (inside < static_cast<int>(ctx.scene->footprints.size()) ? SurfaceKind::kFurnitureTop
                                                                                  : SurfaceKind::kPerson)
                       : SurfaceKind::kFloor;
        return true;
      }
    } else if (s > 0) {
      const double dc = (ceiling_z - cam_z) * row.inv_s;
      if (dc < limit) {
        hit.d = dc;
        hit.kind = SurfaceKind::kCeiling;
        return true;
      }
    }
    return false;
  };
  Hit hit;
  for (const Crossing& c : ray.crossings) {
    if (horizontal(c.d, hit)) {
      if ((hit.kind == SurfaceKind::kFloor || hit.kind == SurfaceKind::kCeiling) && hit.d > ray.d_exit)
        return Hit{};
      return hit;
    }
    const double z = cam_z + s * c.d;
    if (is_full_height(c.kind) || (z >= 0.0 && z <= c.top)) {
      hit.d = c.d;
      hit.kind = c.kind;
      hit.crossing = &c;
      return hit;
    }
    if (c.footprint >= 0) inside = inside == c.footprint ? -1 : c.footprint;
  }
  if (inside >= 0) {  // still above a top: it must be met before infinity
    if (horizontal(std::numeric_limits<double>::infinity(), hit)) return hit;
    return Hit{};
  }
  if (horizontal(ray.d_exit, hit)) return hit;
  return Hit{};
}

// A ray straight up or down (no horizontal direction): the floor, a top or the ceiling above the origin.
// Fills `ray` with an empty column and returns the hit and its distance along the ray.
Hit vertical_hit(const FrameContext& ctx, bool down, ColumnRay& ray, double* distance);

// ---- texturing (surface_shading.cpp)
// std::log2 of the last argument again: every floor (or ceiling) pixel of a level panorama row has the same
// distance, so the same texture footprint, and the logarithm that picks its mip levels was a tenth of the
// render. One per thread; the results are those of std::log2.
struct Log2Memo {
  double argument = std::numeric_limits<double>::quiet_NaN();
  double value = 0.0;
  double operator()(double x) {
    if (!(x == argument)) {
      argument = x;
      value = std::log2(x);
    }
    return value;
  }
};
// Colour of a hit, exposure gain included. pixel_angle: the angular size of a pixel (radians), for mip
// selection; distance: along the 3-D ray. `memo` (optional) remembers the last horizontal surface's mip
// level.
cv::Vec3b shade(const FrameContext& ctx, const ColumnRay& ray, const Hit& hit, const RayRow& row,
                double distance, double pixel_angle, Log2Memo* memo = nullptr);
// Trilinear sample of a pyramid at level-0 texel coordinates with a footprint of `footprint` texels.
cv::Vec3f sample_texture(const TexturePyramid& t, double x, double y, double footprint, bool periodic);
inline cv::Vec3b to_bgr(const cv::Vec3f& c) {
  return {cv::saturate_cast<uchar>(c[0]), cv::saturate_cast<uchar>(c[1]), cv::saturate_cast<uchar>(c[2])};
}

// ---- nuisances (capture_nuisances.cpp)
void add_noise(cv::Mat& rgb, const RenderOptions& o, int frame_index);

// ---- the operator and the trolley (trolley_rig.cpp)
// Simple solids fixed to the camera (the trolley: frame, mast, handle) or to its level, heading-aligned
// frame (the operator standing behind it), in metres, camera frame axes (+x forward, +y left, +z up) with
// the lens at the origin.
struct RigSolid {
  enum Shape : std::uint8_t { kCapsule, kBox } shape = kCapsule;
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();  // capsule axis, or box corners
  double radius = 0.0;                                                       // capsule
  bool level = false;  // true: in the level frame (moves with the heading, not the tilt)
  SurfaceKind kind = SurfaceKind::kTrolley;
  cv::Vec3f colour{1, 1, 1};  // multiplies the texture (or a grey of 128 when material < 0)
  int material = -1;          // TextureMaterial, or -1 for plain
  // Bounding sphere, for a quick rejection.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double bound = 0.0;
};
std::vector<RigSolid> rig_solids(const RenderOptions& o, double camera_height);

struct RigHit {
  double distance = 0.0;  // along the unit ray, 0 = none
  SurfaceKind kind = SurfaceKind::kNone;
  cv::Vec3f colour;  // before the exposure gain
};
// The nearest solid along the unit camera-frame bearing `b_camera` (and the same ray in the level frame,
// `b_level`, for solids that do not tilt with the camera).
RigHit hit_rig(const std::vector<RigSolid>& solids, const SceneTextures& textures,
               const Eigen::Vector3d& b_camera, const Eigen::Vector3d& b_level, double pixel_angle);

}  // namespace render_detail
}  // namespace plenopath
