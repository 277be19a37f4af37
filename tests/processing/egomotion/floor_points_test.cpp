// The floor-level prior (floor_points.h, RefinementOptions::floor_sigma) on synthetic bundles with exact
// ground truth: a corridor with a floor, walls, a ceiling and tables, seen by a camera at 1.5 m; the
// starting values drift in scale as a monocular tracker's do.
#include "processing/egomotion/floor_points.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>

#include "model/camera_path.h"
#include "model/error.h"
#include "processing/egomotion/path_evaluation.h"
#include "tests/processing/egomotion/pose_errors.h"

namespace plenopath {
namespace {

constexpr double kCameraHeight = 1.5;

struct Corridor {
  std::vector<Eigen::Vector3d> truth_poses;
  std::vector<Eigen::Vector3d> truth_points;
  std::vector<char> on_floor;  // truth: the point is on the floor
  BundleProblem problem;       // starting values: the truth with a scale shrinking along the walk
};

// A 30 m corridor, 2.4 m wide (walls at y = +-1.2), 2.8 m high (floor at z = -1.5, ceiling at +1.3), with
// tables (tops at z = -0.75) along one wall. Poses every 0.1 m; each point seen from the poses within
// `sight` metres (short tracks make the scale weakly observable, as on plain walls); bearings with noise.
// The starting values shrink by `drift` per pose (positions of poses and points, and the points' heights,
// as a chain of shrinking steps would place them).
// `bob_m`: the camera's height rides up and down by this much (a sine over 37 poses, as a camera carried
// by hand), which the bundle's level camera centres cannot follow.
Corridor make_corridor(std::uint32_t seed, double drift, double sight = 1.6, double noise = 0.001,
                       int track_poses = 1000,  // track_poses: a point's track ends after that many
                       double bob_m = 0.0) {
  Corridor c;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const int poses = 300;
  for (int i = 0; i < poses; ++i) {
    const double x = 0.1 * i;
    c.truth_poses.emplace_back(x, 0.15 * std::sin(0.3 * x), 0.045 * std::cos(0.3 * x));
  }
  auto add = [&](const Eigen::Vector3d& p, bool floor) {
    c.truth_points.push_back(p);
    c.on_floor.push_back(floor);
  };
  for (int q = 0; q < 6000; ++q) {
    const double x = -1.0 + 32.0 * uniform(rng), kind = uniform(rng);
    if (kind < 0.35) {  // floor
      add({x, -1.2 + 2.4 * uniform(rng), -kCameraHeight}, true);
    } else if (kind < 0.75) {  // walls, floor to ceiling
      add({x, uniform(rng) < 0.5 ? -1.2 : 1.2, -kCameraHeight + 2.8 * uniform(rng)}, false);
    } else if (kind < 0.9) {  // ceiling
      add({x, -1.2 + 2.4 * uniform(rng), 1.3}, false);
    } else {  // table tops along the north wall
      add({x, 0.7 + 0.5 * uniform(rng), -0.75}, false);
    }
  }
  // Starting values: pose i's steps and everything first seen near it shrunk by exp(-drift i).
  std::vector<Eigen::Vector3d> start(c.truth_poses.size());
  start[0] = c.truth_poses[0];
  for (int i = 1; i < poses; ++i) {
    const Eigen::Vector3d step = c.truth_poses[i] - c.truth_poses[i - 1];
    start[i] = start[i - 1] + std::exp(-drift * i) * Eigen::Vector3d(step.x(), step.y(), 0.0);
    start[i].z() = c.truth_poses[i].z();
  }
  c.problem.poses = start;
  for (std::size_t q = 0; q < c.truth_points.size(); ++q) {
    const Eigen::Vector3d& p = c.truth_points[q];
    std::vector<BundleObservation> seen;
    for (int i = 0; i < poses; ++i) {
      const Eigen::Vector3d& pose = c.truth_poses[i];
      const Eigen::Vector3d d(p.x() - pose.x(), p.y() - pose.y(),
                              p.z() - bob_m * std::sin(2 * M_PI * i / 37));
      if (d.head<2>().norm() > sight) continue;
      if (!seen.empty() && i - seen.front().pose >= track_poses) break;
      const Eigen::Matrix3d world_from_camera =
          Eigen::AngleAxisd(pose.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::Vector3d b = (world_from_camera.transpose() * d).normalized() +
                                noise * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
      seen.emplace_back(i, static_cast<int>(c.problem.points.size()), b.normalized());
    }
    if (seen.size() < 3) continue;
    const int i = seen.front().pose;
    const double s = std::exp(-drift * i);
    const Eigen::Vector3d& pose = c.truth_poses[i];
    const Eigen::Vector3d offset = p - Eigen::Vector3d(pose.x(), pose.y(), 0.0);
    c.problem.points.push_back(Eigen::Vector3d(start[i].x(), start[i].y(), 0.0) + s * offset);
    c.problem.observations.insert(c.problem.observations.end(), seen.begin(), seen.end());
    c.truth_points[c.problem.points.size() - 1] = p;
    c.on_floor[c.problem.points.size() - 1] = c.on_floor[q];
  }
  c.truth_points.resize(c.problem.points.size());
  c.on_floor.resize(c.problem.points.size());
  return c;
}

// The floor is found on starting values whose scale halves along the walk: the table tops (half-way down)
// and the walls' foot are told from it by the level of their neighbours, not by one global level.
TEST(FloorPoints, FoundUnderAScaleThatHalvesAlongTheWalk) {
  const Corridor c = make_corridor(3, std::log(2.0) / 300);
  const std::vector<int> floor = find_floor_points(c.problem);
  int true_floor = 0, found_true = 0;
  for (char f : c.on_floor) true_floor += f;
  for (int q : floor) found_true += c.on_floor[static_cast<std::size_t>(q)];
  // The walls' lowest few centimetres are at the floor's level: they count as wrong here all the same.
  const double precision = double(found_true) / floor.size(), recall = double(found_true) / true_floor;
  std::printf("floor points: %zu found, precision %.3f, recall %.3f (of %d on the floor)\n", floor.size(),
              precision, recall, true_floor);
  EXPECT_GT(precision, 0.95);
  EXPECT_GT(recall, 0.6);  // the floor seen at less than 20 deg below the horizon is left out
}

// Tracks of four poses with 0.002 rad of noise (plain walls: corners lost after a few frames) see the
// scale only weakly: refined in windows from starting values that shrink by 30 % along the walk, the path
// keeps most of that drift, or makes its own. With the floor's points held to one level it cannot.
TEST(FloorPoints, TheFloorLevelTakesOutScaleDrift) {
  double ate[2] = {0, 0}, before = 0;
  for (int with_floor = 0; with_floor < 2; ++with_floor) {
    Corridor c = make_corridor(5, std::log(1 / 0.7) / 300, 1.6, 0.002, 4);
    before = pose_errors(c.problem.poses, c.truth_poses).ate_pct;
    RefinementOptions options;
    options.tilt_prior_deg = 0;
    if (with_floor) {
      c.problem.floor_points = find_floor_points(c.problem);
    } else {
      options.floor_sigma = 0;
    }
    refine_bundle(c.problem, options);
    const PathErrors e = pose_errors(c.problem.poses, c.truth_poses);
    ate[with_floor] = e.ate_pct;
    std::printf("%s: ATE %.4f %% (before %.3f %%), heading RMS %.4f deg\n",
                with_floor ? "floor level" : "no floor", e.ate_pct, before, e.rot_rms_deg);
  }
  EXPECT_LT(ate[1], 0.15);  // seen: 0.058 %; 1.106 % without
  EXPECT_LT(ate[1], ate[0] / 5);
}

// The path's error (ATE % of its length) and the floor prior's spread used, refined from starting values
// that shrink by 30 % along the walk (tracks of 12 poses), with the floor prior narrowed by the data or not.
struct FloorRun {
  double ate_pct = 0.0, spread_used = 0.0;
};
FloorRun refine_corridor(double bob_m, bool from_data) {
  Corridor c = make_corridor(5, std::log(1 / 0.7) / 300, 1.6, 0.002, 12, bob_m);
  c.problem.floor_points = find_floor_points(c.problem);
  RefinementOptions options;
  options.tilt_prior_deg = 0;
  if (!from_data) options.floor_sigma_from_data = 0;
  const RefinementReport report = refine_bundle(c.problem, options);
  return {pose_errors(c.problem.poses, c.truth_poses).ate_pct, report.floor_sigma_used};
}

// A level camera over a flat floor: the floor points the first pass finds agree far better than the 1 %
// the prior starts with, and the global passes hold them to that; the path is better for it (seen: ATE
// 0.0064 -> 0.0047 %, spread 0.20 %). A camera that rides up and down by 3 cm (2 % of its height) shows a
// wider spread, so its prior stays wider, and its path is no worse (seen: 0.36 -> 0.22 % at 0.34 %).
TEST(FloorPoints, ThePriorNarrowsToTheSpreadTheFloorShows) {
  const FloorRun level_fixed = refine_corridor(0.0, false), level = refine_corridor(0.0, true);
  std::printf("level camera: ATE %.4f %% at 1 %%, %.4f %% at the floor's spread %.3f %%\n",
              level_fixed.ate_pct, level.ate_pct, 100 * level.spread_used);
  EXPECT_DOUBLE_EQ(level_fixed.spread_used, 0.01);
  EXPECT_LT(level.spread_used, 0.003);
  EXPECT_LT(level.ate_pct, level_fixed.ate_pct);
  const FloorRun bob_fixed = refine_corridor(0.03, false), bob = refine_corridor(0.03, true);
  std::printf("camera riding 3 cm up and down: ATE %.4f %% at 1 %%, %.4f %% at %.3f %%\n", bob_fixed.ate_pct,
              bob.ate_pct, 100 * bob.spread_used);
  EXPECT_GT(bob.spread_used, 1.5 * level.spread_used);
  EXPECT_LT(bob.ate_pct, bob_fixed.ate_pct);
}

// Hand-made depths below a camera at 1.6 m: a small office whose desk tops (0.72 m high: 0.88 m down) hold
// more points than its floor; a few stray points deeper than the floor, too few to be a level. Desks only
// (the floor hidden): the desks' level, the deepest there is.
TEST(FloorPoints, TheFloorIsTheDeepestCrowdedLevelNotTheMostCrowded) {
  std::mt19937 rng(11);
  std::normal_distribution<double> spread(0.0, 0.005);
  std::vector<double> depths;
  for (int k = 0; k < 150; ++k) depths.push_back(0.88 * (1 + spread(rng)));  // desk tops
  for (int k = 0; k < 80; ++k) depths.push_back(1.60 * (1 + spread(rng)));   // floor
  for (double d : {2.1, 2.9, 3.7, 4.4, 6.0}) depths.push_back(d);            // stray
  EXPECT_NEAR(floor_depth(depths), 1.60, 0.01);
  const std::vector<double> desks_only(depths.begin(), depths.begin() + 150);
  EXPECT_NEAR(floor_depth(desks_only), 0.88, 0.01);
  EXPECT_EQ(floor_depth({}), 0.0);
}

// What stands on the floor a few cm high (a shelf's bottom board 7 cm up, skirting and cables 4 cm) shares
// the floor's 4 % bins: the level is narrowed to the floor itself. The three bins' median alone gave 1.578
// (1.4 % short, as the metric scale would be).
TEST(FloorPoints, ThingsAFewCentimetresOffTheFloorDoNotRaiseIt) {
  std::mt19937 rng(5);
  std::normal_distribution<double> spread(0.0, 0.004);
  std::vector<double> depths;
  for (int k = 0; k < 100; ++k) depths.push_back(1.60 * (1 + spread(rng)));  // floor
  for (int k = 0; k < 60; ++k) depths.push_back(1.53 * (1 + spread(rng)));   // shelf bottoms
  for (int k = 0; k < 40; ++k) depths.push_back(1.56 * (1 + spread(rng)));   // skirting, cables
  EXPECT_NEAR(floor_depth(depths), 1.60, 0.003);
}

// Hand-computed: a point at (0.5, 0.5, 0) seen from (0, 0) looking along +x and from (1, 0) turned by
// 90 deg: plan rays at 45 and 135 deg, 90 deg apart. A point seen once spans nothing.
TEST(FloorPoints, ParallaxIsTheAngleTheRaysSpanInThePlanFrame) {
  BundleProblem problem;
  problem.poses = {{0, 0, 0}, {1, 0, M_PI / 2}};
  problem.points = {{0.5, 0.5, 0}, {3, 0, 0}};
  const Eigen::Vector3d from_a = Eigen::Vector3d(0.5, 0.5, 0).normalized();
  const Eigen::Vector3d from_b = Eigen::Vector3d(0.5, 0.5, 0).normalized();  // (-0.5, 0.5) turned by -90
  problem.observations = {{0, 0, from_a}, {1, 0, from_b}, {0, 1, Eigen::Vector3d::UnitX()}};
  const std::vector<float> parallax = point_parallax(problem);
  ASSERT_EQ(parallax.size(), 2u);
  EXPECT_NEAR(parallax[0], M_PI / 2, 1e-6);
  EXPECT_EQ(parallax[1], 0.0f);
}

// The POV-Ray corridor's trap: the trolley and its operator ride with the camera, so their rays stay put and
// the bundle places them anywhere along them, far below the floor; there were more of them than floor
// points, and the scale came out 14x too small. Truth: the camera 1.5 m over the floor (1 unit below the
// poses), so 1.5 m per unit.
TEST(FloorPoints, TheRigRidingWithTheCameraIsNotTheFloor) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.002);
  BundleProblem problem;
  for (int i = 0; i < 200; ++i) problem.poses.emplace_back(0.1 * i, 0.0, 0.0);
  auto observe = [&](int pose, const Eigen::Vector3d& camera_bearing) {
    const Eigen::Vector3d noisy =
        (camera_bearing.normalized() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng))).normalized();
    problem.observations.emplace_back(pose, static_cast<int>(problem.points.size()) - 1, noisy);
  };
  std::vector<double> steep_depths;  // every steep point's depth, the rig's too
  for (int q = 0; q < 150; ++q) {    // floor points, seen from within 1.5 units
    const Eigen::Vector3d p(20.0 * uniform(rng), -1.0 + 2.0 * uniform(rng), -1.0);
    problem.points.push_back(p);
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d d = p - problem.poses[i];
      if (d.head<2>().norm() < 1.5) observe(i, Eigen::Vector3d(d.x(), d.y(), p.z()));
    }
    steep_depths.push_back(1.0);
  }
  for (int q = 0; q < 300; ++q) {  // the rig: a fixed camera-frame bearing 40-80 deg down, for 30 poses
    const double azimuth = 2 * M_PI * uniform(rng), depression = (40 + 40 * uniform(rng)) * M_PI / 180;
    const Eigen::Vector3d b(std::cos(depression) * std::cos(azimuth),
                            std::cos(depression) * std::sin(azimuth), -std::sin(depression));
    const int first = static_cast<int>(170 * uniform(rng));
    problem.points.push_back(problem.poses[first + 15] + (20.0 * (1 + 0.01 * noise(rng)) / -b.z()) * b);
    for (int i = first; i < first + 30; ++i) observe(i, b);
    steep_depths.push_back(-problem.points.back().z());
  }
  ASSERT_NEAR(floor_depth(steep_depths), 20.0, 0.5);  // the trap is set: depth alone picks the rig
  int floor_points = 0;
  EXPECT_NEAR(scale_from_camera_height(problem, 1.5, &floor_points), 1.5, 0.01);
  EXPECT_GE(floor_points, 100);
}

TEST(FloorPoints, OptionsAreChecked) {
  FloorPointOptions o;
  o.min_depression_deg = 90;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.max_level_deviation = 0;
  EXPECT_THROW(o.check(), Error);
  RefinementOptions r;
  r.floor_sigma = -0.01;
  EXPECT_THROW(r.check(), Error);
  r = {};
  r.floor_sigma_from_data = -1;
  EXPECT_THROW(r.check(), Error);
  r = {};
  r.floor_sigma_min = 0;
  EXPECT_THROW(r.check(), Error);
}

// The step from b's pose to a's measured on the floor: camera-frame bearings of floor points (z = -level),
// of points on the walls and a table (not on the floor, a minority), and of the trolley and its operator
// (fixed in the camera's frame: they turn with it). Truth: the poses the bearings were made from.
TEST(FloorStep, MeasuresTheStepFromTheFloorAlone) {
  const double level = 1.5;
  const Eigen::Vector3d a(2.0, 1.0, 0.3), b(2.0 + 0.31 * std::cos(0.5), 1.0 + 0.31 * std::sin(0.5), 0.62);
  auto camera_bearing = [](const Eigen::Vector3d& pose, const Eigen::Vector3d& point) {
    const Eigen::Vector3d d = point - Eigen::Vector3d(pose.x(), pose.y(), 0.0);
    return (Eigen::AngleAxisd(-pose.z(), Eigen::Vector3d::UnitZ()) * d).normalized().eval();
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.0005);  // about a tenth of a pixel at 1024 wide
  auto noisy = [&](Eigen::Vector3d v) {
    v += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    return v.normalized().eval();
  };
  std::vector<Eigen::Vector3d> from_a, from_b;
  for (int k = 0; k < 60; ++k) {  // the floor, 1-3 m around the cameras
    const double angle = M_PI * u(rng), distance = 2.0 + u(rng);
    const Eigen::Vector3d p(a.x() + distance * std::cos(angle), a.y() + distance * std::sin(angle), -level);
    from_a.push_back(noisy(camera_bearing(a, p)));
    from_b.push_back(noisy(camera_bearing(b, p)));
  }
  for (int k = 0; k < 15; ++k) {  // wall bases and a table top, seen steeply too
    const Eigen::Vector3d p(a.x() + 1.2 + 0.5 * u(rng), a.y() + u(rng), -0.75 + 0.3 * u(rng));
    from_a.push_back(noisy(camera_bearing(a, p)));
    from_b.push_back(noisy(camera_bearing(b, p)));
  }
  for (int k = 0; k < 70; ++k) {  // the trolley and the operator: the same bearing from both
    const Eigen::Vector3d rig = Eigen::Vector3d(u(rng), u(rng), -1.0 - 0.4 * std::abs(u(rng))).normalized();
    from_a.push_back(noisy(rig));
    from_b.push_back(noisy(rig));
  }
  for (int k = 0; k < 30; ++k) {  // the ceiling and far walls: not seen steeply down, not used
    const Eigen::Vector3d p(a.x() + 4 * u(rng), a.y() + 4 * u(rng), 1.3);
    from_a.push_back(noisy(camera_bearing(a, p)));
    from_b.push_back(noisy(camera_bearing(b, p)));
  }
  FloorStepInput in;
  in.bearings_a = &from_a;
  in.bearings_b = &from_b;
  in.heading_a = a.z();
  in.heading_b = b.z();
  in.level = level;
  in.direction = Eigen::Vector2d(std::cos(0.5), std::sin(0.5));
  const double deg = M_PI / 180.0, pixel = 2 * M_PI / 1024;
  const FloorStep step = floor_step(in, 25 * deg, 3 * pixel);
  EXPECT_NEAR(step.length, 0.31, 0.003);  // 1 %
  EXPECT_GE(step.points, 50);             // the floor's, less those seen under 25 deg
  EXPECT_LE(step.points, 75);             // never the rig's (70 more)
  EXPECT_LT(step.spread, 0.05);
  // In another unit (the chaining's): the step scales with the level.
  in.level = 3.0;
  EXPECT_NEAR(floor_step(in, 25 * deg, 3 * pixel).length, 0.62, 0.006);
  // Nothing seen steeply down: no step.
  const std::vector<Eigen::Vector3d> level_only(5, Eigen::Vector3d::UnitX());
  in.bearings_a = in.bearings_b = &level_only;
  const FloorStep none = floor_step(in, 25 * deg, 3 * pixel);
  EXPECT_EQ(none.points, 0);
  EXPECT_EQ(none.length, 0.0);
}

}  // namespace
}  // namespace plenopath
