// Registration on the plan from synthetic points (fast; synthetic_walls.h): the registration must find the
// known similarity again with no initial guess.
#include "processing/registration/registration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/error.h"
#include "tests/processing/registration/synthetic_walls.h"

namespace plenopath {
namespace {

constexpr double kDeg = M_PI / 180.0;
using test::symmetric_room;
using test::synthesise;
using test::SyntheticPiece;
using test::wall;

// An L-shaped building: three rooms off a corridor, doorways, one pillar. No symmetry.
FloorPlan l_building() {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  wall(&plan, {0, 0}, {14, 0});
  wall(&plan, {14, 0}, {14, 5});
  wall(&plan, {14, 5}, {6, 5});
  wall(&plan, {6, 5}, {6, 12});
  wall(&plan, {6, 12}, {0, 12});
  wall(&plan, {0, 12}, {0, 0});
  // Corridor y in [0, 2] along the bottom; rooms above it with doorways.
  wall(&plan, {0, 2}, {1.0, 2});
  wall(&plan, {1.9, 2}, {9, 2});
  wall(&plan, {9.9, 2}, {14, 2});
  wall(&plan, {3.5, 2}, {3.5, 12});  // left rooms split
  wall(&plan, {0, 7}, {3.5, 7});
  wall(&plan, {10, 2}, {10, 5});
  // Pillar in the corridor.
  wall(&plan, {7.0, 0.8}, {7.3, 0.8});
  wall(&plan, {7.3, 0.8}, {7.3, 1.1});
  wall(&plan, {7.3, 1.1}, {7.0, 1.1});
  wall(&plan, {7.0, 1.1}, {7.0, 0.8});
  return plan;
}

std::vector<Eigen::Vector2d> corridor_walk() {
  std::vector<Eigen::Vector2d> walk;
  for (double x = 0.8; x < 13.2; x += 0.1) walk.push_back({x, 1.0 + 0.3 * std::sin(x)});
  for (double y = 2.3; y < 6.5; y += 0.1) walk.push_back({1.45, y});  // into the lower-left room
  return walk;
}

double position_error(const Similarity2& found, const Similarity2& truth, const CameraPath& path) {
  double sum = 0;
  for (const PathFrame& f : path.frames)
    sum += (found.apply(f.position()) - truth.apply(f.position())).squaredNorm();
  return std::sqrt(sum / path.size());
}

TEST(Registration, RecoversAKnownSimilarityFromNoisyWallPoints) {
  const FloorPlan plan = l_building();
  Similarity2 truth;
  truth.rotation = 127.3 * kDeg;
  truth.scale = 1.012;  // the tracker's metres 1.2 % short
  truth.translation = {4.2, -7.9};
  const SyntheticPiece piece = synthesise(plan, corridor_walk(), truth, 5);
  RegistrationOptions options;
  const RegistrationResult r = register_on_plan(piece.path, piece.points, plan, options);
  ASSERT_EQ(r.pieces.size(), 1u);
  const PieceRegistration& p = r.pieces[0];
  ASSERT_TRUE(p.ok) << p.message;
  ASSERT_FALSE(p.candidates.empty());
  const RegistrationCandidate& best = p.candidates[0];
  std::printf("%s\n", describe(p).c_str());
  EXPECT_NEAR(std::remainder(best.transform.rotation - truth.rotation, 2 * M_PI), 0.0, 0.05 * kDeg);
  EXPECT_NEAR(best.transform.scale, truth.scale, 0.002);
  EXPECT_LT(position_error(best.transform, truth, piece.path), 0.01);
  EXPECT_GT(best.wall_share, 0.5);
  EXPECT_DOUBLE_EQ(best.free_share, 1.0);
  // The walk places no frame off free space, so the candidates after it are clearly worse.
  if (p.candidates.size() > 1) {
    EXPECT_GT(p.ambiguity_ratio(), 1.3);
  }

  // Applied: every frame lands where the truth puts it, headings turned by the rotation.
  const CameraPath placed = apply_registration(piece.path, r);
  for (std::size_t i = 0; i < placed.size(); i += 17) {
    const Eigen::Vector2d want = truth.apply(piece.path.frames[i].position());
    EXPECT_LT((placed.frames[i].position() - want).norm(), 0.02) << i;
    EXPECT_NEAR(std::remainder(placed.frames[i].heading - truth.rotation, 2 * M_PI), 0.0, 0.1 * kDeg);
  }
}

// A gallery hall: walls drawn as closed outlines 0.3 m thick, four 2 m windows drawn as gaps in the south
// wall, a row of square columns. Open to the outside through its windows, yet the hall is free space and
// the walls' bodies and the columns are not.
TEST(Registration, AHallWithWindowGapsIsFreeSpaceAndItsWallBodiesAreNot) {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  auto outline = [&](const std::vector<Eigen::Vector2d>& c) {
    for (std::size_t k = 0; k < c.size(); ++k) wall(&plan, c[k], c[(k + 1) % c.size()]);
  };
  for (double x0 : {-0.15, 3.0, 6.5, 10.0})  // south wall pieces between windows x 1.0-3.0, 4.5-6.5, ...
    outline({{x0, -0.15},
             {x0 == -0.15 ? 1.0 : x0 + 1.5, -0.15},
             {x0 == -0.15 ? 1.0 : x0 + 1.5, 0.15},
             {x0, 0.15}});
  outline({{11.5, -0.15}, {14.15, -0.15}, {14.15, 0.15}, {11.5, 0.15}});
  outline({{13.85, -0.15}, {14.15, -0.15}, {14.15, 8.15}, {13.85, 8.15}});
  outline({{-0.15, 7.85}, {14.15, 7.85}, {14.15, 8.15}, {-0.15, 8.15}});
  outline({{-0.15, -0.15}, {0.15, -0.15}, {0.15, 8.15}, {-0.15, 8.15}});
  for (double x : {3.5, 7.0, 10.5})
    outline({{x - 0.25, 3.75}, {x + 0.25, 3.75}, {x + 0.25, 4.25}, {x - 0.25, 4.25}});
  std::vector<Eigen::Vector2d> walk;  // round the columns
  for (double x = 1.5; x < 12.5; x += 0.1) walk.push_back({x, 2.0 + 0.2 * std::sin(x)});
  for (double y = 2.0; y < 6.0; y += 0.1) walk.push_back({12.5, y});
  for (double x = 12.5; x > 1.5; x -= 0.1) walk.push_back({x, 6.0});
  Similarity2 truth;
  truth.rotation = -71.0 * kDeg;
  truth.scale = 0.985;
  truth.translation = {-3.0, 12.0};
  const SyntheticPiece piece = synthesise(plan, walk, truth, 21);
  const RegistrationResult r = register_on_plan(piece.path, piece.points, plan);
  ASSERT_EQ(r.pieces.size(), 1u);
  const PieceRegistration& p = r.pieces[0];
  ASSERT_TRUE(p.ok) << p.message;
  std::printf("%s\n", describe(p).c_str());
  const RegistrationCandidate& best = p.candidates[0];
  EXPECT_DOUBLE_EQ(best.free_share, 1.0);
  EXPECT_LT(position_error(best.transform, truth, piece.path), 0.02);
  EXPECT_NEAR(std::remainder(best.transform.rotation - truth.rotation, 2 * M_PI), 0.0, 0.1 * kDeg);
}

TEST(Registration, ASymmetricRoomGivesTwoNearEqualCandidatesAndOneAnchorPicks) {
  const FloorPlan plan = symmetric_room();
  std::vector<Eigen::Vector2d> walk;
  for (double x = 1.0; x < 9.0; x += 0.1) walk.push_back({x, 3.0 + 0.8 * std::sin(x * 0.9)});
  Similarity2 truth;
  truth.rotation = -33 * kDeg;
  truth.translation = {-2.0, 5.0};
  const SyntheticPiece piece = synthesise(plan, walk, truth, 9);
  const RegistrationResult r = register_on_plan(piece.path, piece.points, plan);
  ASSERT_EQ(r.pieces.size(), 1u);
  const PieceRegistration& p = r.pieces[0];
  ASSERT_TRUE(p.ok) << p.message;
  ASSERT_GE(p.candidates.size(), 2u);
  std::printf("%s\n", describe(p).c_str());
  EXPECT_LT(p.ambiguity_ratio(), 1.1) << "the half turn fits as well";
  // The two: the truth and the truth turned by 180 deg about the room's centre.
  Similarity2 turned = truth;
  turned.rotation = truth.rotation + M_PI;
  turned.translation = Eigen::Vector2d(10, 6) - truth.translation;
  int matched_truth = -1, matched_turned = -1;
  for (int c = 0; c < 2; ++c) {
    const Similarity2& t = p.candidates[static_cast<std::size_t>(c)].transform;
    if (position_error(t, truth, piece.path) < 0.03) matched_truth = c;
    if (position_error(t, turned, piece.path) < 0.03) matched_turned = c;
  }
  ASSERT_GE(matched_truth, 0);
  ASSERT_GE(matched_turned, 0);
  // One anchor (frame 10 at its true place) decides.
  Anchors anchors = {{10, truth.apply(piece.path.frames[10].position()), std::nullopt}};
  EXPECT_EQ(candidate_for_anchors(piece.path, p, anchors), matched_truth);
  anchors[0].position = turned.apply(piece.path.frames[10].position());
  EXPECT_EQ(candidate_for_anchors(piece.path, p, anchors), matched_turned);
}

// A walk down a long plain corridor: its two long walls hold the placement across it and say nothing along
// it; only the door jambs do (a few points each, 2 cm of noise): in one of these six placements the points
// themselves score best 6 cm along the corridor from the truth, and the refinement from the truth goes
// there too. Wherever the coarse search's cells fall, the placement must not settle further off, nor
// let the scale take up a shift (registration_povray_test.cpp has the walk that did).
TEST(Registration, ACorridorWalkLandsWhereItBelongsAlongTheCorridor) {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  // Corridor y in [0, 2.2], x in [0, 32]; 0.9 m doorways every 6 m, alternating sides.
  std::vector<double> south = {0.0}, north = {0.0};
  for (double x = 4.0; x < 30; x += 6.0) {
    std::vector<double>& side = (static_cast<int>(x) / 6) % 2 ? north : south;
    side.push_back(x);
    side.push_back(x + 0.9);
  }
  south.push_back(32.0);
  north.push_back(32.0);
  for (std::size_t k = 0; k + 1 < south.size(); k += 2) wall(&plan, {south[k], 0.0}, {south[k + 1], 0.0});
  for (std::size_t k = 0; k + 1 < north.size(); k += 2) wall(&plan, {north[k], 2.2}, {north[k + 1], 2.2});
  wall(&plan, {0, 0}, {0, 2.2});
  wall(&plan, {32, 0}, {32, 2.2});
  std::vector<Eigen::Vector2d> walk;
  for (double x = 6.0; x < 26.0; x += 0.15) walk.push_back({x, 1.1 + 0.05 * std::sin(0.7 * x)});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    Similarity2 truth;
    truth.rotation = (360 * unit(rng) - 180) * kDeg;
    truth.scale = 0.995 + 0.01 * unit(rng);
    truth.translation = {20 * unit(rng) - 10, 20 * unit(rng) - 10};
    const SyntheticPiece piece = synthesise(plan, walk, truth, 40 + static_cast<std::uint32_t>(trial));
    const RegistrationResult r = register_on_plan(piece.path, piece.points, plan);
    ASSERT_EQ(r.pieces.size(), 1u);
    const PieceRegistration& p = r.pieces[0];
    ASSERT_TRUE(p.ok) << trial << ": " << p.message;
    const RegistrationCandidate& best = p.candidates[0];
    std::printf("trial %d: %s; %.3f m off\n", trial, describe(p).c_str(),
                position_error(best.transform, truth, piece.path));
    EXPECT_LT(position_error(best.transform, truth, piece.path), 0.08) << trial;
    EXPECT_NEAR(best.transform.scale, truth.scale, 0.002) << trial;
  }
}

// Two rooms side by side under a corridor: A (6 m deep, a door to the corridor) and B (4 m, none), sharing
// the wall x = 6. The walk stays in A near that wall. Points on walls alone prefer a wrong placement: moved
// 4 m into B, the shared wall lands on B's far wall, a shelf front 2 m from A's far wall on the shared wall,
// and the corridor wall seen through A's door on the corridor wall (607 points on walls against the truth's
// 557). But A's far wall and the corridor are then seen through walls. Turned round (in A or into B) the
// corridor is seen through the outer wall. What was seen through walls tells the truth apart (the POV-Ray
// gap walk's first room was placed turned round in its neighbour without it).
TEST(Registration, ARoomIsToldFromItsLookAlikeByWhatWasSeenThroughWalls) {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  wall(&plan, {0, 0}, {10, 0});
  wall(&plan, {10, 0}, {10, 7});
  wall(&plan, {10, 7}, {0, 7});
  wall(&plan, {0, 7}, {0, 0});
  wall(&plan, {6, 0}, {6, 5});
  wall(&plan, {0, 5}, {4, 5});  // A's door: x in [4, 5]
  wall(&plan, {5, 5}, {10, 5});
  CameraPath path;
  for (int i = 0; i <= 40; ++i) {
    PathFrame f;
    f.index = i;
    f.x = 3.5 + 0.05 * i;
    f.y = 2.5 + 0.3 * std::sin(0.2 * i);
    path.frames.push_back(f);
  }
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<PathPoint> points;
  auto line = [&](Eigen::Vector2d a, Eigen::Vector2d b, int count) {
    for (int k = 0; k < count; ++k) {
      PathPoint p;
      const Eigen::Vector2d q = a + (b - a) * (k + 0.5) / count + Eigen::Vector2d(noise(rng), noise(rng));
      p.position = {q.x(), q.y(), -0.5};
      p.observations = 5;
      p.frame = static_cast<int>(rng() % path.frames.size());  // seen from somewhere along the walk
      points.push_back(p);
    }
  };
  line({6, 0.2}, {6, 4.8}, 230);  // the shared wall
  line({3, 0}, {6, 0}, 100);      // A's side walls near the walk
  line({3, 5}, {4, 5}, 33);
  line({5, 5}, {6, 5}, 34);
  line({2, 1}, {2, 4}, 150);      // a shelf front, not on the plan
  line({0, 0.5}, {0, 4.5}, 100);  // A's far wall
  line({4.1, 7}, {4.9, 7}, 60);   // the corridor wall, through the door
  const double n = static_cast<double>(points.size());
  const Eigen::Vector2d start = path.frames.front().position();  // the truth: the identity

  RegistrationOptions walls_only;
  walls_only.seen_through_weight = 0;
  const RegistrationResult before = register_on_plan(path, points, plan, walls_only);
  ASSERT_TRUE(before.pieces.at(0).ok) << before.pieces[0].message;
  std::printf("points on walls only: %s\n", describe(before.pieces[0]).c_str());
  EXPECT_GT((before.pieces[0].candidates.front().transform.apply(start) - start).norm(), 1.0);

  const RegistrationResult r = register_on_plan(path, points, plan);
  const PieceRegistration& p = r.pieces.at(0);
  ASSERT_TRUE(p.ok) << p.message;
  std::printf("with what was seen through walls: %s\n", describe(p).c_str());
  const RegistrationCandidate& best = p.candidates.front();
  EXPECT_LT((best.transform.apply(start) - start).norm(), 0.02);
  EXPECT_NEAR(std::remainder(best.transform.rotation, 2 * M_PI), 0.0, 0.2 * kDeg);
  EXPECT_LT(best.through_share, 0.01);
  // Moved into B: A's far wall and the corridor (160 points) are seen through walls.
  bool moved_offered = false;
  for (const RegistrationCandidate& c : p.candidates)
    if ((c.transform.apply(start) - (start + Eigen::Vector2d(4, 0))).norm() < 0.05) {
      moved_offered = true;
      EXPECT_NEAR(c.through_share, 160 / n, 0.01);
      EXPECT_LT(c.score, 0.9 * best.score);
    }
  EXPECT_TRUE(moved_offered);
}

// Frames the tracker bridged (held where no image placed them: the gap walk's camera inside a wall) say
// nothing of where the piece lies: the free-space share counts the others.
TEST(Registration, BridgedFramesAreNoEvidenceOfFreeSpace) {
  const FloorPlan plan = l_building();
  SyntheticPiece piece = synthesise(plan, corridor_walk(), Similarity2{}, 4);
  const PathFrame last = piece.path.frames.back();
  for (int i = 1; i <= 30; ++i) {  // held 3 m outside the building, as inside a thick wall
    PathFrame f = last;
    f.index = last.index + i;
    f.x = -3.0;
    f.flags = kFrameBridged;
    piece.path.frames.push_back(f);
  }
  const RegistrationResult r = register_on_plan(piece.path, piece.points, plan);
  ASSERT_TRUE(r.pieces.at(0).ok) << r.pieces[0].message;
  const RegistrationCandidate& best = r.pieces[0].candidates.front();
  EXPECT_DOUBLE_EQ(best.free_share, 1.0);
  EXPECT_LT((best.transform.apply(last.position()) - last.position()).norm(), 0.02);
}

TEST(Registration, APlanWithoutSightBlockingSegmentsIsAClearError) {
  FloorPlan plan = l_building();
  plan.source_file = "/tmp/empty_walls.dxf";
  for (PlanSegment& s : plan.segments) s.occluder = false;
  const SyntheticPiece piece = synthesise(l_building(), corridor_walk(), Similarity2{}, 1);
  try {
    register_on_plan(piece.path, piece.points, plan);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/tmp/empty_walls.dxf"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no sight-blocking segments"), std::string::npos) << e.what();
  }
}

TEST(Registration, PointsFromAnotherBuildingFitNowhere) {
  // Points of the L building's walk registered on a plan of a round hall (no straight wall longer than
  // 2.4 m): the best candidate is reported with its figures and the piece is not placed.
  FloorPlan hall;
  hall.layers = {{"WALLS", 7, true, true, 0}};
  const int sides = 24;
  for (int i = 0; i < sides; ++i) {
    const double a0 = 2 * M_PI * i / sides, a1 = 2 * M_PI * (i + 1) / sides;
    wall(&hall, {9 * std::cos(a0), 9 * std::sin(a0)}, {9 * std::cos(a1), 9 * std::sin(a1)});
  }
  const SyntheticPiece piece = synthesise(l_building(), corridor_walk(), Similarity2{}, 2);
  const RegistrationResult r = register_on_plan(piece.path, piece.points, hall);
  ASSERT_EQ(r.pieces.size(), 1u);
  EXPECT_FALSE(r.pieces[0].ok);
  EXPECT_FALSE(r.all_ok());
  EXPECT_EQ(r.pieces[0].message.rfind("no placement fits: best candidate has ", 0), 0u)
      << r.pieces[0].message;
  EXPECT_NE(r.pieces[0].message.find("% of wall points on walls"), std::string::npos);
  // Nothing applied to a piece that did not fit.
  const CameraPath same = apply_registration(piece.path, r);
  EXPECT_EQ(same, piece.path);
}

TEST(Registration, APathFarLargerThanThePlanIsRefusedWithItsSpan) {
  // A tracker that lost its scale (seen: a path 380 000 % too long) hands over a path kilometres long for
  // a 12 m building: refused at once with both spans, never searched (the search's rasters are sized by
  // the path: that one asked for 13 TB).
  SyntheticPiece piece = synthesise(l_building(), corridor_walk(), Similarity2{}, 3);
  for (PathFrame& f : piece.path.frames) {
    f.x *= 1000;
    f.y *= 1000;
  }
  for (PathPoint& p : piece.points) p.position.head<2>() *= 1000;  // heights stay metric (camera height)
  const RegistrationResult r = register_on_plan(piece.path, piece.points, l_building());
  ASSERT_EQ(r.pieces.size(), 1u);
  EXPECT_FALSE(r.pieces[0].ok);
  EXPECT_EQ(r.pieces[0].message.rfind("no placement fits: the path spans ", 0), 0u) << r.pieces[0].message;
  EXPECT_NE(r.pieces[0].message.find("is the metric scale right"), std::string::npos);
  EXPECT_EQ(apply_registration(piece.path, r), piece.path);
}

TEST(Registration, TwoPiecesAreRegisteredEachOnItsOwn) {
  const FloorPlan plan = l_building();
  std::vector<Eigen::Vector2d> first, second;
  for (double x = 0.8; x < 6.5; x += 0.1) first.push_back({x, 1.0});
  for (double y = 7.5; y < 11.5; y += 0.1) second.push_back({1.7 + 0.2 * std::sin(y), y});  // upper-left room
  Similarity2 t0, t1;
  t0.rotation = 0.0;  // piece 0 as the tracker leaves it: first frame at the origin
  t0.translation = {0.8, 1.0};
  t1.rotation = 71 * kDeg;
  t1.translation = {1.9, 7.5};
  const SyntheticPiece a = synthesise(plan, first, t0, 3), b = synthesise(plan, second, t1, 4);
  CameraPath path = a.path;
  path.pieces = {
      PathPiece{0, static_cast<int>(a.path.size()) - 1, true, "camera_height", 1.0, ""},
      PathPiece{static_cast<int>(a.path.size()), static_cast<int>(a.path.size() + b.path.size()) - 1, false,
                "camera_height", 1.0, "no tracks"}};
  std::vector<PathPoint> points = a.points;
  for (PathFrame f : b.path.frames) {
    f.index += static_cast<int>(a.path.size());
    f.piece = 1;
    path.frames.push_back(f);
  }
  for (PathPoint p : b.points) {
    p.piece = 1;
    points.push_back(p);
  }
  const RegistrationResult r = register_on_plan(path, points, plan);
  ASSERT_EQ(r.pieces.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const PieceRegistration& p = r.pieces[static_cast<std::size_t>(k)];
    ASSERT_TRUE(p.ok) << k << ": " << p.message;
    std::printf("%s\n", describe(p).c_str());
    const Similarity2& want = k == 0 ? t0 : t1;
    const CameraPath own = path.piece_path(k);
    EXPECT_LT(position_error(p.candidates[0].transform, want, own), 0.02) << k;
    EXPECT_NEAR(std::remainder(p.candidates[0].transform.rotation - want.rotation, 2 * M_PI), 0.0,
                0.1 * kDeg);
  }
  std::vector<PathPoint> moved = points;
  const CameraPath placed = apply_registration(path, r, {}, &moved);
  EXPECT_TRUE(placed.pieces[1].placed);
  // A wall point of piece 1, moved with it, lies on a wall of the plan again (within the noise).
  const PathPoint& q = moved[a.points.size()];
  EXPECT_EQ(q.piece, 1);
  double nearest = 1e9;
  for (const PlanSegment& s : plan.segments) {
    const Eigen::Vector2d ab = s.b - s.a;
    const double t = std::clamp((q.position.head<2>() - s.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (q.position.head<2>() - (s.a + t * ab)).norm());
  }
  EXPECT_LT(nearest, 0.1);
}

TEST(Registration, OptionsAreChecked) {
  RegistrationOptions o;
  o.cell_m = 0;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.coarse_cell_m = 0.01;
  try {
    o.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("RegistrationOptions.coarse_cell_m"), std::string::npos);
  }
  o = {};
  o.seen_through_weight = -1;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.seen_through_depth_margin = 1;
  EXPECT_THROW(o.check(), Error);
  for (double bad : {-1.0, 50.0}) {
    o = {};
    o.local_search_deg = bad;
    EXPECT_THROW(o.check(), Error) << bad;
  }
  o = {};
  o.local_search_step_deg = 0;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.local_search_m = -0.1;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.local_search_deg = 0;  // off
  EXPECT_NO_THROW(o.check());
}

TEST(Registration, ACancelEndsWithCancelled) {
  struct CancelAtOnce : CancellableProgress {
    void report(double, const std::string&) override { cancel(); }
  } progress;
  const SyntheticPiece piece = synthesise(l_building(), corridor_walk(), Similarity2{}, 1);
  EXPECT_THROW(register_on_plan(piece.path, piece.points, l_building(), {}, progress), Cancelled);
}

}  // namespace
}  // namespace plenopath
