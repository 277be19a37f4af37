// Visibility against brute-force oracles written here: a ray caster for envelope areas and radial
// functions, and dense sampling of the visible vertex set for events along paths.
#include "processing/visibility/visibility.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "model/error.h"
#include "tests/processing/plan/plan_oracle.h"

namespace plenopath {
namespace {

using test::add_polygon;
using test::add_rectangle;
using test::add_wall;
using test::cast_ray;
using test::ray_cast_area;

using Vec = Eigen::Vector2d;

// The sample-like plan: an L-shaped flat with interior walls (T-junctions, a door gap = a dangling wall)
// and two pillars.
FloorPlan sample_plan() {
  FloorPlan plan;
  add_polygon(&plan, {{0, 0}, {12, 0}, {12, 6}, {7, 6}, {7, 10}, {0, 10}});
  add_wall(&plan, {5, 0}, {5, 3.5});   // from the outer wall, leaves a door gap up to y = 4.5
  add_wall(&plan, {5, 4.5}, {5, 10});  // reaches the outer wall: T-junction at (5, 10)
  add_wall(&plan, {0, 6}, {3.8, 6});   // kitchen wall, dangling end
  add_rectangle(&plan, {9, 3}, 0.6, 0.6, 0.3);
  add_rectangle(&plan, {2.5, 2.5}, 0.5, 0.8, 0.0);
  return plan;
}

TEST(Visibility, BoxRoomEnvelopeIsTheRoom) {
  FloorPlan plan;
  add_polygon(&plan, {{0, 0}, {10, 0}, {10, 8}, {0, 8}});
  const VisibilityIndex index(plan);
  const Envelope e = index.envelope({3, 2});
  ASSERT_EQ(e.status, EnvelopeStatus::ok);
  EXPECT_NEAR(e.area, 80.0, 1e-9);
  EXPECT_EQ(e.polygon.size(), 4u);
  // Radial function: +X first, counter-clockwise.
  const auto r = index.radial_function({3, 2}, 4);
  EXPECT_NEAR(r[0], 7.0, 1e-12);
  EXPECT_NEAR(r[1], 6.0, 1e-12);
  EXPECT_NEAR(r[2], 3.0, 1e-12);
  EXPECT_NEAR(r[3], 2.0, 1e-12);
}

TEST(Visibility, SamplePlanMatchesRayCaster) {
  const FloorPlan plan = sample_plan();
  const VisibilityIndex index(plan);
  const auto walls = index.effective_segments();
  // Thickening only moved the dangling walls by half the thickness.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0.0, 12.0), uy(0.0, 10.0);
  int checked = 0;
  for (int trial = 0; trial < 200 && checked < 12; ++trial) {
    const Vec p(ux(rng), uy(rng));
    const Envelope e = index.envelope(p);
    if (e.status != EnvelopeStatus::ok) continue;
    ++checked;
    const double truth = ray_cast_area(walls, p, 40000);
    EXPECT_NEAR(e.area / truth, 1.0, 1e-3) << p.transpose();
    const int samples = 720;
    const auto radial = index.radial_function(p, samples);
    for (int k = 0; k < samples; ++k) {
      const double t = cast_ray(walls, p, 2 * M_PI * k / samples);
      ASSERT_NEAR(radial[k], t, 1e-6) << p.transpose() << " k " << k;
    }
  }
  EXPECT_GE(checked, 10);
}

FloorPlan random_plan(std::mt19937* rng, int pillars) {
  FloorPlan plan;
  add_polygon(&plan, {{0, 0}, {20, 0}, {20, 15}, {0, 15}});
  std::uniform_real_distribution<double> ux(2.0, 18.0), uy(2.0, 13.0), size(0.3, 1.2), angle(0.0, M_PI);
  std::vector<Vec> centres;
  while (static_cast<int>(centres.size()) < pillars) {
    const Vec c(ux(*rng), uy(*rng));
    bool clear = true;
    for (const auto& o : centres) clear &= (o - c).norm() > 2.0;
    if (!clear) continue;
    centres.push_back(c);
    add_rectangle(&plan, c, size(*rng), size(*rng), angle(*rng));
  }
  return plan;
}

TEST(Visibility, RandomPlansMatchRayCaster) {
  std::mt19937 rng(42);
  for (int plan_index = 0; plan_index < 4; ++plan_index) {
    FloorPlan plan = random_plan(&rng, 6);
    // Stubs from the bottom wall into the room (dangling walls).
    std::uniform_real_distribution<double> along(1.0, 19.0), len(0.5, 1.5);
    for (int i = 0; i < 2; ++i) {
      const double x = along(rng);
      add_wall(&plan, {x, 0.0}, {x, len(rng)});
    }
    const VisibilityIndex index(plan);
    const auto walls = index.effective_segments();
    std::uniform_real_distribution<double> ux(0.0, 20.0), uy(0.0, 15.0);
    int checked = 0;
    for (int trial = 0; trial < 100 && checked < 5; ++trial) {
      const Vec p(ux(rng), uy(rng));
      const Envelope e = index.envelope(p);
      if (e.status != EnvelopeStatus::ok) continue;
      ++checked;
      EXPECT_NEAR(e.area / ray_cast_area(walls, p, 20000), 1.0, 1e-3)
          << "plan " << plan_index << " " << p.transpose();
      const auto radial = index.radial_function(p, 360);
      for (int k = 0; k < 360; ++k) ASSERT_NEAR(radial[k], cast_ray(walls, p, 2 * M_PI * k / 360), 1e-6);
    }
    EXPECT_EQ(checked, 5);
  }
}

TEST(Visibility, DegenerateGeometryAndPointStatus) {
  FloorPlan plan;
  add_polygon(&plan, {{0, 0}, {10, 0}, {10, 8}, {0, 8}});
  add_wall(&plan, {0, 0}, {10, 0});             // duplicate
  add_wall(&plan, {2, 0}, {6, 0});              // collinear overlap
  add_wall(&plan, {4, 8}, {12, 8});             // collinear, sticking out
  add_wall(&plan, {3, 3}, {3, 3});              // zero length
  add_wall(&plan, {5, 8}, {5, 6});              // T-junction, dangling
  add_rectangle(&plan, {7, 3}, 1.0, 1.0, 0.0);  // pillar
  const VisibilityIndex index(plan);
  EXPECT_EQ(index.classify({2, 2}), EnvelopeStatus::ok);
  EXPECT_EQ(index.classify({7, 3}), EnvelopeStatus::inside_obstacle);
  EXPECT_EQ(index.classify({5, 0}), EnvelopeStatus::on_wall);
  EXPECT_EQ(index.classify({10, 8}), EnvelopeStatus::on_wall);     // on a vertex
  EXPECT_EQ(index.classify({6.5, 2.5}), EnvelopeStatus::on_wall);  // the pillar's corner
  EXPECT_EQ(index.classify({5.003, 7}), EnvelopeStatus::on_wall);  // inside the thickened stub
  EXPECT_EQ(index.classify({-1, 4}), EnvelopeStatus::outside);
  EXPECT_EQ(index.classify({11, 9}), EnvelopeStatus::outside);
  EXPECT_EQ(index.classify({std::nan(""), 1}), EnvelopeStatus::outside);
  for (const Vec& p : {Vec(5, 0), Vec(10, 8), Vec(7, 3), Vec(-1, 4)}) {
    const Envelope e = index.envelope(p);
    EXPECT_NE(e.status, EnvelopeStatus::ok);
    EXPECT_TRUE(e.polygon.empty());
    EXPECT_EQ(e.area, 0.0);
    const auto r = index.radial_function(p, 8);
    EXPECT_EQ(r, std::vector<double>(8, 0.0));
  }
  // A point in the corner region hidden by nothing sees the room minus the pillar's shadow.
  const Envelope e = index.envelope({1, 1});
  ASSERT_EQ(e.status, EnvelopeStatus::ok);
  EXPECT_NEAR(e.area / ray_cast_area(index.effective_segments(), {1, 1}, 40000), 1.0, 1e-3);

  FloorPlan empty;
  EXPECT_THROW(VisibilityIndex{empty}, Error);
  VisibilityOptions bad;
  bad.dangling_wall_thickness_m = 0.0;
  EXPECT_THROW(bad.check(), Error);
}

// ---- events against dense sampling of the visible vertex set.

double orient(const Vec& a, const Vec& b, const Vec& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

bool blocked(const std::vector<PlanSegment>& walls, const Vec& p, const Vec& v) {
  for (const auto& w : walls) {
    const double o1 = orient(p, v, w.a), o2 = orient(p, v, w.b);
    const double o3 = orient(w.a, w.b, p), o4 = orient(w.a, w.b, v);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  }
  return false;
}

std::vector<char> visible_set(const std::vector<PlanSegment>& walls, const std::vector<Vec>& vertices,
                              const Vec& p) {
  std::vector<char> out(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) out[i] = !blocked(walls, p, vertices[i]);
  return out;
}

TEST(Visibility, EventsMatchDenseSamplingOfVisibleVertices) {
  std::mt19937 rng(3);
  int total_events = 0;
  for (int plan_index = 0; plan_index < 3; ++plan_index) {
    const FloorPlan plan = random_plan(&rng, 4);
    const VisibilityIndex index(plan);
    const auto walls = index.effective_segments();
    const auto vertices = index.vertices();
    // A random path of 4 vertices in free space whose segments cross no wall.
    std::uniform_real_distribution<double> ux(0.5, 19.5), uy(0.5, 14.5);
    CameraPath path;
    while (path.frames.size() < 4) {
      const Vec p(ux(rng), uy(rng));
      if (index.classify(p) != EnvelopeStatus::ok) continue;
      if (!path.frames.empty()) {
        const Vec q = path.frames.back().position();
        if (blocked(walls, q, p)) continue;
        bool touches = false;
        for (const auto& w : walls)
          touches |= std::abs(orient(q, p, w.a)) < 1e-9 || std::abs(orient(q, p, w.b)) < 1e-9;
        if (touches) continue;
      }
      PathFrame f;
      f.index = static_cast<int>(path.frames.size());
      f.x = p.x();
      f.y = p.y();
      path.frames.push_back(f);
    }
    const VisibilityCells cells = index.cells_along_path(path);
    const auto s_at = path.arc_lengths();
    auto point_at = [&](double s) -> Vec {
      std::size_t i = 0;
      while (i + 2 < s_at.size() && s > s_at[i + 1]) ++i;
      const double t = (s - s_at[i]) / (s_at[i + 1] - s_at[i]);
      return path.frames[i].position() + t * (path.frames[i + 1].position() - path.frames[i].position());
    };
    const double step = 0.001;
    const int n = static_cast<int>(s_at.back() / step);
    std::vector<std::vector<char>> sets(n + 1);
    for (int k = 0; k <= n; ++k) sets[k] = visible_set(walls, vertices, point_at(k * step));
    // No missed event: every change between neighbouring samples has an event between them.
    for (int k = 0; k < n; ++k) {
      if (sets[k] == sets[k + 1]) continue;
      bool found = false;
      for (const auto& e : cells.events) found |= e.s >= k * step - 1e-9 && e.s <= (k + 1) * step + 1e-9;
      EXPECT_TRUE(found) << "plan " << plan_index << ": missed change at s = " << k * step;
    }
    // No extra event: each event changes the set across its sample interval (unless two share it).
    for (std::size_t i = 0; i < cells.events.size(); ++i) {
      const double s = cells.events[i].s;
      const int k = static_cast<int>(std::floor(s / step));
      if (k < 0 || k >= n) continue;
      bool shared = false;
      for (std::size_t j = 0; j < cells.events.size(); ++j)
        shared |= j != i && std::floor(cells.events[j].s / step) == k;
      if (shared) continue;
      EXPECT_NE(sets[k], sets[k + 1]) << "plan " << plan_index << ": extra event at s = " << s;
      // frame holds the path segment.
      const int f = cells.events[i].frame;
      EXPECT_LE(s_at[f], s + 1e-9);
      EXPECT_GE(s_at[f + 1], s - 1e-9);
    }
    total_events += static_cast<int>(cells.events.size());
    // Cells tile the path.
    ASSERT_EQ(cells.cells.size(), cells.events.size() + 1);
    EXPECT_DOUBLE_EQ(cells.cells.front().s_begin, 0.0);
    EXPECT_NEAR(cells.cells.back().s_end, s_at.back(), 1e-12);
    for (std::size_t c = 0; c < cells.cells.size(); ++c) {
      const auto& cell = cells.cells[c];
      EXPECT_NEAR(cell.length, cell.s_end - cell.s_begin, 1e-12);
      if (c > 0) {
        EXPECT_DOUBLE_EQ(cell.s_begin, cells.cells[c - 1].s_end);
      }
      const Vec mid = point_at(0.5 * (cell.s_begin + cell.s_end));
      EXPECT_NEAR(cell.area_mid / ray_cast_area(walls, mid, 20000), 1.0, 1e-3);
      EXPECT_GT(cell.area_mean, 0.0);
    }
    EXPECT_FALSE(cells.critical_lines.empty());
  }
  EXPECT_GT(total_events, 10);
}

TEST(Visibility, CellsAlongPathFramesAndWallCrossing) {
  FloorPlan plan;
  add_polygon(&plan, {{0, 0}, {10, 0}, {10, 4}, {0, 4}});
  add_wall(&plan, {5, 0}, {5, 4});  // two rooms
  const VisibilityIndex index(plan);
  CameraPath path;
  for (int i = 0; i <= 8; ++i) {
    PathFrame f;
    f.index = i;
    f.x = 1.0 + i;
    f.y = 2.0;
    path.frames.push_back(f);
  }
  const VisibilityCells cells = index.cells_along_path(path);
  // Two closed rooms: the only event is the wall crossing at x = 5 (s = 4).
  ASSERT_EQ(cells.events.size(), 1u);
  EXPECT_NEAR(cells.events[0].s, 4.0, 1e-12);
  EXPECT_EQ(cells.events[0].frame, 3);
  ASSERT_EQ(cells.cells.size(), 2u);
  EXPECT_EQ(cells.cells[0].first_frame, 0);
  EXPECT_EQ(cells.cells[0].last_frame, 3);
  EXPECT_EQ(cells.cells[1].first_frame, 4);
  EXPECT_EQ(cells.cells[1].last_frame, 8);
  EXPECT_NEAR(cells.cells[0].area_mid, 20.0, 1e-9);
  EXPECT_NEAR(cells.cells[1].area_mean, 20.0, 1e-9);
  EXPECT_TRUE(index.cells_along_path(CameraPath()).cells.empty());
}

}  // namespace
}  // namespace plenopath
