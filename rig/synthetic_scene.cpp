// Building the synthetic scene from a floor plan: walls, pillars and furniture as vertical faces, furniture
// tops, the floor rectangle, per-surface materials, tints, lighting and posters (deterministic in the
// texture seed and the surface's index), and the uniform grid the ray caster walks.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "model/error.h"
#include "model/option_check.h"
#include "rig/render_internal.h"
#include "rig/scene_textures.h"

namespace plenopath {
namespace render_detail {

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

}  // namespace render_detail

namespace {

using render_detail::is_full_height;
using render_detail::point_in_polygon;

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
}  // namespace

// ---- options
void SceneOptions::check() const {
  const std::string s = "SceneOptions.";
  require_option(wall_height > 0.0 && wall_height <= 100.0, s + "wall_height", "must be in (0, 100] m",
                 wall_height);
  require_option(camera_height > 0.0 && camera_height < wall_height, s + "camera_height",
                 "must be in (0, wall_height)", camera_height);
  require_option(furniture_height > 0.0 && furniture_height <= wall_height, s + "furniture_height",
                 "must be in (0, wall_height]", furniture_height);
  for (const auto& [layer, h] : furniture_layer_heights)
    require_option(h > 0.0 && h <= wall_height, s + "furniture_layer_heights['" + layer + "']",
                   "must be in (0, wall_height]", h);
  require_option(floor_margin >= 0.0, s + "floor_margin", "must be >= 0", floor_margin);
  require_option(texture_size >= 16 && texture_size <= 8192 && (texture_size & (texture_size - 1)) == 0,
                 s + "texture_size", "must be a power of two in [16, 8192]", texture_size);
  require_option(texels_per_metre > 0.0, s + "texels_per_metre", "must be > 0", texels_per_metre);
}

// ---- scene
SyntheticScene build_synthetic_scene(const FloorPlan& plan, const SceneOptions& options) {
  options.check();
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
    if (options.wall_finish == WallFinish::kPlainPaint && is_full_height(f.kind)) {
      // One paint for the whole building: faces differ by a few per cent (touch-ups, light), not by hue.
      f.material = kMaterialPaint;
      const float t = static_cast<float>(0.97 + 0.06 * unit(3));
      f.tint = cv::Vec3f(t, t, t);
    }
    const Eigen::Vector2d e = (f.b - f.a).normalized();
    const Eigen::Vector2d n(-e.y(), e.x());
    f.shade = static_cast<float>(0.62 + 0.25 * std::abs(n.dot(light1)) + 0.13 * std::abs(n.dot(light2)));
    f.poster_begin = static_cast<int>(scene.posters.size());
    const double len = (f.b - f.a).norm();
    if (options.posters && f.kind == SurfaceKind::kWall && len >= 1.6 && unit(6) < 0.6) {
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

}  // namespace plenopath
