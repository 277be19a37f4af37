// The synthetic surround camera. The scene is 2.5-D, so a panorama is rendered in two passes: one 2-D ray
// cast per column collects every vertical face the column's rays can meet (sorted by horizontal distance,
// up to the first full-height wall), then each pixel of the column walks that short list with its own slope
// to find the first face, floor, ceiling or furniture top. Both passes run in parallel.
#include "rig/synthetic_camera.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <opencv2/core/utility.hpp>
#include <set>

#include "model/error.h"
#include "rig/scene_textures.h"

namespace plenopath {
namespace {

constexpr double kPi = M_PI;

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
  return s;
}
bool contains_any(const std::string& name, std::initializer_list<const char*> words) {
  const std::string u = upper(name);
  for (const char* w : words)
    if (u.find(w) != std::string::npos) return true;
  return false;
}
bool listed(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

bool point_in_polygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

bool is_full_height(SurfaceKind k) { return k == SurfaceKind::kWall || k == SurfaceKind::kPillar; }

// ---- people
struct PersonTrack {
  Eigen::Vector2d a, b;
  double speed = 1.2;  // m/s
  double phase = 0.0;  // metres along the back-and-forth walk at t = 0
  cv::Vec3f shirt, trousers;
};

bool segment_blocked(const SyntheticScene& scene, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                     double clearance) {
  for (const auto& f : scene.faces) {
    // Distance between segments pq and ab is small, or they cross.
    const Eigen::Vector2d e = f.b - f.a, d = q - p;
    const double denom = cross(d, e);
    if (std::abs(denom) > 1e-12) {
      const double t = cross(f.a - p, e) / denom, s = cross(f.a - p, d) / denom;
      if (t >= 0 && t <= 1 && s >= 0 && s <= 1) return true;
    }
    auto point_segment = [](const Eigen::Vector2d& x, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      const Eigen::Vector2d ab = b - a;
      const double l2 = ab.squaredNorm();
      const double t = l2 > 0 ? std::clamp((x - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
      return (x - (a + t * ab)).norm();
    };
    if (point_segment(p, f.a, f.b) < clearance || point_segment(q, f.a, f.b) < clearance ||
        point_segment(f.a, p, q) < clearance || point_segment(f.b, p, q) < clearance)
      return true;
  }
  for (const auto& fp : scene.footprints)
    if (point_in_polygon(fp.points, p) || point_in_polygon(fp.points, q)) return true;
  return false;
}

std::vector<PersonTrack> people_tracks(const SyntheticScene& scene, int count, std::uint32_t seed) {
  std::vector<PersonTrack> tracks;
  for (int i = 0; i < count; ++i) {
    cv::RNG rng(mix_hash(0x5eed00ull + seed * 7919ull + static_cast<std::uint64_t>(i)));
    PersonTrack t;
    bool found = false;
    for (int attempt = 0; attempt < 500 && !found; ++attempt) {
      t.a = {rng.uniform(scene.floor_min.x(), scene.floor_max.x()),
             rng.uniform(scene.floor_min.y(), scene.floor_max.y())};
      const double angle = rng.uniform(0.0, 2 * kPi), length = rng.uniform(2.0, 7.0);
      t.b = t.a + length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      found = !segment_blocked(scene, t.a, t.b, 0.4);
    }
    if (!found) continue;  // a plan too cramped for walkers
    t.speed = rng.uniform(0.8, 1.5);
    t.phase = rng.uniform(0.0, 20.0);
    t.shirt = cv::Vec3f(rng.uniform(0.3f, 1.3f), rng.uniform(0.3f, 1.3f), rng.uniform(0.3f, 1.3f));
    t.trousers = cv::Vec3f(rng.uniform(0.2f, 0.6f), rng.uniform(0.2f, 0.6f), rng.uniform(0.2f, 0.6f));
    tracks.push_back(t);
  }
  return tracks;
}

struct PersonNow {
  PersonPose pose;
  cv::Vec3f shirt, trousers;
};

std::vector<PersonNow> people_now(const SyntheticScene& scene, const RenderOptions& o, int frame_index) {
  std::vector<PersonNow> out;
  if (o.people <= 0) return out;
  const double time = frame_index / o.frame_rate;
  const auto tracks = people_tracks(scene, o.people, o.people_seed);
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const auto& t = tracks[i];
    const double len = (t.b - t.a).norm();
    double s = std::fmod(t.phase + t.speed * time, 2 * len);
    if (s > len) s = 2 * len - s;  // back and forth
    PersonNow p;
    p.pose.centre = t.a + (t.b - t.a) * (s / len);
    p.pose.id = static_cast<int>(i);
    p.shirt = t.shirt;
    p.trousers = t.trousers;
    out.push_back(p);
  }
  return out;
}

// ---- the per-column ray cast
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
  float gain = 1.0f;
};

FrameContext make_context(const SyntheticScene& scene, const RenderOptions& o, const Eigen::Vector3d& origin,
                          int frame_index) {
  FrameContext c;
  c.scene = &scene;
  c.origin = origin.head<2>();
  c.cam_z = origin.z();
  for (const auto& p : people_now(scene, o, frame_index))  // nobody stands inside the camera
    if ((p.pose.centre - c.origin).norm() > p.pose.radius + 0.05) c.people.push_back(p);
  for (const auto& fp : scene.footprints) c.footprint_tops.push_back(static_cast<float>(fp.top));
  for (const auto& p : c.people) c.footprint_tops.push_back(static_cast<float>(p.pose.height));
  for (std::size_t i = 0; i < scene.footprints.size(); ++i)
    if (point_in_polygon(scene.footprints[i].points, c.origin)) c.start_footprint = static_cast<int>(i);
  c.gain = static_cast<float>(1.0 + o.exposure_drift *
                                        std::sin(2 * kPi * frame_index / o.exposure_period_frames + 0.7));
  return c;
}

}  // namespace

// Which faces each cell of a uniform grid over the floor rectangle touches.
struct SceneGrid {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell = 1.0;
  int nx = 0, ny = 0;
  std::vector<int> start;  // faces of cell c: faces[start[c] .. start[c + 1])
  std::vector<int> faces;
};

namespace {

// Does segment ab touch the rectangle [lo, hi]? (Liang-Barsky clipping.)
bool segment_touches_box(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& lo,
                         const Eigen::Vector2d& hi) {
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

std::shared_ptr<const SceneGrid> build_grid(const SyntheticScene& scene) {
  auto grid = std::make_shared<SceneGrid>();
  const Eigen::Vector2d size = scene.floor_max - scene.floor_min;
  const double area = std::max(size.x() * size.y(), 1e-6);
  grid->cell = std::clamp(std::sqrt(area / static_cast<double>(scene.faces.size())), 0.2, 10.0);
  grid->cell = std::max(grid->cell, std::sqrt(area / 4e6));  // at most ~4 million cells
  grid->origin = scene.floor_min;
  grid->nx = std::max(1, static_cast<int>(std::ceil(size.x() / grid->cell)));
  grid->ny = std::max(1, static_cast<int>(std::ceil(size.y() / grid->cell)));
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(grid->nx) * grid->ny);
  const double eps = 1e-9 * (1.0 + size.norm());
  for (std::size_t i = 0; i < scene.faces.size(); ++i) {
    const SceneFace& f = scene.faces[i];
    const Eigen::Vector2d lo = f.a.cwiseMin(f.b), hi = f.a.cwiseMax(f.b);
    const int x0 = std::clamp(static_cast<int>(std::floor((lo.x() - eps - grid->origin.x()) / grid->cell)), 0,
                              grid->nx - 1);
    const int x1 = std::clamp(static_cast<int>(std::floor((hi.x() + eps - grid->origin.x()) / grid->cell)), 0,
                              grid->nx - 1);
    const int y0 = std::clamp(static_cast<int>(std::floor((lo.y() - eps - grid->origin.y()) / grid->cell)), 0,
                              grid->ny - 1);
    const int y1 = std::clamp(static_cast<int>(std::floor((hi.y() + eps - grid->origin.y()) / grid->cell)), 0,
                              grid->ny - 1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d clo =
            grid->origin + grid->cell * Eigen::Vector2d(x, y) - Eigen::Vector2d::Constant(eps);
        const Eigen::Vector2d chi = clo + Eigen::Vector2d::Constant(grid->cell + 2 * eps);
        if (segment_touches_box(f.a, f.b, clo, chi))
          cells[static_cast<std::size_t>(y) * grid->nx + x].push_back(static_cast<int>(i));
      }
  }
  grid->start.reserve(cells.size() + 1);
  for (const auto& c : cells) {
    grid->start.push_back(static_cast<int>(grid->faces.size()));
    grid->faces.insert(grid->faces.end(), c.begin(), c.end());
  }
  grid->start.push_back(static_cast<int>(grid->faces.size()));
  return grid;
}

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

void cast_column(const FrameContext& ctx, const Eigen::Vector2d& dir, ColumnRay& ray, FaceStamps& stamps) {
  const SyntheticScene& scene = *ctx.scene;
  ray.origin = ctx.origin;
  ray.dir = dir;
  ray.crossings.clear();
  // Exit from the floor rectangle (slabs).
  double exit = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    if (dir[k] > 0)
      exit = std::min(exit, (scene.floor_max[k] - ctx.origin[k]) / dir[k]);
    else if (dir[k] < 0)
      exit = std::min(exit, (scene.floor_min[k] - ctx.origin[k]) / dir[k]);
  }
  ray.d_exit = std::max(0.0, exit);
  double nearest_wall = std::numeric_limits<double>::infinity();
  auto test_face = [&](int i) {
    const SceneFace& f = scene.faces[i];
    const Eigen::Vector2d e = f.b - f.a;
    const double denom = cross(dir, e);
    if (denom == 0.0) return;
    const Eigen::Vector2d w = f.a - ctx.origin;
    const double t = cross(w, e) / denom;
    if (!(t > 0.0)) return;
    const double s = cross(w, dir) / denom;
    if (s < 0.0 || s > 1.0) return;
    const double len = e.norm();
    const float incidence = static_cast<float>(std::abs(denom) / len);
    ray.crossings.push_back({t, s * len + f.u_offset, static_cast<float>(f.top), incidence,
                             1.0f / std::sqrt(std::max(incidence, 0.02f)), i, f.footprint, f.kind});
    if (is_full_height(f.kind)) nearest_wall = std::min(nearest_wall, t);
  };
  const SceneGrid* grid = scene.grid.get();
  const bool inside_grid = grid && ctx.origin.x() >= grid->origin.x() && ctx.origin.y() >= grid->origin.y() &&
                           ctx.origin.x() < grid->origin.x() + grid->nx * grid->cell &&
                           ctx.origin.y() < grid->origin.y() + grid->ny * grid->cell;
  if (!inside_grid) {
    for (std::size_t i = 0; i < scene.faces.size(); ++i) test_face(static_cast<int>(i));
  } else {
    // Walk the cells along the ray (Amanatides & Woo) until a full-height face is met within a visited cell.
    stamps.next_ray(scene.faces.size());
    int ix = std::min(grid->nx - 1, static_cast<int>((ctx.origin.x() - grid->origin.x()) / grid->cell));
    int iy = std::min(grid->ny - 1, static_cast<int>((ctx.origin.y() - grid->origin.y()) / grid->cell));
    const int step_x = dir.x() > 0 ? 1 : (dir.x() < 0 ? -1 : 0);
    const int step_y = dir.y() > 0 ? 1 : (dir.y() < 0 ? -1 : 0);
    const double inf = std::numeric_limits<double>::infinity();
    double t_max_x =
        step_x ? (grid->origin.x() + (ix + (step_x > 0)) * grid->cell - ctx.origin.x()) / dir.x() : inf;
    double t_max_y =
        step_y ? (grid->origin.y() + (iy + (step_y > 0)) * grid->cell - ctx.origin.y()) / dir.y() : inf;
    const double t_delta_x = step_x ? grid->cell / std::abs(dir.x()) : inf;
    const double t_delta_y = step_y ? grid->cell / std::abs(dir.y()) : inf;
    while (true) {
      const int c = iy * grid->nx + ix;
      for (int k = grid->start[c]; k < grid->start[c + 1]; ++k)
        if (stamps.first_visit(grid->faces[k])) test_face(grid->faces[k]);
      const double t_exit = std::min(t_max_x, t_max_y);
      if (nearest_wall <= t_exit * (1 + 1e-12) + 1e-12) break;
      if (t_max_x < t_max_y) {
        ix += step_x;
        t_max_x += t_delta_x;
      } else {
        iy += step_y;
        t_max_y += t_delta_y;
      }
      if (ix < 0 || iy < 0 || ix >= grid->nx || iy >= grid->ny) break;
    }
  }
  const int nfoot = static_cast<int>(ctx.scene->footprints.size());
  for (std::size_t p = 0; p < ctx.people.size(); ++p) {
    const PersonPose& person = ctx.people[p].pose;
    const Eigen::Vector2d oc = ctx.origin - person.centre;
    const double b = oc.dot(dir), c = oc.squaredNorm() - person.radius * person.radius;
    const double disc = b * b - c;
    if (disc <= 0) continue;
    const double root = std::sqrt(disc);
    const double t1 = -b - root, t2 = -b + root;
    if (t2 <= 0) continue;
    auto around = [&](double t) {
      const Eigen::Vector2d q = ctx.origin + t * dir - person.centre;
      return (std::atan2(q.y(), q.x()) + kPi) * person.radius;
    };
    const int id = -1 - static_cast<int>(p);
    const float incidence = static_cast<float>(root / person.radius);
    const float spread = 1.0f / std::sqrt(std::max(incidence, 0.02f));
    if (t1 > 0)
      ray.crossings.push_back({t1, around(t1), static_cast<float>(person.height), incidence, spread, id,
                               nfoot + static_cast<int>(p), SurfaceKind::kPerson});
    ray.crossings.push_back({t2, around(t2), static_cast<float>(person.height), incidence, spread, id,
                             nfoot + static_cast<int>(p), SurfaceKind::kPerson});
  }
  std::sort(ray.crossings.begin(), ray.crossings.end(), [](const Crossing& a, const Crossing& b) {
    return a.d < b.d || (a.d == b.d && a.face < b.face);
  });
  for (std::size_t i = 0; i < ray.crossings.size(); ++i)
    if (is_full_height(ray.crossings[i].kind)) {
      ray.crossings.resize(i + 1);
      break;
    }
}

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
inline Hit first_hit(const FrameContext& ctx, const ColumnRay& ray, const RayRow& row) {
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

// ---- texturing
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

inline cv::Vec3f sample_texture(const TexturePyramid& t, double x, double y, double footprint,
                                bool periodic) {
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

inline cv::Vec3b to_bgr(const cv::Vec3f& c) {
  return {cv::saturate_cast<uchar>(c[0]), cv::saturate_cast<uchar>(c[1]), cv::saturate_cast<uchar>(c[2])};
}

const cv::Vec3b kSky(235, 206, 160);

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

void add_noise(cv::Mat& rgb, const RenderOptions& o, int frame_index) {
  if (o.noise_sigma <= 0) return;
  cv::RNG rng(mix_hash(0x4015eull + o.noise_seed * 1000003ull + static_cast<std::uint64_t>(frame_index)));
  cv::Mat noise(rgb.size(), CV_16SC3);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, o.noise_sigma);
  cv::Mat sum;
  cv::add(rgb, noise, sum, cv::noArray(), CV_16SC3);
  sum.convertTo(rgb, CV_8UC3);
}

}  // namespace

// ---- options
std::string SceneOptions::check() const {
  if (!(wall_height > 0.0) || wall_height > 100.0) return "wall_height must be in (0, 100] m";
  if (!(camera_height > 0.0) || camera_height >= wall_height)
    return "camera_height must be in (0, wall_height)";
  if (!(furniture_height > 0.0) || furniture_height > wall_height)
    return "furniture_height must be in (0, wall_height]";
  for (const auto& [layer, h] : furniture_layer_heights)
    if (!(h > 0.0) || h > wall_height)
      return "furniture height of layer '" + layer + "' must be in (0, wall_height]";
  if (!(floor_margin >= 0.0)) return "floor_margin must be >= 0";
  if (texture_size < 16 || texture_size > 8192 || (texture_size & (texture_size - 1)) != 0)
    return "texture_size must be a power of two in [16, 8192]";
  if (!(texels_per_metre > 0.0)) return "texels_per_metre must be > 0";
  return {};
}

std::string RenderOptions::check() const {
  if (width < 8 || height < 4 || width > 32768 || height > 16384)
    return "size must be between 8x4 and 32768x16384";
  if (threads < 0) return "threads must be >= 0";
  if (!(noise_sigma >= 0.0) || noise_sigma > 100.0) return "noise_sigma must be in [0, 100]";
  if (!(exposure_drift >= 0.0) || exposure_drift >= 1.0) return "exposure_drift must be in [0, 1)";
  if (!(exposure_period_frames > 0.0)) return "exposure_period_frames must be > 0";
  if (people < 0 || people > 1000) return "people must be in [0, 1000]";
  if (!(frame_rate > 0.0)) return "frame_rate must be > 0";
  if (jpeg_quality < 1 || jpeg_quality > 100) return "jpeg_quality must be in [1, 100]";
  return {};
}

// ---- scene
SyntheticScene build_synthetic_scene(const FloorPlan& plan, const SceneOptions& options) {
  if (const std::string e = options.check(); !e.empty()) throw Error("synthetic scene options: " + e);
  SyntheticScene scene;
  scene.options = options;
  const std::uint64_t seed = options.texture_seed;

  auto selected = [&](const std::string& layer) {
    if (!options.layers.empty()) return listed(options.layers, layer);
    const PlanLayer* l = plan.find_layer(layer);
    return !l || l->visible;
  };
  auto is_column = [&](const std::string& layer) {
    return options.column_layers.empty() ? contains_any(layer, {"COL", "PILLAR"})
                                         : listed(options.column_layers, layer);
  };
  auto is_furniture = [&](const std::string& layer) {
    return options.furniture_layers.empty() ? contains_any(layer, {"FURN", "DESK", "TABLE", "EQUIP"})
                                            : listed(options.furniture_layers, layer);
  };
  auto furniture_top = [&](const std::string& layer) {
    auto it = options.furniture_layer_heights.find(layer);
    return it == options.furniture_layer_heights.end() ? options.furniture_height : it->second;
  };

  auto add_face = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, double top, SurfaceKind kind,
                      int footprint) {
    if ((b - a).norm() < 1e-9) return;
    SceneFace f;
    f.a = a;
    f.b = b;
    f.top = top;
    f.kind = kind;
    f.footprint = footprint;
    scene.faces.push_back(f);
  };
  std::set<std::string> furniture_layers_with_outlines;
  for (const auto& o : plan.outlines)
    if (o.closed && o.points.size() >= 3 && selected(o.layer) && is_furniture(o.layer) &&
        !is_column(o.layer)) {
      furniture_layers_with_outlines.insert(o.layer);
      SceneFootprint fp;
      fp.points = o.points;
      fp.top = furniture_top(o.layer);
      const int id = static_cast<int>(scene.footprints.size());
      for (std::size_t i = 0; i < o.points.size(); ++i)
        add_face(o.points[i], o.points[(i + 1) % o.points.size()], fp.top, SurfaceKind::kFurnitureSide, id);
      scene.footprints.push_back(fp);
    }
  for (const auto& s : plan.segments) {
    if (!selected(s.layer)) continue;
    if (is_column(s.layer))
      add_face(s.a, s.b, options.wall_height, SurfaceKind::kPillar, -1);
    else if (is_furniture(s.layer)) {
      if (!furniture_layers_with_outlines.count(s.layer))  // loose furniture lines: low double-sided faces
        add_face(s.a, s.b, furniture_top(s.layer), SurfaceKind::kFurnitureSide, -1);
    } else if (s.occluder)
      add_face(s.a, s.b, options.wall_height, SurfaceKind::kWall, -1);
  }
  if (scene.faces.empty())
    throw Error((plan.source_file.empty() ? std::string("floor plan") : plan.source_file) +
                ": nothing to render: no occluding, column or furniture geometry on the selected layers");

  // Extents of what is rendered.
  Eigen::Vector2d lo = scene.faces[0].a, hi = scene.faces[0].a;
  for (const auto& f : scene.faces) {
    lo = lo.cwiseMin(f.a).cwiseMin(f.b);
    hi = hi.cwiseMax(f.a).cwiseMax(f.b);
  }
  scene.floor_min = lo - Eigen::Vector2d::Constant(options.floor_margin);
  scene.floor_max = hi + Eigen::Vector2d::Constant(options.floor_margin);

  // Per-surface materials, tints, offsets, lighting and posters: deterministic in (seed, surface index).
  const Eigen::Vector2d light1 = Eigen::Vector2d(0.6, 0.8), light2 = Eigen::Vector2d(-0.8, 0.3).normalized();
  for (std::size_t i = 0; i < scene.faces.size(); ++i) {
    SceneFace& f = scene.faces[i];
    const std::uint64_t h = mix_hash(seed * 0x100000001b3ull + i);
    auto unit = [h](int k) { return hash_unit(h + static_cast<std::uint64_t>(k)); };
    switch (f.kind) {
      case SurfaceKind::kPillar:
        f.material = kMaterialPillar;
        break;
      case SurfaceKind::kFurnitureSide:
        f.material = kMaterialFurnitureSide;
        break;
      default:
        f.material = kMaterialWall0 + static_cast<int>(unit(1) * kMaterialWallCount) % kMaterialWallCount;
    }
    f.u_offset = unit(2) * 64.0;
    f.tint = cv::Vec3f(static_cast<float>(0.85 + 0.3 * unit(3)), static_cast<float>(0.85 + 0.3 * unit(4)),
                       static_cast<float>(0.85 + 0.3 * unit(5)));
    const Eigen::Vector2d e = (f.b - f.a).normalized();
    const Eigen::Vector2d n(-e.y(), e.x());
    f.shade = static_cast<float>(0.62 + 0.25 * std::abs(n.dot(light1)) + 0.13 * std::abs(n.dot(light2)));
    f.poster_begin = static_cast<int>(scene.posters.size());
    const double len = (f.b - f.a).norm();
    if (f.kind == SurfaceKind::kWall && len >= 1.6 && unit(6) < 0.6) {
      ScenePoster p;
      const double w = 0.6 + 0.4 * unit(7), hgt = w * 352.0 / 256.0;
      const double centre = f.u_offset + 0.2 + w / 2 + unit(8) * (len - 0.4 - w);
      p.u0 = centre - w / 2;
      p.u1 = centre + w / 2;
      p.z0 = 1.45 - hgt / 2 + 0.2 * unit(9);
      p.z1 = p.z0 + hgt;
      p.image = static_cast<int>(unit(10) * 8) % 8;
      if (p.z1 < options.wall_height - 0.05) scene.posters.push_back(p);
    }
    f.poster_end = static_cast<int>(scene.posters.size());
  }
  for (std::size_t i = 0; i < scene.footprints.size(); ++i) {
    const std::uint64_t h = mix_hash(seed * 0x9e3779b1ull + 77 + i);
    SceneFootprint& fp = scene.footprints[i];
    fp.material = kMaterialFurnitureTop;
    fp.tint = cv::Vec3f(static_cast<float>(0.8 + 0.4 * hash_unit(h)),
                        static_cast<float>(0.8 + 0.4 * hash_unit(h + 1)),
                        static_cast<float>(0.8 + 0.4 * hash_unit(h + 2)));
    fp.texture_offset = Eigen::Vector2d(hash_unit(h + 3) * 16.0, hash_unit(h + 4) * 16.0);
  }
  if (options.use_grid) scene.grid = build_grid(scene);
  scene.textures = make_scene_textures(options.texture_seed, options.texture_size, options.texels_per_metre);
  return scene;
}

// ---- rendering
RenderedPanorama render_panorama(const SyntheticScene& scene, const PathFrame& pose,
                                 const RenderOptions& options) {
  RenderedPanorama out;
  render_panorama(scene, pose, options, out);
  return out;
}

void render_panorama(const SyntheticScene& scene, const PathFrame& pose, const RenderOptions& options,
                     RenderedPanorama& out) {
  if (const std::string e = options.check(); !e.empty()) throw Error("render options: " + e);
  if (!scene.textures) throw Error("render_panorama: the scene was not built with build_synthetic_scene");
  const int w = options.width, h = options.height;
  const FrameContext ctx =
      make_context(scene, options, {pose.x, pose.y, scene.options.camera_height}, pose.index);

  std::vector<ColumnRay> columns(w);
  // threads == 1 keeps everything on the calling thread; otherwise OpenCV's pool does the work.
  const int stripes = std::max(1, cv::getNumThreads());
  auto run = [&options](const cv::Range& range, int nstripes,
                        const std::function<void(const cv::Range&)>& body) {
    if (options.threads == 1)
      body(range);
    else
      cv::parallel_for_(range, body, nstripes);
  };
  run(cv::Range(0, w), stripes * 4, [&](const cv::Range& r) {
    FaceStamps stamps;
    for (int u = r.start; u < r.end; ++u) {
      const double azimuth = (u + 0.5) / w * 2.0 * kPi - kPi;
      const double angle = pose.heading - azimuth;  // world angle of the column
      cast_column(ctx, Eigen::Vector2d(std::cos(angle), std::sin(angle)), columns[u], stamps);
    }
  });

  out.rgb.create(h, w, CV_8UC3);
  if (options.depth)
    out.depth.create(h, w, CV_32F);
  else
    out.depth.release();
  const double pixel_angle = 2.0 * kPi / w;
  // Per-row constants, then the pixels in tiles: neighbouring pixels of a tile sample neighbouring texels,
  // which keeps the textures' working set in cache.
  std::vector<RayRow> rows;
  rows.reserve(h);
  for (int v = 0; v < h; ++v) {
    const double elevation = kPi / 2.0 - (v + 0.5) / h * kPi;
    rows.emplace_back(std::tan(elevation), std::cos(elevation), std::sin(elevation));
  }
  constexpr int kTileW = 64, kTileH = 32;
  const int tiles_x = (w + kTileW - 1) / kTileW, tiles_y = (h + kTileH - 1) / kTileH;
  run(cv::Range(0, tiles_x * tiles_y), stripes * 8, [&](const cv::Range& r) {
    for (int t = r.start; t < r.end; ++t) {
      const int u0 = (t % tiles_x) * kTileW, v0 = (t / tiles_x) * kTileH;
      const int u1 = std::min(w, u0 + kTileW), v1 = std::min(h, v0 + kTileH);
      for (int v = v0; v < v1; ++v) {
        const RayRow& row = rows[v];
        cv::Vec3b* rgb = out.rgb.ptr<cv::Vec3b>(v);
        float* depth = options.depth ? out.depth.ptr<float>(v) : nullptr;
        for (int u = u0; u < u1; ++u) {
          const Hit hit = first_hit(ctx, columns[u], row);
          const double distance = hit.kind == SurfaceKind::kNone ? 0.0 : hit.d * row.sec_e;
          rgb[u] = shade(ctx, columns[u], hit, row, distance, pixel_angle);
          if (depth) depth[u] = static_cast<float>(distance);
        }
      }
    }
  });
  add_noise(out.rgb, options, pose.index);
}

RayHit trace_ray(const SyntheticScene& scene, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                 const RenderOptions& options, int frame_index) {
  if (!scene.textures) throw Error("trace_ray: the scene was not built with build_synthetic_scene");
  const FrameContext ctx = make_context(scene, options, origin, frame_index);
  const Eigen::Vector3d d = direction.normalized();
  const double horizontal = std::hypot(d.x(), d.y());
  ColumnRay ray;
  const double pixel_angle = 2.0 * kPi / options.width;
  RayHit result;
  const double cos_e = horizontal, sin_e = d.z();
  if (horizontal < 1e-12) {  // straight up or down: no face can be met
    ray.origin = ctx.origin;
    ray.dir = Eigen::Vector2d(1, 0);
    ray.d_exit = 0;
    Hit hit;
    const bool inside_floor = (ctx.origin.array() >= scene.floor_min.array()).all() &&
                              (ctx.origin.array() <= scene.floor_max.array()).all();
    double dist = 0;
    if (d.z() < 0) {
      const double level = ctx.start_footprint >= 0 ? ctx.footprint_tops[ctx.start_footprint] : 0.0;
      if (ctx.start_footprint >= 0 || inside_floor) {
        hit.kind = ctx.start_footprint >= 0 ? SurfaceKind::kFurnitureTop : SurfaceKind::kFloor;
        hit.footprint = ctx.start_footprint;
        dist = ctx.cam_z - level;
      }
    } else if (inside_floor) {
      hit.kind = SurfaceKind::kCeiling;
      dist = scene.options.wall_height - ctx.cam_z;
    }
    result.distance = dist;
    result.kind = hit.kind;
    result.bgr = shade(ctx, ray, hit, RayRow(0.0, 0.0, sin_e), dist, pixel_angle);
    return result;
  }
  FaceStamps stamps;
  cast_column(ctx, Eigen::Vector2d(d.x(), d.y()) / horizontal, ray, stamps);
  const double s = d.z() / horizontal;
  const RayRow row(s, cos_e, sin_e);
  const Hit hit = first_hit(ctx, ray, row);
  result.kind = hit.kind;
  result.distance = hit.kind == SurfaceKind::kNone ? 0.0 : hit.d / horizontal;
  result.bgr = shade(ctx, ray, hit, row, result.distance, pixel_angle);
  return result;
}

RenderedPanorama render_directions(const SyntheticScene& scene, const Eigen::Vector3d& origin,
                                   const cv::Mat& directions, double pixel_angle,
                                   const RenderOptions& options, int frame_index) {
  if (!scene.textures) throw Error("render_directions: the scene was not built with build_synthetic_scene");
  if (directions.type() != CV_64FC3) throw Error("render_directions: directions must be CV_64FC3");
  if (const std::string e = options.check(); !e.empty()) throw Error("render options: " + e);
  const FrameContext ctx = make_context(scene, options, origin, frame_index);
  RenderedPanorama out;
  out.rgb.create(directions.size(), CV_8UC3);
  out.depth.create(directions.size(), CV_32F);
  auto body = [&](const cv::Range& r) {
    ColumnRay ray;
    FaceStamps stamps;
    for (int v = r.start; v < r.end; ++v)
      for (int u = 0; u < directions.cols; ++u) {
        const cv::Vec3d& dv = directions.at<cv::Vec3d>(v, u);
        const Eigen::Vector3d d = Eigen::Vector3d(dv[0], dv[1], dv[2]).normalized();
        const double horizontal = std::hypot(d.x(), d.y());
        if (horizontal < 1e-12) {  // straight up or down: rare, use the general path
          const RayHit hit = trace_ray(scene, origin, d, options, frame_index);
          out.rgb.at<cv::Vec3b>(v, u) = hit.bgr;
          out.depth.at<float>(v, u) = static_cast<float>(hit.distance);
          continue;
        }
        FaceStamps stamps;
        cast_column(ctx, Eigen::Vector2d(d.x(), d.y()) / horizontal, ray, stamps);
        const RayRow row(d.z() / horizontal, horizontal, d.z());
        const Hit hit = first_hit(ctx, ray, row);
        const double distance = hit.kind == SurfaceKind::kNone ? 0.0 : hit.d / horizontal;
        out.rgb.at<cv::Vec3b>(v, u) = shade(ctx, ray, hit, row, distance, pixel_angle);
        out.depth.at<float>(v, u) = static_cast<float>(distance);
      }
  };
  if (options.threads == 1)
    body(cv::Range(0, directions.rows));
  else
    cv::parallel_for_(cv::Range(0, directions.rows), body, std::max(1, cv::getNumThreads()) * 4);
  add_noise(out.rgb, options, frame_index);
  return out;
}

std::vector<PersonPose> people_at_frame(const SyntheticScene& scene, const RenderOptions& options,
                                        int frame_index) {
  std::vector<PersonPose> out;
  for (const auto& p : people_now(scene, options, frame_index)) out.push_back(p.pose);
  return out;
}

}  // namespace plenopath
