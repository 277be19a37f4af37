// The fast envelope areas (triangular expansion in doubles, closed-form cell means, exact fallback) against
// a brute-force ray caster written here and against the exact CGAL class.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "model/path_io.h"
#include "processing/visibility/visibility.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/plan/plan_oracle.h"

namespace plenopath {
namespace {

using test::add_polygon;
using test::add_wall;
using test::ray_cast_area;

using Vec = Eigen::Vector2d;

// A 20 m x 15 m room split by a wall at x = 10 with a door (T-junctions), rotated pillars and dangling
// stubs from the bottom wall.
FloorPlan random_plan(std::mt19937* rng) {
  FloorPlan plan;
  add_polygon(&plan, {{0, 0}, {20, 0}, {20, 15}, {0, 15}});
  std::uniform_real_distribution<double> door(3.0, 11.0), ux(1.5, 18.5), uy(2.0, 13.0), size(0.3, 1.0),
      angle(0.0, M_PI), stub(0.5, 1.5);
  const double d = door(*rng);
  add_wall(&plan, {10, 0}, {10, d});
  add_wall(&plan, {10, d + 1.2}, {10, 15});
  std::vector<Vec> centres;
  while (centres.size() < 6) {
    const Vec c(ux(*rng), uy(*rng));
    bool clear = std::abs(c.x() - 10.0) > 1.0;
    for (const auto& o : centres) clear &= (o - c).norm() > 2.0;
    if (!clear) continue;
    centres.push_back(c);
    const Eigen::Rotation2Dd r(angle(*rng));
    const double w = size(*rng) / 2, h = size(*rng) / 2;
    add_polygon(&plan, {c + r * Vec(-w, -h), c + r * Vec(w, -h), c + r * Vec(w, h), c + r * Vec(-w, h)});
  }
  for (int i = 0; i < 2; ++i) {
    const double x = ux(*rng);
    add_wall(&plan, {x, 0.0}, {x, stub(*rng)});
  }
  return plan;
}

std::vector<Vec> free_points(const VisibilityIndex& index, std::mt19937* rng, int n) {
  std::uniform_real_distribution<double> ux(0.0, 20.0), uy(0.0, 15.0);
  std::vector<Vec> points;
  while (static_cast<int>(points.size()) < n) {
    const Vec p(ux(*rng), uy(*rng));
    if (index.classify(p) == EnvelopeStatus::ok) points.push_back(p);
  }
  return points;
}

double orient(const Vec& a, const Vec& b, const Vec& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// Whether [p, q] touches a wall (closed segments).
bool crosses_wall(const std::vector<PlanSegment>& walls, const Vec& p, const Vec& q) {
  for (const auto& w : walls) {
    const double o1 = orient(p, q, w.a), o2 = orient(p, q, w.b), o3 = orient(w.a, w.b, p),
                 o4 = orient(w.a, w.b, q);
    if (o1 == 0 && o2 == 0) {  // collinear: do they overlap?
      const Vec d = q - p;
      const double ta = (w.a - p).dot(d) / d.squaredNorm(), tb = (w.b - p).dot(d) / d.squaredNorm();
      if (std::max(ta, tb) >= 0 && std::min(ta, tb) <= 1) return true;
      continue;
    }
    if (o1 * o2 <= 0 && o3 * o4 <= 0) return true;
  }
  return false;
}

// A random walk through free space, frames 0.4 m apart, turning at every frame (so cells hold corners).
CameraPath random_walk(const VisibilityIndex& index, std::mt19937* rng, int frames) {
  const auto walls = index.effective_segments();
  std::uniform_real_distribution<double> turn(-0.6, 0.6), heading(0.0, 2 * M_PI);
  CameraPath path;
  Vec p = free_points(index, rng, 1).front();
  double h = heading(*rng);
  while (static_cast<int>(path.frames.size()) < frames) {
    PathFrame f;
    f.index = static_cast<int>(path.frames.size());
    f.x = p.x();
    f.y = p.y();
    path.frames.push_back(f);
    for (int attempt = 0;; ++attempt) {
      const double g = attempt < 20 ? h + turn(*rng) : heading(*rng);
      const Vec q = p + 0.4 * Vec(std::cos(g), std::sin(g));
      if (index.classify(q) == EnvelopeStatus::ok && !crosses_wall(walls, p, q)) {
        p = q;
        h = g;
        break;
      }
    }
  }
  return path;
}

Vec point_at(const CameraPath& path, const std::vector<double>& s_at, double s) {
  std::size_t i = 1;
  while (i + 1 < s_at.size() && s > s_at[i]) ++i;
  const double t = (s - s_at[i - 1]) / (s_at[i] - s_at[i - 1]);
  return path.frames[i - 1].position() + t * (path.frames[i].position() - path.frames[i - 1].position());
}

// The mean of f over [s0, s1] of the path: Simpson's rule on each straight piece between path vertices.
template <typename F>
double path_mean(const CameraPath& path, const std::vector<double>& s_at, double s0, double s1, int intervals,
                 const F& f) {
  std::vector<double> breaks = {s0};
  for (double s : s_at)
    if (s > s0 && s < s1) breaks.push_back(s);
  breaks.push_back(s1);
  double integral = 0.0;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double h = (breaks[k + 1] - breaks[k]) / intervals;
    for (int i = 0; i <= intervals; ++i) {
      const double w = (i == 0 || i == intervals) ? 1 : (i % 2 ? 4 : 2);
      integral += w * h / 3.0 * f(point_at(path, s_at, breaks[k] + i * h));
    }
  }
  return integral / (s1 - s0);
}

VisibilityOptions exact_options() {
  VisibilityOptions o;
  o.area_method = AreaMethod::exact;
  return o;
}

TEST(VisibilityFastArea, MatchesRayCasterAndExactOnRandomPlans) {
  std::mt19937 rng(11);
  std::size_t queries = 0;
  for (int plan_index = 0; plan_index < 4; ++plan_index) {
    const FloorPlan plan = random_plan(&rng);
    const VisibilityIndex fast(plan), exact(plan, exact_options());
    const auto walls = fast.effective_segments();
    for (const Vec& p : free_points(fast, &rng, 8)) {
      const double a = fast.envelope_area(p);
      ++queries;
      EXPECT_NEAR(a / exact.envelope_area(p), 1.0, 1e-9) << "plan " << plan_index << " " << p.transpose();
      EXPECT_NEAR(a / ray_cast_area(walls, p, 20000), 1.0, 1e-3)
          << "plan " << plan_index << " " << p.transpose();
    }
    EXPECT_EQ(fast.envelope_area({-5, -5}), 0.0);  // outside
    const EnvelopeAreaCounts counts = fast.area_counts();
    EXPECT_GE(counts.fast, 7u) << "plan " << plan_index << ": the fast path should answer almost every query";
    EXPECT_EQ(counts.fast + counts.exact, 8u);
    EXPECT_EQ(exact.area_counts().fast, 0u);
  }
  EXPECT_EQ(queries, 32u);
}

TEST(VisibilityFastArea, StartsOnAnEdgeAndFallsBackWhereTheExpansionGivesUp) {
  // The centre of a rectangle lies on its triangulation's diagonal (either one): the expansion starts
  // from both triangles beside that edge.
  FloorPlan box;
  add_polygon(&box, {{0, 0}, {10, 0}, {10, 8}, {0, 8}});
  const VisibilityIndex box_index(box);
  EXPECT_NEAR(box_index.envelope_area({5, 4}), 80.0, 1e-9);
  EXPECT_NEAR(box_index.envelope_area({3, 2}), 80.0, 1e-9);
  EXPECT_NEAR(box_index.envelope_area({5 + 1e-10, 4}), 80.0, 1e-9);
  EXPECT_EQ(box_index.area_counts().fast, 3u);
  EXPECT_EQ(box_index.area_counts().exact, 0u);

  // One window step allowed: every query falls back, for single points and for the cells.
  std::mt19937 rng(5);
  const FloorPlan plan = random_plan(&rng);
  VisibilityOptions capped;
  capped.fast_area_max_steps = 1;
  const VisibilityIndex fallback(plan, capped), fast(plan), exact(plan, exact_options());
  const auto walls = fallback.effective_segments();
  for (const Vec& p : free_points(fallback, &rng, 6)) {
    const double a = fallback.envelope_area(p);
    EXPECT_DOUBLE_EQ(a, exact.envelope_area(p));
    EXPECT_NEAR(a / ray_cast_area(walls, p, 20000), 1.0, 1e-3) << p.transpose();
  }
  EXPECT_EQ(fallback.area_counts().fast, 0u);
  EXPECT_EQ(fallback.area_counts().exact, 6u);

  const CameraPath path = random_walk(fast, &rng, 12);
  const VisibilityCells slow_cells = fallback.cells_along_path(path),
                        fast_cells = fast.cells_along_path(path);
  EXPECT_EQ(fallback.area_counts().fast, 0u);
  EXPECT_EQ(slow_cells.events, fast_cells.events);
  ASSERT_EQ(slow_cells.cells.size(), fast_cells.cells.size());
  for (std::size_t c = 0; c < fast_cells.cells.size(); ++c) {
    EXPECT_NEAR(slow_cells.cells[c].area_mid / fast_cells.cells[c].area_mid, 1.0, 1e-9) << "cell " << c;
    // The fallback integrates the cell with three queries (no closed form): close, not identical.
    EXPECT_NEAR(slow_cells.cells[c].area_mean / fast_cells.cells[c].area_mean, 1.0, 1e-3) << "cell " << c;
  }
}

TEST(VisibilityFastArea, CellMeanAreaIsTheMeanOverTheCell) {
  std::mt19937 rng(23);
  int checked = 0, against_rays = 0;
  for (int plan_index = 0; plan_index < 3; ++plan_index) {
    const FloorPlan plan = random_plan(&rng);
    const VisibilityIndex fast(plan), exact(plan, exact_options());
    const auto walls = fast.effective_segments();
    const CameraPath path = random_walk(fast, &rng, 25);
    const auto s_at = path.arc_lengths();
    const VisibilityCells cells = fast.cells_along_path(path);
    // One expansion per cell (at its middle); the rest of the cell from its wedges in closed form.
    const EnvelopeAreaCounts counts = fast.area_counts();
    EXPECT_LE(counts.fast + counts.exact, cells.cells.size() + cells.cells.size() / 10 + 2)
        << "plan " << plan_index;
    EXPECT_GT(counts.closed_form, 3 * cells.cells.size());
    for (std::size_t c = 0; c < cells.cells.size(); c += std::max<std::size_t>(1, cells.cells.size() / 15)) {
      const auto& cell = cells.cells[c];
      if (cell.length < 1e-3) continue;
      const Vec mid = point_at(path, s_at, 0.5 * (cell.s_begin + cell.s_end));
      EXPECT_NEAR(cell.area_mid / exact.envelope_area(mid), 1.0, 1e-9);
      const double mean = path_mean(path, s_at, cell.s_begin, cell.s_end, 16,
                                    [&](const Vec& q) { return exact.envelope_area(q); });
      EXPECT_NEAR(cell.area_mean / mean, 1.0, 1e-6) << "plan " << plan_index << " cell " << c;
      ++checked;
      if (c % 3 == 0) {
        const double rays = path_mean(path, s_at, cell.s_begin, cell.s_end, 2,
                                      [&](const Vec& q) { return ray_cast_area(walls, q, 20000); });
        EXPECT_NEAR(cell.area_mean / rays, 1.0, 1e-3) << "plan " << plan_index << " cell " << c;
        ++against_rays;
      }
    }
  }
  EXPECT_GE(checked, 30);
  EXPECT_GE(against_rays, 8);
}

TEST(VisibilityFastArea, DegenerateGeometryAndGridAlignedPoints) {
  // Duplicated, overlapping and collinear walls, a T-junction with a dangling stub, a pillar; queried on a
  // 0.25 m grid, where the query point is often collinear with walls and with pairs of vertices.
  FloorPlan plan;
  add_polygon(&plan, {{0, 0}, {10, 0}, {10, 8}, {0, 8}});
  add_wall(&plan, {0, 0}, {10, 0});
  add_wall(&plan, {2, 0}, {6, 0});
  add_wall(&plan, {4, 8}, {12, 8});
  add_wall(&plan, {3, 3}, {3, 3});
  add_wall(&plan, {5, 8}, {5, 6});
  add_polygon(&plan, {{6.5, 2.5}, {7.5, 2.5}, {7.5, 3.5}, {6.5, 3.5}});
  add_polygon(&plan, {{2, 5}, {3, 5}, {3, 5.5}, {2, 5.5}});
  const VisibilityIndex fast(plan), exact(plan, exact_options());
  const auto walls = fast.effective_segments();
  int queries = 0;
  for (double x = 0.25; x < 10; x += 0.25)
    for (double y = 0.25; y < 8; y += 0.25) {
      if (fast.classify({x, y}) != EnvelopeStatus::ok) continue;
      ++queries;
      const double a = fast.envelope_area({x, y});
      ASSERT_NEAR(a / exact.envelope_area({x, y}), 1.0, 1e-9) << x << " " << y;
      if (queries % 40 == 0) {
        EXPECT_NEAR(a / ray_cast_area(walls, {x, y}, 20000), 1.0, 1e-3) << x << " " << y;
      }
    }
  EXPECT_GT(queries, 1000);
  // Some of these may fall back (the answer is exact either way); most must not.
  EXPECT_GE(fast.area_counts().fast, static_cast<std::size_t>(queries * 9 / 10));
  std::printf("grid-aligned points: %d queries, %zu fast, %zu exact fallbacks\n", queries,
              fast.area_counts().fast, fast.area_counts().exact);
}

// Crossing, touching and axis-aligned free-standing walls, queried very near plan vertices (1 nm to 1 mm)
// and on lines through pairs of vertices: the fast answer equals the exact one, whichever path gives it.
TEST(VisibilityFastArea, NearVerticesAndOnVertexLines) {
  std::mt19937 rng(99);
  std::size_t queries = 0, fallbacks = 0;
  for (int plan_index = 0; plan_index < 6; ++plan_index) {
    FloorPlan plan;
    add_polygon(&plan, {{0, 0}, {20, 0}, {20, 15}, {0, 15}});
    std::uniform_real_distribution<double> ux(1, 19), uy(1, 14), length(0.2, 2), angle(0, M_PI);
    for (int k = 0; k < 15; ++k) {
      const Vec c(ux(rng), uy(rng));
      const double a = k % 5 == 0 ? 0.0 : k % 7 == 0 ? M_PI / 2 : angle(rng);
      add_wall(&plan, c, c + length(rng) * Vec(std::cos(a), std::sin(a)));
    }
    const VisibilityIndex fast(plan), exact(plan, exact_options());
    const auto vertices = fast.vertices();
    std::uniform_real_distribution<double> exponent(-9, -3), direction(0, 2 * M_PI), along(-1, 2);
    for (int k = 0; k < 300; ++k) {
      const Vec a = vertices[rng() % vertices.size()], b = vertices[rng() % vertices.size()];
      const double r = std::pow(10.0, exponent(rng)), t = direction(rng);
      const Vec p = k % 2 ? Vec(a + r * Vec(std::cos(t), std::sin(t))) : Vec(a + along(rng) * (b - a));
      if (fast.classify(p) != EnvelopeStatus::ok) continue;
      ++queries;
      ASSERT_NEAR(fast.envelope_area(p) / exact.envelope_area(p), 1.0, 1e-9)
          << "plan " << plan_index << " p " << p.x() << " " << p.y();
    }
    fallbacks += fast.area_counts().exact;
  }
  EXPECT_GT(queries, 1000u);
  EXPECT_LT(fallbacks * 20, queries);  // under 5 %
  std::printf("near vertices and on vertex lines: %zu queries, %zu exact fallbacks\n", queries, fallbacks);
}

// The office sample along its default walk: areas against the ray caster, and the critical lines drawn for
// the cell decomposition are windows clipped to free space (from a plan vertex to a wall, through free
// space only).
TEST(VisibilityFastArea, OfficeSampleCellsAndCriticalLines) {
  const FloorPlan plan = make_office_sample_plan();
  const CameraPath path =
      read_path_file(std::string(PLENOPATH_SOURCE_DIR) + "/resources/samples/office/office_path.json");
  const VisibilityIndex index(plan);
  const auto walls = index.effective_segments();
  const auto vertices = index.vertices();
  const auto s_at = path.arc_lengths();
  const VisibilityCells cells = index.cells_along_path(path);
  ASSERT_GT(cells.cells.size(), 100u);
  EXPECT_EQ(index.area_counts().exact, 0u);
  for (std::size_t c = 0; c < cells.cells.size(); c += cells.cells.size() / 12) {
    const auto& cell = cells.cells[c];
    const Vec mid = point_at(path, s_at, 0.5 * (cell.s_begin + cell.s_end));
    EXPECT_NEAR(cell.area_mid / ray_cast_area(walls, mid, 20000), 1.0, 1e-3) << "cell " << c;
  }
  ASSERT_FALSE(cells.critical_lines.empty());
  auto distance_to_walls = [&](const Vec& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& w : walls) {
      const Vec d = w.b - w.a;
      const double t = std::clamp((p - w.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (w.a + t * d - p).norm());
    }
    return best;
  };
  for (const auto& line : cells.critical_lines) {
    double nearest_vertex = std::numeric_limits<double>::infinity();
    for (const auto& v : vertices) nearest_vertex = std::min(nearest_vertex, (v - line.a).norm());
    ASSERT_LT(nearest_vertex, 1e-9) << "a critical line starts at a plan vertex: " << line.a.transpose();
    ASSERT_LT(distance_to_walls(line.b), 1e-6) << "and ends on a wall: " << line.b.transpose();
    ASSERT_GT((line.b - line.a).norm(), 1e-9);
    for (double f : {0.01, 0.25, 0.5, 0.75, 0.99})
      ASSERT_EQ(index.classify(line.a + f * (line.b - line.a)), EnvelopeStatus::ok)
          << "through free space: " << line.a.transpose() << " -> " << line.b.transpose() << " at " << f;
    // The open segment crosses no wall.
    const Vec a = line.a + 1e-7 * (line.b - line.a), b = line.b - 1e-7 * (line.b - line.a);
    ASSERT_FALSE(crosses_wall(walls, a, b)) << line.a.transpose() << " -> " << line.b.transpose();
  }
}

TEST(VisibilityFastArea, CellsDoNotDependOnThreadsOrRuns) {
  std::mt19937 rng(31);
  const FloorPlan plan = random_plan(&rng);
  VisibilityOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const VisibilityIndex single(plan, one), dual(plan, two);
  const CameraPath path = random_walk(single, &rng, 60);
  const VisibilityCells reference = single.cells_along_path(path);
  EXPECT_GT(reference.cells.size(), 20u);
  for (int run = 0; run < 3; ++run) EXPECT_TRUE(dual.cells_along_path(path) == reference) << "run " << run;
}

}  // namespace
}  // namespace plenopath
