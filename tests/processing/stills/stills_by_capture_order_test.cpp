// Stills placed next to their neighbours in capture order. Walking reach: a hand-made wall with a door,
// distances measured by hand. Placement: stills rendered by the studio's renderer at known poses in the
// office sample (corridor, then through a door into a room), the first placed at its truth, the others
// unplaced pieces of their own at the origin; no pairs at all, so only the plan and the capture order can
// place them. Each still placed must be within 5 cm and 0.5 deg of the render's truth; a pair whose turn
// contradicts the fit keeps a still off the plan.
#include "processing/stills/stills_by_capture_order.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/error.h"
#include "tests/processing/stills/rendered_stills.h"

namespace plenopath {
namespace {

PlanSegment wall(double ax, double ay, double bx, double by) {
  PlanSegment s;
  s.a = {ax, ay};
  s.b = {bx, by};
  s.layer = "A-WALL";
  s.occluder = true;
  return s;
}

bool has_spot_near(const std::vector<Eigen::Vector2d>& spots, const Eigen::Vector2d& p) {
  for (const Eigen::Vector2d& s : spots)
    if ((s - p).norm() < 1e-6) return true;
  return false;
}

// A wall along x = 0 from y = -5 to y = 5, open above y = 5 (the door). From (-0.5, 0): the spot (0.5, 0)
// is 1 m away in a straight line but 2 * hypot(0.5, 5) = 10.05 m on foot round the wall's end.
TEST(StillsByCaptureOrder, WalkingReachGoesRoundTheWalls) {
  FloorPlan plan;
  plan.segments.push_back(wall(0, -5, 0, 5));
  const Eigen::Vector2d from(-0.5, 0.0);
  const double step = 0.1;
  const std::vector<Eigen::Vector2d> near = spots_within_walking_reach(plan, from, 4.0, step);
  EXPECT_TRUE(has_spot_near(near, from));
  EXPECT_TRUE(has_spot_near(near, from + Eigen::Vector2d(-3.0, 0.0)));   // 3 m on this side
  EXPECT_FALSE(has_spot_near(near, from + Eigen::Vector2d(1.0, 0.0)));   // across the wall
  EXPECT_FALSE(has_spot_near(near, from + Eigen::Vector2d(-4.5, 0.0)));  // beyond reach
  for (const Eigen::Vector2d& s : near) EXPECT_LT(s.x(), 0.0);
  // 11 m of reach (the 8-connected walk is at most 8 % longer than the true one): round the end.
  const std::vector<Eigen::Vector2d> far = spots_within_walking_reach(plan, from, 11.0, step);
  EXPECT_TRUE(has_spot_near(far, from + Eigen::Vector2d(1.0, 0.0)));
  // Without the wall, the straight-line reach on the grid: every spot within the 8-connected distance,
  // so at least every spot within reach / 1.0824 in a straight line.
  const std::vector<Eigen::Vector2d> open = spots_within_walking_reach(FloorPlan{}, from, 2.0, step);
  int inside = 0;
  for (int i = -20; i <= 20; ++i)
    for (int k = -20; k <= 20; ++k) {
      const Eigen::Vector2d p = from + step * Eigen::Vector2d(i, k);
      if ((p - from).norm() <= 2.0 / 1.0824) {
        ++inside;
        EXPECT_TRUE(has_spot_near(open, p)) << i << " " << k;
      }
    }
  EXPECT_GT(inside, 300);
  for (const Eigen::Vector2d& s : open) EXPECT_LE((s - from).norm(), 2.0 + 1e-9);
  EXPECT_THROW(spots_within_walking_reach(plan, from, 0.0, step), Error);
}

struct RenderedStills {
  std::vector<Eigen::Vector3d> truth;  // x, y, heading (rad)
  std::vector<cv::Mat> images;
  CameraPath path;  // still 0 placed at its truth, the others unplaced at the origin
};

RenderedStills render_stills(const FloorPlan& plan, const std::vector<Eigen::Vector3d>& truth) {
  RenderedStills out;
  out.truth = truth;
  out.images = test::render_stills_at(plan, truth);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    PathFrame f = test::frame_at(static_cast<int>(i), truth[i]);
    PathPiece piece;
    piece.first_index = piece.last_index = f.index;
    piece.placed = i == 0;
    piece.scale_source = "camera_height";
    out.path.pieces.push_back(piece);
    f.piece = static_cast<int>(i);
    if (i > 0) f.x = f.y = f.heading = 0.0;
    out.path.frames.push_back(f);
  }
  return out;
}

using test::heading_error_deg;

// The office sample: round the open office (8 x 6.5 m, desks, a square pillar), 2-3 m apart, then out
// through its door into the corridor, which looks alike all along.
const std::vector<Eigen::Vector3d> kWalk = {
    {2.0, 10.0, 0.4}, {4.6, 12.8, 2.2}, {6.6, 10.4, -0.9}, {4.0, 9.4, 1.9}, {4.5, 7.3, -2.6}};

struct WalkResult {
  int placed = 0;
  int wrong = 0;  // placed farther than 5 cm or 0.5 deg from the truth
};

WalkResult place_walk(const FloorPlan& plan, const RenderedStills& stills,
                      const std::vector<StillsPair>& pairs, std::vector<PathPoint>* points,
                      CameraPath* placed_path) {
  CaptureOrderReport report;
  const CameraPath placed = place_stills_by_capture_order(
      stills.path, pairs, [&](int i) { return stills.images[static_cast<std::size_t>(i)]; }, plan, points, {},
      &report);
  WalkResult out;
  for (std::size_t i = 1; i < stills.truth.size(); ++i) {
    const PathFrame* f = placed.find_frame(static_cast<int>(i));
    const double position_error = (f->position() - stills.truth[i].head<2>()).norm();
    const double heading_error = heading_error_deg(f->heading, stills.truth[i].z());
    const bool on_plan = placed.piece_placed(f->piece);
    std::printf("still %zu: %s, %.3f m, %.2f deg\n", i, on_plan ? "placed" : "unplaced", position_error,
                heading_error);
    out.placed += on_plan;
    out.wrong += on_plan && !(position_error < 0.05 && heading_error < 0.5);
  }
  for (const CaptureOrderRejection& q : report.rejected)
    std::printf("  left still %d: %s\n", q.frame, q.reason.c_str());
  EXPECT_EQ(out.placed, static_cast<int>(report.placed.size()));
  if (placed_path) *placed_path = placed;
  return out;
}

// Pairs that give the turn between consecutive stills but a wrong direction (as a look-alike room does).
std::vector<StillsPair> turn_only_pairs(const std::vector<Eigen::Vector3d>& truth) {
  std::vector<StillsPair> pairs;
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    StillsPair p;
    p.a = static_cast<int>(i);
    p.b = static_cast<int>(i + 1);
    p.inliers = 60;
    p.turn_deg = std::remainder(truth[i + 1].z() - truth[i].z(), 2 * M_PI) * 180 / M_PI;
    p.direction_deg = 77.0;  // not used
    pairs.push_back(p);
  }
  return pairs;
}

TEST(StillsByCaptureOrder, AWalkOfStillsIsPlacedOneFromTheNext) {
  const FloorPlan plan = make_office_sample_plan();
  const RenderedStills stills = render_stills(plan, kWalk);
  // With the pairs' turns: every still in the room placed, each within 5 cm and 0.5 deg; the corridor's
  // is placed right or left.
  std::vector<PathPoint> points(1);
  points[0].piece = 3;  // moves with still 3
  points[0].position = {1.0, 0.0, 0.5};
  CameraPath placed;
  const WalkResult with_turns = place_walk(plan, stills, turn_only_pairs(kWalk), &points, &placed);
  EXPECT_GE(with_turns.placed, 3);
  EXPECT_EQ(with_turns.wrong, 0);
  // The point moved with still 3: 1 m ahead of it, at its height.
  const PathFrame* f3 = placed.find_frame(3);
  ASSERT_TRUE(placed.piece_placed(f3->piece));
  const Eigen::Vector2d ahead =
      f3->position() + Eigen::Vector2d(std::cos(f3->heading), std::sin(f3->heading));
  EXPECT_LT((points[0].position.head<2>() - ahead).norm(), 1e-9);
  EXPECT_DOUBLE_EQ(points[0].position.z(), 0.5);
  // Without any pair nothing confirms that a still was shot where the capture order points: each is left
  // for the author.
  const WalkResult alone = place_walk(plan, stills, {}, nullptr, nullptr);
  EXPECT_EQ(alone.placed, 0);
}

// Still 1's only pair says it is turned 180 deg from what its fit says: it stays off the plan, and so do
// the stills after it, which only it could reach.
TEST(StillsByCaptureOrder, APairThatContradictsTheHeadingKeepsTheStillOff) {
  const FloorPlan plan = make_office_sample_plan();
  RenderedStills stills = render_stills(plan, {kWalk[0], kWalk[1], kWalk[2]});
  StillsPair wrong;
  wrong.a = 0;
  wrong.b = 1;
  wrong.inliers = 100;
  wrong.turn_deg = std::remainder(kWalk[1].z() - kWalk[0].z() + M_PI, 2 * M_PI) * 180 / M_PI;
  CaptureOrderReport report;
  const CameraPath placed = place_stills_by_capture_order(
      stills.path, {wrong}, [&](int i) { return stills.images[static_cast<std::size_t>(i)]; }, plan, nullptr,
      {}, &report);
  EXPECT_FALSE(placed.piece_placed(placed.find_frame(1)->piece));
  EXPECT_FALSE(placed.piece_placed(placed.find_frame(2)->piece));
  EXPECT_TRUE(report.placed.empty());
  // The same pair with its true turn agrees, and the still is placed.
  StillsPair right = wrong;
  right.turn_deg = std::remainder(kWalk[1].z() - kWalk[0].z(), 2 * M_PI) * 180 / M_PI;
  CaptureOrderReport right_report;
  const CameraPath right_placed = place_stills_by_capture_order(
      stills.path, {right}, [&](int i) { return stills.images[static_cast<std::size_t>(i)]; }, plan, nullptr,
      {}, &right_report);
  ASSERT_TRUE(right_placed.piece_placed(right_placed.find_frame(1)->piece));
  ASSERT_FALSE(right_report.placed.empty());
  EXPECT_EQ(right_report.placed[0].pairs_voting, 1);
  EXPECT_EQ(right_report.placed[0].pairs_agreeing, 1);
}

TEST(StillsByCaptureOrder, BadOptionsAreRefused) {
  CaptureOrderPlacementOptions options;
  options.reach_m = 0.0;
  EXPECT_THROW(options.check(), Error);
  options = {};
  options.coarse_width = 722;
  EXPECT_THROW(options.check(), Error);
  options = {};
  options.min_ambiguity_ratio = 0.9;
  EXPECT_THROW(options.check(), Error);
  options = {};
  options.turn_tolerance_deg = 0.0;
  EXPECT_THROW(options.check(), Error);
}

}  // namespace
}  // namespace plenopath
