// Placing hotspot quads in a hand-made room: 8 m x 5 m (walls x = 0, x = 8, y = 0, y = 5) with a half wall
// x = 4, y 0..2.5. The camera is 1.6 m up. Truth is the room's known wall planes and points picked on them.
#include "processing/hotspots/hotspot_placement.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/error.h"
#include "processing/hotspots/hotspot_geometry.h"

namespace plenopath {
namespace {

constexpr double kHeight = 1.6;

FloorPlan room() {
  FloorPlan plan;
  auto wall = [&](double ax, double ay, double bx, double by) {
    plan.segments.push_back({{ax, ay}, {bx, by}, "WALLS", true});
  };
  wall(0, 0, 8, 0);
  wall(8, 0, 8, 5);
  wall(8, 5, 0, 5);
  wall(0, 5, 0, 0);
  wall(4, 0, 4, 2.5);
  return plan;
}

PathFrame pose(double x, double y, double heading_deg) {
  PathFrame f;
  f.x = x;
  f.y = y;
  f.heading = heading_deg * M_PI / 180.0;
  return f;
}

// A poster on the east wall x = 8: y 3..4.5, z 1..2.2 (corners clockwise seen from the room).
std::vector<Eigen::Vector3d> east_poster() { return {{8, 4.5, 2.2}, {8, 3, 2.2}, {8, 3, 1}, {8, 4.5, 1}}; }

std::vector<SphericalAngles> marks(const std::vector<Eigen::Vector3d>& points, const PathFrame& p) {
  std::vector<SphericalAngles> out;
  for (const auto& q : points) out.push_back(direction_in_frame(q, p, kHeight));
  return out;
}

HotspotPlacementOptions options() {
  HotspotPlacementOptions o;
  o.lift.camera_height_m = kHeight;
  return o;
}

TEST(HotspotPlacement, SnapsToTheWallItLiesOn) {
  const PathFrame p = pose(1.0, 3.5, 20.0);
  const PlacedQuad placed = place_hotspot_quad(marks(east_poster(), p), p, room(), cv::Mat(), options());
  EXPECT_EQ(placed.placement, HotspotPlacement::kWall);
  EXPECT_EQ(placed.quad.wall_segment, 1);
  EXPECT_NE(placed.message.find("wall"), std::string::npos);
  ASSERT_EQ(placed.quad.corners.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_LT((placed.quad.corners[i] - east_poster()[i]).norm(), 1e-9) << i;
  EXPECT_NEAR(std::abs(placed.quad.normal.x()), 1.0, 1e-12);
}

TEST(HotspotPlacement, UsesDepthWhenNoWallIsHit) {
  // No plan; the depth map of a wall x = 6 (metres along each pixel-centre ray).
  const PathFrame p = pose(1.0, 3.5, 0.0);
  const int w = 2048, h = 1024;
  cv::Mat depth(h, w, CV_32F, cv::Scalar(0));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3d d = equirect_to_bearing({u + 0.5, v + 0.5}, w, h);  // heading 0: world = camera
      if (d.x() > 1e-3) depth.at<float>(v, u) = static_cast<float>(5.0 / d.x());
    }
  const std::vector<Eigen::Vector3d> truth{{6, 4, 2}, {6, 3, 2}, {6, 3, 1}, {6, 4, 1}};
  const PlacedQuad placed = place_hotspot_quad(marks(truth, p), p, FloorPlan(), depth, options());
  EXPECT_EQ(placed.placement, HotspotPlacement::kDepth);
  EXPECT_NE(placed.message.find("depth"), std::string::npos);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LT((placed.quad.corners[i] - truth[i]).norm(), 0.02) << i;
}

TEST(HotspotPlacement, FallsBackToAPlaneFacingTheCameraAndSaysSo) {
  const PathFrame p = pose(1.0, 3.5, 0.0);
  const std::vector<Eigen::Vector3d> far{{9, 4, 2}, {9, 3, 2}, {9, 3, 1}, {9, 4, 1}};
  HotspotPlacementOptions o = options();
  o.fallback_distance_m = 3.0;
  const PlacedQuad placed = place_hotspot_quad(marks(far, p), p, FloorPlan(), cv::Mat(), o);
  EXPECT_EQ(placed.placement, HotspotPlacement::kFacingCamera);
  EXPECT_NE(placed.message.find("facing the camera"), std::string::npos) << placed.message;
  EXPECT_FALSE(placed.quad.warning.empty());
  // Mean direction is +x, so the plane is x = 1 + 3 = 4; each corner stays on its marked ray (scaled by 3/8).
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d expected =
        Eigen::Vector3d(1, 3.5, kHeight) + 3.0 / 8.0 * (far[i] - Eigen::Vector3d(1, 3.5, kHeight));
    EXPECT_LT((placed.quad.corners[i] - expected).norm(), 1e-9) << i;
  }
}

TEST(HotspotPlacement, BadInputIsAnErrorNotACrash) {
  const PathFrame p = pose(1.0, 3.5, 0.0);
  EXPECT_THROW(place_hotspot_quad({{0, 0}, {0.1, 0}}, p, room(), cv::Mat(), options()), Error);
  EXPECT_THROW(place_hotspot_quad({{0, 0}, {NAN, 0}, {0.1, 0.1}}, p, room(), cv::Mat(), options()), Error);
  HotspotPlacementOptions bad = options();
  bad.fallback_distance_m = 0;
  EXPECT_THROW(place_hotspot_quad(marks(east_poster(), p), p, room(), cv::Mat(), bad), Error);
}

TEST(HotspotPlacement, DraggedCornerMovesOnTheQuadsPlane) {
  // Dragging a corner in another frame: the new corner is where that frame's ray meets the wall x = 8.
  const PathFrame other = pose(5.0, 4.0, 90.0);
  const Eigen::Vector3d target(8, 4.8, 2.4);
  const Eigen::Vector3d got =
      point_on_quad_plane(east_poster(), direction_in_frame(target, other, kHeight), other, kHeight);
  EXPECT_LT((got - target).norm(), 1e-9);
  // Looking away from the wall: an error, not a point behind the camera.
  EXPECT_THROW(point_on_quad_plane(east_poster(), {M_PI, 0.0}, pose(5.0, 4.0, 0.0), kHeight), Error);
  EXPECT_THROW(fit_plane({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}), Error);
}

TEST(HotspotPlacement, VisibleOnlyWhereNoWallIsInTheWay) {
  const FloorPlan plan = room();
  HotspotVisibilityOptions o;
  o.camera_height_m = kHeight;
  const PathFrame author = pose(1.0, 3.5, 0.0);
  EXPECT_TRUE(hotspot_visible_from(east_poster(), author, plan, o, &author));
  EXPECT_TRUE(hotspot_visible_from(east_poster(), pose(7.0, 1.0, 0.0), plan, o, &author));
  // A poster low on the east wall at y 0.5..1.5: from (1, 3.5) the sight line to its centre (8, 1) crosses
  // x = 4 at y = 3.5 - 2.5 * 3 / 7 = 2.43 < 2.5, inside the half wall.
  const std::vector<Eigen::Vector3d> low{{8, 1.5, 2}, {8, 0.5, 2}, {8, 0.5, 1}, {8, 1.5, 1}};
  EXPECT_FALSE(hotspot_visible_from(low, author, plan, o));
  EXPECT_TRUE(hotspot_visible_from(low, pose(6.0, 2.0, 0.0), plan, o));
  // A poster on the half wall's east face: seen from the east side, not from behind (west of x = 4).
  const PathFrame east_author = pose(6.0, 1.0, 180.0);
  const std::vector<Eigen::Vector3d> on_half{{4, 0.8, 2}, {4, 1.8, 2}, {4, 1.8, 1}, {4, 0.8, 1}};
  EXPECT_TRUE(hotspot_visible_from(on_half, east_author, plan, o, &east_author));
  EXPECT_FALSE(hotspot_visible_from(on_half, pose(2.0, 1.0, 0.0), plan, o, &east_author));
  o.max_distance_m = 2.0;
  EXPECT_FALSE(hotspot_visible_from(east_poster(), author, plan, o, &author));
}

TEST(HotspotPlacement, PositionToShowPrefersTheAuthoringFrame) {
  CameraPath path;
  for (int i = 0; i < 10; ++i) {
    PathFrame f = pose(0.5 + 0.8 * i, 1.0, 0.0);  // y = 1: behind the half wall for x < 4
    f.index = 100 + i;
    path.frames.push_back(f);
  }
  Hotspot h;
  h.frame = 104;
  h.world_corners = {{8, 1.5, 2}, {8, 0.5, 2}, {8, 0.5, 1}, {8, 1.5, 1}};
  HotspotVisibilityOptions o;
  o.camera_height_m = kHeight;
  EXPECT_EQ(position_to_show_hotspot(h, path, room(), 0, o), 4);
  // Not on the path any more: the nearest frame east of the half wall (x = 0.5 + 0.8 * 5 = 4.5).
  h.frame = 7;
  EXPECT_EQ(position_to_show_hotspot(h, path, room(), 0, o), 5);
  h.world_corners.clear();
  EXPECT_EQ(position_to_show_hotspot(h, path, room(), 0, o), -1);
}

}  // namespace
}  // namespace plenopath
