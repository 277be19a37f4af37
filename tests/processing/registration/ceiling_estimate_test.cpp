// The ceiling height from the tracker's points (registration's wall band ends under it). Truths: the heights
// the points were made at, by hand.
#include <gtest/gtest.h>

#include <random>

#include "processing/registration/registration_internal.h"

namespace plenopath {
namespace {

using registration_detail::estimate_ceiling;

// `n` points at height `above_floor` (+- `spread`), for a camera `camera` above the floor.
void add_band(std::vector<PathPoint>* points, int n, double above_floor, double spread, double camera,
              std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-spread, spread);
  for (int i = 0; i < n; ++i) {
    PathPoint p;
    p.position = {0.0, 0.0, above_floor + u(*rng) - camera};
    p.observations = 5;
    points->push_back(p);
  }
}

double ceiling_of(const std::vector<PathPoint>& points, double camera) {
  std::vector<const PathPoint*> ptrs;
  for (const PathPoint& p : points) ptrs.push_back(&p);
  RegistrationOptions options;
  options.camera_height_m = camera;
  return estimate_ceiling(ptrs, options);
}

TEST(CeilingEstimate, ATallHallIsNotCutAtItsDensestBand) {
  // A 7 m hall: walls textured from 1.8 to 3.4 m, a window transom crowd at 3.0 m denser than the ceiling's,
  // the ceiling at 7.0 m, a few strays between (beams, lights).
  std::mt19937 rng(3);
  std::vector<PathPoint> points;
  add_band(&points, 300, 2.6, 0.8, 1.6, &rng);
  add_band(&points, 90, 3.0, 0.03, 1.6, &rng);
  add_band(&points, 50, 6.95, 0.04, 1.6, &rng);
  for (double z = 3.6; z < 6.8; z += 0.35) add_band(&points, 1, z, 0.0, 1.6, &rng);
  EXPECT_NEAR(ceiling_of(points, 1.6), 6.95, 0.05);
}

TEST(CeilingEstimate, AnOfficeCeilingAndTheFallback) {
  std::mt19937 rng(4);
  std::vector<PathPoint> points;
  add_band(&points, 200, 1.8, 0.5, 1.5, &rng);   // walls up to 2.3 m
  add_band(&points, 100, 2.6, 0.03, 1.5, &rng);  // the ceiling
  EXPECT_NEAR(ceiling_of(points, 1.5), 2.6, 0.05);
  // Walls whose points thin out towards a plain ceiling: no crowd, so camera height + 1 m, not the top of
  // the walls' spread.
  std::vector<PathPoint> plain;
  for (int k = 0; k < 10; ++k) add_band(&plain, 60 - 5 * k, 1.75 + 0.1 * k, 0.05, 1.5, &rng);
  EXPECT_DOUBLE_EQ(ceiling_of(plain, 1.5), 2.5);
  // Too few points above the camera: camera height + 1 m.
  std::vector<PathPoint> few;
  add_band(&few, 20, 2.6, 0.03, 1.5, &rng);
  EXPECT_DOUBLE_EQ(ceiling_of(few, 1.5), 2.5);
}

}  // namespace
}  // namespace plenopath
