// Registration end to end against the renderer's ground truth (issue 19): walks rendered by the project's
// renderer on two plans, tracked (frame 0 at the origin, heading 0: no alignment at all), registered on the
// plan by the tracker's own points, and compared frame by frame with where the renderer put the camera.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "processing/egomotion/egomotion.h"
#include "processing/registration/registration.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

constexpr double kDeg = M_PI / 180.0;

RenderOptions small_render() {
  RenderOptions render;
  render.width = 512;
  render.height = 256;
  render.depth = false;
  return render;
}

EgomotionResult track(const SyntheticScene& scene, const CameraPath& truth) {
  EgomotionOptions options;
  options.camera_height_m = 1.6;
  const RenderOptions render = small_render();
  return EgomotionTracker::run(
      static_cast<int>(truth.size()),
      [&](int i) { return render_panorama(scene, truth.frames[i], render).rgb; }, options);
}

struct PlacementErrors {
  int frames = 0;
  double position_rms_m = 0, heading_rms_deg = 0;
};

// Absolute errors on the plan, no alignment: frame i of `placed` against frame i of `truth`.
PlacementErrors absolute_errors(const CameraPath& placed, const CameraPath& truth, int piece) {
  PlacementErrors e;
  double p2 = 0, h2 = 0;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    if (placed.frames[i].piece != piece) continue;
    p2 += (placed.frames[i].position() - truth.frames[i].position()).squaredNorm();
    h2 += std::pow(wrap_angle(placed.frames[i].heading - truth.frames[i].heading), 2);
    ++e.frames;
  }
  e.position_rms_m = std::sqrt(p2 / std::max(1, e.frames));
  e.heading_rms_deg = std::sqrt(h2 / std::max(1, e.frames)) / kDeg;
  return e;
}

void expect_placed_on_truth(const EgomotionResult& tracked, const CameraPath& truth, const FloorPlan& plan,
                            const char* what) {
  ASSERT_EQ(tracked.path.size(), truth.size());
  ASSERT_FALSE(tracked.tracked_points.empty());
  const RegistrationResult r = register_on_plan(tracked.path, tracked.tracked_points, plan);
  ASSERT_EQ(static_cast<int>(r.pieces.size()), tracked.path.piece_count());
  const CameraPath placed = apply_registration(tracked.path, r);
  for (const PieceRegistration& p : r.pieces) {
    ASSERT_TRUE(p.ok) << what << ": " << p.message;
    const PlacementErrors e = absolute_errors(placed, truth, p.piece);
    std::printf("%s, %s; %d frames: position RMS %.4f m, heading RMS %.4f deg (%.2f s)\n", what,
                describe(p).c_str(), e.frames, e.position_rms_m, e.heading_rms_deg, r.seconds);
    EXPECT_LE(e.position_rms_m, 0.05) << what << " piece " << p.piece;
    EXPECT_LE(e.heading_rms_deg, 0.2) << what << " piece " << p.piece;
    EXPECT_TRUE(placed.piece_placed(p.piece));
  }
}

TEST(RegistrationRendered, AnOfficeWalkLandsOnThePlanByItself) {
  const FloorPlan plan = make_office_sample_plan();
  AutoWalkOptions walk;
  walk.max_frames = 100;
  walk.seed = 7;
  const CameraPath truth = auto_walk(plan, walk);
  ASSERT_EQ(truth.size(), 100u);
  const EgomotionResult tracked = track(build_synthetic_scene(plan), truth);
  // The tracker's points: in the path's frame, metric (the floor near -1.6 m), each with its piece.
  int floor_like = 0;
  for (const PathPoint& p : tracked.tracked_points) {
    EXPECT_EQ(p.piece, 0);
    EXPECT_GE(p.observations, 1);
    floor_like += std::abs(p.position.z() + 1.6) < 0.05;
  }
  EXPECT_GT(floor_like, 20);
  expect_placed_on_truth(tracked, truth, plan, "office");
}

// Two 6 x 5 m rooms with no door between them (as in the CapturePieces tests), each with features that
// break its symmetry (a pillar, wall stubs); the walk is cut where it would pass through the wall: a
// capture in two pieces.
FloorPlan two_rooms_with_features() {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) { plan.segments.push_back({a, b, "WALLS", true}); };
  wall({0, 0}, {12, 0});
  wall({12, 0}, {12, 5});
  wall({12, 5}, {0, 5});
  wall({0, 5}, {0, 0});
  wall({6, 0}, {6, 5});
  wall({4.5, 0}, {4.5, 1.0});    // a stub in the first room
  wall({2.0, 3.8}, {2.4, 3.8});  // a pillar
  wall({2.4, 3.8}, {2.4, 4.2});
  wall({2.4, 4.2}, {2.0, 4.2});
  wall({2.0, 4.2}, {2.0, 3.8});
  wall({9.5, 5.0}, {9.5, 4.0});  // an L in the second room
  wall({9.5, 4.0}, {10.5, 4.0});
  return plan;
}

TEST(RegistrationRendered, EachPieceOfABrokenCaptureLandsOnItsOwn) {
  const FloorPlan plan = two_rooms_with_features();
  const SyntheticScene scene = build_synthetic_scene(plan);
  // Along the first room, then (the recording restarted in the other room) back along the second, facing
  // the other way.
  CameraPath truth;
  for (int i = 0; i < 60; ++i) {
    PathFrame f;
    f.index = static_cast<int>(truth.size());
    f.x = 0.8 + 0.08 * i;
    f.y = 2.5 + 0.4 * std::sin(i / 18.0);
    f.heading = 0.25 * std::sin(i / 25.0);
    truth.frames.push_back(f);
  }
  for (int i = 0; i < 55; ++i) {
    PathFrame f;
    f.index = static_cast<int>(truth.size());
    f.x = 11.2 - 0.08 * i;
    f.y = 2.0 + 0.3 * std::sin(i / 15.0);
    f.heading = wrap_angle(M_PI + 0.2 * std::sin(i / 20.0));
    truth.frames.push_back(f);
  }
  const EgomotionResult tracked = track(scene, truth);
  ASSERT_EQ(tracked.path.piece_count(), 2)
      << "the rooms share nothing; tracks continued into frame 60: " << tracked.continued_tracks[60];
  int per_piece[2] = {0, 0};
  for (const PathPoint& p : tracked.tracked_points) {
    ASSERT_TRUE(p.piece == 0 || p.piece == 1) << p.piece;
    ++per_piece[p.piece];
  }
  EXPECT_GT(per_piece[0], 100);
  EXPECT_GT(per_piece[1], 100);
  expect_placed_on_truth(tracked, truth, plan, "two rooms");
}

}  // namespace
}  // namespace plenopath
