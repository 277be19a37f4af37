// Hotspot geometry against the synthetic renderer's own posters: a poster marked in one frame, lifted onto
// its wall (from the plan or from depth), lands within 1 px of where the renderer draws it 2 m further on.
#include "processing/hotspots/hotspot_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/error.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

constexpr int kWidth = 1024, kHeight = 512;

struct Fixture {
  FloorPlan plan = make_office_sample_plan();
  SyntheticScene scene = build_synthetic_scene(plan);
  CameraPath walk = auto_walk(plan);
};
const Fixture& fixture() {
  static const Fixture f;
  return f;
}

std::vector<Eigen::Vector3d> poster_corners(const SyntheticScene& scene, const SceneFace& face,
                                            const ScenePoster& p) {
  const Eigen::Vector2d along = (face.b - face.a).normalized();
  auto at = [&](double u, double z) {
    const Eigen::Vector2d xy = face.a + u * along;
    return Eigen::Vector3d(xy.x(), xy.y(), z);
  };
  (void)scene;
  return {at(p.u0, p.z1), at(p.u1, p.z1), at(p.u1, p.z0), at(p.u0, p.z0)};
}

double render_depth_at(const cv::Mat& depth, const Eigen::Vector2d& px) {
  return depth.at<float>(static_cast<int>(px.y()), static_cast<int>(px.x()) % depth.cols);
}

struct Case {
  PathFrame a, b;
  std::vector<Eigen::Vector3d> truth;
  RenderedPanorama render_a, render_b;
};

// A frame A, a frame B about 2 m further along the path, and a poster both see (the renderer's depth at the
// poster's projected centre equals the distance to it in both frames).
Case search_case() {
  const Fixture& f = fixture();
  const double h = f.scene.options.camera_height;
  RenderOptions ro;
  ro.width = kWidth;
  ro.height = kHeight;
  const std::vector<double> s = f.walk.arc_lengths();
  for (std::size_t i = 0; i < f.walk.frames.size(); i += 25) {
    std::size_t j = i;
    while (j < f.walk.frames.size() && s[j] - s[i] < 2.0) ++j;
    if (j >= f.walk.frames.size()) break;
    const PathFrame& a = f.walk.frames[i];
    const PathFrame& b = f.walk.frames[j];
    for (const SceneFace& face : f.scene.faces) {
      if (face.kind != SurfaceKind::kWall) continue;
      for (int k = face.poster_begin; k < face.poster_end; ++k) {
        const std::vector<Eigen::Vector3d> corners = poster_corners(f.scene, face, f.scene.posters[k]);
        Eigen::Vector3d centre = Eigen::Vector3d::Zero();
        for (const auto& c : corners) centre += c / 4.0;
        bool seen = true;
        for (const PathFrame* pose : {&a, &b}) {
          const double dist = (centre - Eigen::Vector3d(pose->x, pose->y, h)).norm();
          seen = seen && dist < 6.0;
        }
        if (!seen) continue;
        Case c{a, b, corners, render_panorama(f.scene, a, ro), render_panorama(f.scene, b, ro)};
        bool visible = true;
        for (const auto* pair : {&c.a, &c.b}) {
          const RenderedPanorama& r = pair == &c.a ? c.render_a : c.render_b;
          for (const auto& corner : corners) {
            const Eigen::Vector3d inset = centre + 0.9 * (corner - centre);  // just inside the corner
            const Eigen::Vector2d px = project_to_equirect(inset, *pair, h, kWidth, kHeight);
            const double expected = (inset - Eigen::Vector3d(pair->x, pair->y, h)).norm();
            visible = visible && std::abs(render_depth_at(r.depth, px) - expected) < 0.05;
          }
        }
        if (visible) return c;
      }
    }
  }
  ADD_FAILURE() << "no poster is seen from two frames 2 m apart on the sample walk";
  return {};
}

const Case& find_case() {
  static const Case c = search_case();
  return c;
}

std::vector<SphericalAngles> marked_corners(const Case& c, double h) {
  // The author clicks pixel centres: the marks are the true corners rounded to the nearest pixel centre.
  std::vector<SphericalAngles> marks;
  for (const auto& corner : c.truth) {
    const Eigen::Vector2d px = project_to_equirect(corner, c.a, h, kWidth, kHeight);
    const Eigen::Vector2d clicked(std::floor(px.x()) + 0.5, std::floor(px.y()) + 0.5);
    marks.push_back(equirect_to_angles(clicked, kWidth, kHeight));
  }
  return marks;
}

double max_reprojection_error_px(const Case& c, const LiftedQuad& quad, double h) {
  double worst = 0;
  for (std::size_t i = 0; i < c.truth.size(); ++i) {
    const Eigen::Vector2d expected = project_to_equirect(c.truth[i], c.b, h, kWidth, kHeight);
    const Eigen::Vector2d got = project_to_equirect(quad.corners[i], c.b, h, kWidth, kHeight);
    Eigen::Vector2d d = got - expected;
    d.x() = std::remainder(d.x(), double(kWidth));
    worst = std::max(worst, d.norm());
  }
  return worst;
}

TEST(HotspotGeometry, PosterLiftedOntoItsWallReprojectsWithinOnePixel) {
  const Case c = find_case();
  ASSERT_EQ(c.truth.size(), 4u);
  const double h = fixture().scene.options.camera_height;
  // The renderer draws the poster where we project it: its depth at each (inset) corner in frame B.
  HotspotLiftOptions options;
  options.camera_height_m = h;
  const LiftedQuad quad = lift_quad_to_wall(marked_corners(c, h), c.a, fixture().plan, options);
  EXPECT_TRUE(quad.warning.empty()) << quad.warning;
  const double error = max_reprojection_error_px(c, quad, h);
  RecordProperty("max_reprojection_px", std::to_string(error));
  std::printf("poster lifted onto its wall: max reprojection error %.3f px at %dx%d, frames %d -> %d\n",
              error, kWidth, kHeight, c.a.index, c.b.index);
  EXPECT_LT(error, 1.0);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LT((quad.corners[i] - c.truth[i]).norm(), 0.02) << i;
}

TEST(HotspotGeometry, PosterLiftedFromDepthReprojectsWithinOnePixel) {
  const Case c = find_case();
  ASSERT_EQ(c.truth.size(), 4u);
  const double h = fixture().scene.options.camera_height;
  HotspotLiftOptions options;
  options.camera_height_m = h;
  // Depth at a corner pixel can fall just off the poster's wall; marks pulled 3 % inwards avoid the edge.
  std::vector<SphericalAngles> marks;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& t : c.truth) centre += t / 4.0;
  std::vector<Eigen::Vector3d> inner;
  for (const auto& t : c.truth) inner.push_back(centre + 0.97 * (t - centre));
  for (const auto& p : inner) marks.push_back(direction_in_frame(p, c.a, h));
  const LiftedQuad quad = lift_quad_from_depth(marks, c.a, c.render_a.depth, options);
  EXPECT_LT(quad.planarity_rms_m, 0.01);
  Case inner_case = c;
  inner_case.truth = inner;
  const double error = max_reprojection_error_px(inner_case, quad, h);
  std::printf("poster lifted from depth: max reprojection error %.3f px\n", error);
  EXPECT_LT(error, 1.0);
}

TEST(HotspotGeometry, MarksFromTwoFramesAgree) {
  const Case c = find_case();
  ASSERT_EQ(c.truth.size(), 4u);
  const double h = fixture().scene.options.camera_height;
  HotspotLiftOptions options;
  options.camera_height_m = h;
  const LiftedQuad from_a = lift_quad_to_wall(marked_corners(c, h), c.a, fixture().plan, options);
  Case swapped = c;
  std::swap(swapped.a, swapped.b);
  const LiftedQuad from_b = lift_quad_to_wall(marked_corners(swapped, h), swapped.a, fixture().plan, options);
  EXPECT_LT(quad_consistency_m(from_a, from_b), 0.03);
  // A mark shifted by 40 px in frame B no longer agrees.
  std::vector<SphericalAngles> wrong = marked_corners(swapped, h);
  for (auto& a : wrong) a.azimuth += 40.0 * 2 * M_PI / kWidth;
  const LiftedQuad off = lift_quad_to_wall(wrong, swapped.a, fixture().plan, options);
  EXPECT_GT(quad_consistency_m(from_a, off), 0.1);
}

TEST(HotspotGeometry, HomographyMatchesTheAnalyticProjectionOfThePlane) {
  // A 1.2 m x 0.8 m rectangle on a wall 3 m ahead, seen from a view looking slightly right and down.
  const PathFrame pose{0, "", 1.0, 2.0, 0.3, 1.0, 0, ""};
  const double h = 1.6;
  const Eigen::Vector3d o(4.0, 2.5, 2.0), e1(0.2, 1.18, 0.0), e3(0, 0, -0.8);
  const std::vector<Eigen::Vector3d> quad = {o, o + e1, o + e1 + e3, o + e3};
  PerspectiveView view;
  view.yaw = 0.35;
  view.pitch = -0.1;
  const cv::Size media(640, 360);
  const cv::Matx33d H = media_to_view_homography(quad, pose, h, view, media);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const double s = U(rng), t = U(rng);
    const auto analytic = project_to_view(o + s * e1 + t * e3, pose, h, view);
    ASSERT_TRUE(analytic.has_value());
    const cv::Vec3d p = H * cv::Vec3d(s * media.width, t * media.height, 1.0);
    EXPECT_NEAR(p[0] / p[2], analytic->x(), 1e-6);
    EXPECT_NEAR(p[1] / p[2], analytic->y(), 1e-6);
  }
  // Behind the viewer: a clear error.
  view.yaw += M_PI;
  EXPECT_THROW(media_to_view_homography(quad, pose, h, view, media), Error);
}

TEST(HotspotGeometry, MediaWarpsOntoTheQuadInAPanorama) {
  const Case c = find_case();
  ASSERT_EQ(c.truth.size(), 4u);
  const double h = fixture().scene.options.camera_height;
  cv::Mat frame = c.render_b.rgb.clone();
  cv::Mat media(90, 160, CV_8UC3, cv::Scalar(0, 255, 0));
  media(cv::Rect(0, 0, 80, 45)).setTo(cv::Scalar(255, 0, 0));  // top-left quarter blue
  const int painted = warp_media_into_equirect(frame, media, c.truth, c.b, h);
  EXPECT_GT(painted, 50);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& t : c.truth) centre += t / 4.0;
  const Eigen::Vector3d top_left =
      c.truth[0] + 0.25 * (c.truth[1] - c.truth[0]) + 0.25 * (c.truth[3] - c.truth[0]);
  const Eigen::Vector3d bottom_right =
      c.truth[0] + 0.75 * (c.truth[1] - c.truth[0]) + 0.75 * (c.truth[3] - c.truth[0]);
  auto pixel = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector2d px = project_to_equirect(p, c.b, h, kWidth, kHeight);
    return frame.at<cv::Vec3b>(static_cast<int>(px.y()), static_cast<int>(px.x()));
  };
  EXPECT_EQ(pixel(top_left), cv::Vec3b(255, 0, 0));
  EXPECT_EQ(pixel(bottom_right), cv::Vec3b(0, 255, 0));
  // Far from the quad nothing changed.
  const Eigen::Vector2d away = project_to_equirect(centre, c.b, h, kWidth, kHeight);
  const int u = (static_cast<int>(away.x()) + kWidth / 2) % kWidth;
  EXPECT_EQ(frame.at<cv::Vec3b>(kHeight / 2, u), c.render_b.rgb.at<cv::Vec3b>(kHeight / 2, u));
}

TEST(HotspotGeometry, BadInputGetsClearErrors) {
  const PathFrame pose{0, "", 0.0, 0.0, 0.0, 1.0, 0, ""};
  FloorPlan empty;
  const std::vector<SphericalAngles> quad = {{0.1, 0.1}, {-0.1, 0.1}, {-0.1, -0.1}, {0.1, -0.1}};
  EXPECT_THROW(lift_quad_to_wall(quad, pose, empty), Error);                               // no wall
  EXPECT_THROW(lift_quad_to_wall({{0.1, 0.1}, {0.2, 0.1}}, pose, fixture().plan), Error);  // two corners
  EXPECT_THROW(lift_quad_to_wall({{0, M_PI / 2}, {1, M_PI / 2}, {2, M_PI / 2}}, pose, fixture().plan), Error);
  EXPECT_THROW(lift_quad_from_depth(quad, pose, cv::Mat()), Error);                                // no depth
  EXPECT_THROW(lift_quad_from_depth(quad, pose, cv::Mat(64, 128, CV_32F, cv::Scalar(0))), Error);  // no hit
  HotspotLiftOptions bad;
  bad.camera_height_m = 0;
  EXPECT_THROW(bad.check(), Error);
}

}  // namespace
}  // namespace plenopath
