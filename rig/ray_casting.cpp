// The 2-D ray cast of the synthetic camera: which vertical faces (walls, pillars, furniture sides, people)
// a horizontal ray meets, in order, up to the first full-height face. Through the uniform grid over the
// faces (Amanatides & Woo) or, without one, by testing every face.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rig/render_internal.h"

namespace plenopath::render_detail {
namespace {

// Where the ray leaves the floor rectangle (slabs).
double floor_exit(const SyntheticScene& scene, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir) {
  double exit = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    if (dir[k] > 0)
      exit = std::min(exit, (scene.floor_max[k] - origin[k]) / dir[k]);
    else if (dir[k] < 0)
      exit = std::min(exit, (scene.floor_min[k] - origin[k]) / dir[k]);
  }
  return std::max(0.0, exit);
}

// Appends the crossing of the ray with face i, if any; returns its distance (infinity when none).
double add_face_crossing(const SyntheticScene& scene, const Eigen::Vector2d& origin,
                         const Eigen::Vector2d& dir, int i, ColumnRay& ray) {
  const SceneFace& f = scene.faces[i];
  const Eigen::Vector2d e = f.b - f.a;
  const double denom = cross(dir, e);
  const double none = std::numeric_limits<double>::infinity();
  if (denom == 0.0) return none;
  const Eigen::Vector2d w = f.a - origin;
  const double t = cross(w, e) / denom;
  if (!(t > 0.0)) return none;
  const double s = cross(w, dir) / denom;
  if (s < 0.0 || s > 1.0) return none;
  const double len = e.norm();
  const float incidence = static_cast<float>(std::abs(denom) / len);
  ray.crossings.push_back({t, s * len + f.u_offset, static_cast<float>(f.top), incidence,
                           1.0f / std::sqrt(std::max(incidence, 0.02f)), i, f.footprint, f.kind});
  return t;
}

void add_people_crossings(const FrameContext& ctx, const Eigen::Vector2d& dir, ColumnRay& ray) {
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
}

// Sorts the crossings by distance and drops what lies behind the first full-height face.
void finish_crossings(ColumnRay& ray) {
  std::sort(ray.crossings.begin(), ray.crossings.end(), [](const Crossing& a, const Crossing& b) {
    return a.d < b.d || (a.d == b.d && a.face < b.face);
  });
  for (std::size_t i = 0; i < ray.crossings.size(); ++i)
    if (is_full_height(ray.crossings[i].kind)) {
      ray.crossings.resize(i + 1);
      break;
    }
}

}  // namespace

void cast_column(const FrameContext& ctx, const Eigen::Vector2d& dir, ColumnRay& ray, FaceStamps& stamps) {
  const SyntheticScene& scene = *ctx.scene;
  ray.origin = ctx.origin;
  ray.dir = dir;
  ray.crossings.clear();
  ray.d_exit = floor_exit(scene, ctx.origin, dir);
  double nearest_wall = std::numeric_limits<double>::infinity();
  auto test_face = [&](int i) {
    const double t = add_face_crossing(scene, ctx.origin, dir, i, ray);
    if (std::isfinite(t) && is_full_height(scene.faces[i].kind)) nearest_wall = std::min(nearest_wall, t);
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
  add_people_crossings(ctx, dir, ray);
  finish_crossings(ray);
}

void cast_from_candidates(const FrameContext& ctx, const Eigen::Vector2d& dir,
                          const std::vector<int>& candidates, ColumnRay& ray) {
  ray.origin = ctx.origin;
  ray.dir = dir;
  ray.crossings.clear();
  ray.d_exit = floor_exit(*ctx.scene, ctx.origin, dir);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const int i = candidates[k];
    if (std::find(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(k), i) !=
        candidates.begin() + static_cast<std::ptrdiff_t>(k))
      continue;  // listed twice
    add_face_crossing(*ctx.scene, ctx.origin, dir, i, ray);
  }
  add_people_crossings(ctx, dir, ray);
  finish_crossings(ray);
}

Hit vertical_hit(const FrameContext& ctx, bool down, ColumnRay& ray, double* distance) {
  const SyntheticScene& scene = *ctx.scene;
  ray.origin = ctx.origin;
  ray.dir = Eigen::Vector2d(1, 0);
  ray.crossings.clear();
  ray.d_exit = 0;
  Hit hit;
  const bool inside_floor = (ctx.origin.array() >= scene.floor_min.array()).all() &&
                            (ctx.origin.array() <= scene.floor_max.array()).all();
  double dist = 0;
  if (down) {
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
  *distance = dist;
  return hit;
}

}  // namespace plenopath::render_detail
