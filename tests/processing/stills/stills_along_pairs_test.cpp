// Stills placed on the plan through pairs that give a direction and a turn but no length: stills rendered
// by the studio's renderer at known poses along the office sample's corridor; still 0 placed at its truth,
// the others unplaced at the origin of pieces of their own. The pairs are made from the truth (turn and
// direction exactly as planar_two_point.h defines them), so the test checks the placement, not matching:
// each still must come within 5 cm and 0.5 deg of the render's truth, chained 0 -> 1 -> 2. A pair whose
// direction points into a wall, and a still whose pair is weak, are left unplaced.
#include "processing/stills/stills_along_pairs.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/error.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

double heading_error_deg(double a, double b) {
  return std::abs(std::remainder(a - b, 2 * M_PI)) * 180 / M_PI;
}

StillsPair pair_from_truth(const PathFrame& a, const PathFrame& b, int ia, int ib, int inliers) {
  StillsPair p;
  p.a = ia;
  p.b = ib;
  p.inliers = inliers;
  p.turn_deg = std::remainder(b.heading - a.heading, 2 * M_PI) * 180 / M_PI;
  const Eigen::Vector2d d = b.position() - a.position();
  p.direction_deg = std::remainder(std::atan2(d.y(), d.x()) - a.heading, 2 * M_PI) * 180 / M_PI;
  p.median_parallax_deg = 10.0;
  return p;
}

TEST(StillsAlongPairs, AChainOfPairsWithoutLengthsIsPlacedByThePlan) {
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene world = build_synthetic_scene(plan, SceneOptions{});
  RenderOptions render;
  render.width = 1440;
  render.height = 720;
  render.depth = false;
  // The corridor (y 6.5-7.5 in the office sample) and the lobby.
  const std::vector<Eigen::Vector3d> truth = {
      {2.0, 7.0, 0.4}, {5.2, 7.1, 2.2}, {8.6, 6.9, -0.9}, {12.5, 4.0, 1.0}};
  std::vector<cv::Mat> stills;
  CameraPath path;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    PathFrame f;
    f.index = static_cast<int>(i);
    f.x = truth[i].x();
    f.y = truth[i].y();
    f.heading = truth[i].z();
    stills.push_back(render_panorama(world, f, render).rgb);
    PathPiece piece;
    piece.first_index = piece.last_index = f.index;
    piece.placed = i == 0;
    piece.scale_source = "camera_height";
    path.pieces.push_back(piece);
    f.piece = static_cast<int>(i);
    if (i > 0) f.x = f.y = f.heading = 0.0;  // unplaced: own coordinates
    path.frames.push_back(f);
  }
  auto at = [&](int i) {
    PathFrame f;
    f.x = truth[i].x();
    f.y = truth[i].y();
    f.heading = truth[i].z();
    return f;
  };
  std::vector<StillsPair> pairs = {pair_from_truth(at(0), at(1), 0, 1, 60),
                                   pair_from_truth(at(1), at(2), 1, 2, 50),
                                   pair_from_truth(at(2), at(3), 2, 3, 5)};  // too weak
  PairPlacementReport report;
  const CameraPath placed = place_stills_along_pairs(
      path, pairs, [&](int i) { return stills[static_cast<std::size_t>(i)]; }, plan, {}, &report);
  ASSERT_EQ(report.placed.size(), 2u);
  for (int i : {1, 2}) {
    const PathFrame* f = placed.find_frame(i);
    ASSERT_NE(f, nullptr);
    EXPECT_TRUE(placed.piece_placed(f->piece)) << i;
    const double position_error = (f->position() - truth[i].head<2>()).norm();
    std::printf("still %d: %.3f m, %.2f deg\n", i, position_error,
                heading_error_deg(f->heading, truth[i].z()));
    EXPECT_LT(position_error, 0.05) << i;
    EXPECT_LT(heading_error_deg(f->heading, truth[i].z()), 0.5) << i;
  }
  EXPECT_EQ(report.placed[0].from_frame, 0);
  EXPECT_EQ(report.placed[1].from_frame, 1);
  EXPECT_FALSE(placed.piece_placed(placed.find_frame(3)->piece));  // its only pair is too weak

  // A pair pointing the wrong way (into the walls across the corridor, then the rooms beyond): the fit
  // there is poor or ambiguous, and the still is left for the author.
  StillsPair wrong = pair_from_truth(at(0), at(1), 0, 1, 60);
  wrong.direction_deg += 90.0;
  PairPlacementReport wrong_report;
  const CameraPath left = place_stills_along_pairs(
      path, {wrong}, [&](int i) { return stills[static_cast<std::size_t>(i)]; }, plan, {}, &wrong_report);
  EXPECT_TRUE(wrong_report.placed.empty());
  EXPECT_FALSE(left.piece_placed(left.find_frame(1)->piece));
}

TEST(StillsAlongPairs, BadOptionsAreRefused) {
  PairPlacementOptions options;
  options.max_distance_m = 0.1;
  EXPECT_THROW(options.check(), Error);
  options = {};
  options.min_ambiguity_ratio = 0.5;
  EXPECT_THROW(options.check(), Error);
}

}  // namespace
}  // namespace plenopath
