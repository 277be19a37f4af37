// The synthetic camera against independent truth: depth from a brute-force 3-D ray/box intersection built
// straight from the FloorPlan, box directions against the POV-Ray convention fixtures, walk geometry
// against the plan's walls.
#include "rig/synthetic_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <set>

#include "model/error.h"
#include "rig/plan_drawing.h"
#include "rig/spherical.h"
#include "tests/rig/oracle_scene.h"

namespace plenopath {
namespace {

using test::cross2;
using test::OracleScene;

TEST(SyntheticCamera, DepthMatchesIndependentIntersection) {
  const FloorPlan plan = make_office_sample_plan();
  const SyntheticScene scene = build_synthetic_scene(plan);
  const OracleScene oracle(plan);
  RenderOptions options;
  options.width = 256;
  options.height = 128;
  std::mt19937 rng(12345);
  const PathFrame poses[] = {
      {0, "", 4.0, 7.5, 0.3, 1.0, kFrameOk, ""},     // corridor
      {1, "", 11.0, 10.0, -2.0, 1.0, kFrameOk, ""},  // meeting room, table in view
      {2, "", 12.6, 2.6, 3.1, 1.0, kFrameOk, ""},    // lobby between round pillars
      {3, "", 4.5, 1.0, 1.57, 1.0, kFrameOk, ""},    // lab, near benches
  };
  int checked = 0, furniture_hits = 0;
  double worst = 0.0;
  for (const PathFrame& pose : poses) {
    const RenderedPanorama pano = render_panorama(scene, pose, options);
    ASSERT_EQ(pano.depth.type(), CV_32F);
    const Eigen::Vector3d origin(pose.x, pose.y, 1.6);
    const Eigen::Matrix3d world_from_camera = world_from_camera_rotation(pose.heading);
    for (int k = 0; k < 2500; ++k) {
      const int u = std::uniform_int_distribution<int>(0, options.width - 1)(rng);
      const int v = std::uniform_int_distribution<int>(0, options.height - 1)(rng);
      const Eigen::Vector3d d =
          world_from_camera * equirect_to_bearing({u + 0.5, v + 0.5}, options.width, options.height);
      const double expected = oracle.intersect(origin, d.normalized());
      const double got = pano.depth.at<float>(v, u);
      worst = std::max(worst, std::abs(got - expected));
      ASSERT_NEAR(got, expected, 1e-6) << "pose " << pose.index << " pixel " << u << "," << v;
      furniture_hits += (expected > 0 && std::abs((origin + expected * d).z() - 0.75) < 1e-9);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 10000);
  EXPECT_GT(furniture_hits, 10);  // the furniture tops were exercised
  RecordProperty("worst_depth_error_m", std::to_string(worst));
}

TEST(SyntheticCamera, ThreadCountDoesNotChangeTheImage) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions options;
  options.width = 256;
  options.height = 128;
  options.people = 4;
  options.noise_sigma = 2.0;
  options.exposure_drift = 0.1;
  const PathFrame pose{17, "", 12.0, 7.4, 0.5, 1.0, kFrameOk, ""};
  RenderOptions single = options;
  single.threads = 1;
  const RenderedPanorama a = render_panorama(scene, pose, options);
  const RenderedPanorama b = render_panorama(scene, pose, single);
  EXPECT_EQ(cv::norm(a.rgb, b.rgb, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.depth, b.depth, cv::NORM_INF), 0.0);
}

TEST(SyntheticCamera, PeopleAppearAndMove) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions options;
  options.people = 6;
  const auto at0 = people_at_frame(scene, options, 0);
  const auto at30 = people_at_frame(scene, options, 30);
  ASSERT_EQ(at0.size(), 6u);
  ASSERT_EQ(at30.size(), 6u);
  for (std::size_t i = 0; i < at0.size(); ++i) {
    EXPECT_LT((at0[i].centre - at30[i].centre).norm(), 1.6);  // at most 1.5 m/s for one second
    double farthest = 0;
    for (int frame = 10; frame <= 150; frame += 10)
      farthest =
          std::max(farthest, (people_at_frame(scene, options, frame)[i].centre - at0[i].centre).norm());
    EXPECT_GT(farthest, 0.5) << "person " << i;
  }
  // A ray aimed at a person's chest hits the person at the right distance.
  const PersonPose& p = at0[0];
  const Eigen::Vector3d origin(p.centre.x() + 1.0, p.centre.y(), 1.2);
  const RayHit hit = trace_ray(scene, origin, {-1, 0, 0}, options, 0);
  EXPECT_EQ(hit.kind, SurfaceKind::kPerson);
  EXPECT_NEAR(hit.distance, 1.0 - p.radius, 1e-9);
}

TEST(SyntheticCamera, TraceRayAgreesWithThePanorama) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions options;
  options.width = 128;
  options.height = 64;
  const PathFrame pose{0, "", 16.0, 11.0, 1.0, 1.0, kFrameOk, ""};
  const RenderedPanorama pano = render_panorama(scene, pose, options);
  const Eigen::Matrix3d r = world_from_camera_rotation(pose.heading);
  for (int v = 3; v < 64; v += 7)
    for (int u = 0; u < 128; u += 5) {
      const Eigen::Vector3d d = r * equirect_to_bearing({u + 0.5, v + 0.5}, 128, 64);
      const RayHit hit = trace_ray(scene, {pose.x, pose.y, 1.6}, d, options);
      EXPECT_NEAR(hit.distance, pano.depth.at<float>(v, u), 1e-5) << u << "," << v;
    }
}

// Four boxes 5 m from the camera, told apart by their widths (red 0.8 m at +X, green 1.2 m at +Y, blue 1.6 m
// at -X, yellow 2.0 m at -Y), inside a 24 m room. Their azimuths in our render must match the azimuths of
// the coloured boxes in the POV-Ray fixtures (tests/data/convention/README.md).
FloorPlan convention_plan() {
  PlanDrawing d;
  d.layers = {{"WALLS", 7}, {"FURNITURE", 5}};
  d.polylines.push_back({{{-12, -12}, {12, -12}, {12, 12}, {-12, 12}}, true, "WALLS"});
  const double widths[4] = {0.8, 1.2, 1.6, 2.0};
  const Eigen::Vector2d dirs[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d c = 5.0 * dirs[i];
    const Eigen::Vector2d side(-dirs[i].y(), dirs[i].x());
    const double hw = widths[i] / 2;
    d.polylines.push_back({{c - 0.5 * dirs[i] - hw * side, c - 0.5 * dirs[i] + hw * side,
                            c + 0.5 * dirs[i] + hw * side, c + 0.5 * dirs[i] - hw * side},
                           true,
                           "FURNITURE"});
  }
  return flatten_drawing(d);
}

struct Blob {
  double azimuth, width;
};

// Runs of horizon columns whose depth is under 6 m (the boxes), with wrap-around.
std::vector<Blob> horizon_blobs(const cv::Mat& depth) {
  const int w = depth.cols, v = depth.rows / 2;
  std::vector<char> near(w);
  for (int u = 0; u < w; ++u) near[u] = depth.at<float>(v, u) > 0 && depth.at<float>(v, u) < 6.0f;
  int start = 0;
  while (start < w && near[start]) ++start;  // begin outside a run
  std::vector<Blob> blobs;
  for (int k = 0; k < w;) {
    const int u = (start + k) % w;
    if (!near[u]) {
      ++k;
      continue;
    }
    int len = 0;
    double sx = 0, sy = 0;
    while (k < w && near[(start + k) % w]) {
      const double a = equirect_to_angles({(start + k) % w + 0.5, v + 0.5}, w, depth.rows).azimuth;
      sx += std::cos(a);
      sy += std::sin(a);
      ++len;
      ++k;
    }
    blobs.push_back({std::atan2(sy, sx), static_cast<double>(len)});
  }
  std::sort(blobs.begin(), blobs.end(), [](const Blob& a, const Blob& b) { return a.width < b.width; });
  return blobs;
}

double fixture_azimuth(const cv::Mat& img, cv::Vec3b lo, cv::Vec3b hi) {
  double sx = 0, sy = 0;
  for (int v = img.rows / 2 - 10; v < img.rows / 2 + 10; ++v)
    for (int u = 0; u < img.cols; ++u) {
      const cv::Vec3b p = img.at<cv::Vec3b>(v, u);
      bool match = true;
      for (int k = 0; k < 3; ++k) match = match && p[k] >= lo[k] && p[k] <= hi[k];
      if (!match) continue;
      const double a = equirect_to_angles({u + 0.5, v + 0.5}, img.cols, img.rows).azimuth;
      sx += std::cos(a);
      sy += std::sin(a);
    }
  return std::atan2(sy, sx);
}

TEST(SyntheticCamera, BoxAzimuthsMatchThePovRayFixtures) {
  SceneOptions scene_options;
  scene_options.furniture_height = 2.1;
  const SyntheticScene scene = build_synthetic_scene(convention_plan(), scene_options);
  RenderOptions options;
  options.width = 512;
  options.height = 256;
  const std::pair<cv::Vec3b, cv::Vec3b> colours[4] = {{{0, 0, 120}, {90, 90, 255}},      // red
                                                      {{0, 120, 0}, {90, 255, 90}},      // green
                                                      {{120, 0, 0}, {255, 90, 90}},      // blue
                                                      {{0, 120, 120}, {90, 255, 255}}};  // yellow
  for (int heading_deg : {0, 30, 90}) {
    const cv::Mat fixture = cv::imread(std::string(PLENOPATH_TEST_DATA_DIR) + "/convention/pano_heading" +
                                       std::to_string(heading_deg) + ".png");
    ASSERT_FALSE(fixture.empty());
    const PathFrame pose{0, "", 0.0, 0.0, heading_deg * M_PI / 180, 1.0, kFrameOk, ""};
    const std::vector<Blob> blobs = horizon_blobs(render_panorama(scene, pose, options).depth);
    ASSERT_EQ(blobs.size(), 4u) << "heading " << heading_deg;
    for (int i = 0; i < 4; ++i) {
      const double pov = fixture_azimuth(fixture, colours[i].first, colours[i].second);
      EXPECT_NEAR(std::remainder(blobs[i].azimuth - pov, 2 * M_PI) * 180 / M_PI, 0.0, 0.75)
          << "heading " << heading_deg << " box " << i;
    }
  }
}

TEST(SyntheticCamera, BadOptionsAndEmptyPlansAreReported) {
  SceneOptions bad;
  bad.camera_height = 3.0;
  try {
    bad.check();
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "SceneOptions.camera_height must be in (0, wall_height), got 3");
  }
  EXPECT_THROW(build_synthetic_scene(make_office_sample_plan(), bad), Error);
  FloorPlan empty;
  empty.source_file = "empty.dxf";
  try {
    build_synthetic_scene(empty);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("empty.dxf"), std::string::npos);
  }
  RenderOptions r;
  r.width = 2;
  EXPECT_THROW(render_panorama(build_synthetic_scene(make_office_sample_plan()), PathFrame{}, r), Error);
}

bool segments_cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                    const Eigen::Vector2d& b) {
  const double d1 = cross2(q - p, a - p), d2 = cross2(q - p, b - p), d3 = cross2(b - a, p - a),
               d4 = cross2(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

double point_segment_distance(const Eigen::Vector2d& x, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (x - (a + t * ab)).norm();
}

TEST(AutoWalk, StaysClearOfWallsAndVisitsTheRooms) {
  const FloorPlan plan = make_office_sample_plan();
  AutoWalkOptions options;
  const CameraPath path = auto_walk(plan, options);
  ASSERT_GT(path.size(), 300u);
  // Room rectangles of the sample (hand-copied from its layout).
  const double rooms[8][4] = {{0, 8.5, 8, 15}, {8, 8.5, 14, 15}, {14, 8.5, 19.5, 15}, {19.5, 8.5, 25, 15},
                              {0, 0, 9, 6.5},  {9, 0, 16, 6.5},  {16, 0, 25, 6.5},    {0, 6.5, 25, 8.5}};
  std::set<int> visited;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const PathFrame& f = path.frames[i];
    for (int r = 0; r < 8; ++r)
      if (f.x > rooms[r][0] && f.x < rooms[r][2] && f.y > rooms[r][1] && f.y < rooms[r][3]) visited.insert(r);
    for (const auto& s : plan.segments) {
      if (!s.occluder && s.layer != "FURNITURE") continue;
      EXPECT_GT(point_segment_distance(f.position(), s.a, s.b), options.clearance - 0.15) << "frame " << i;
      if (i > 0) {
        EXPECT_FALSE(segments_cross(path.frames[i - 1].position(), f.position(), s.a, s.b)) << "frame " << i;
      }
    }
    if (i > 0) {
      const Eigen::Vector2d step = f.position() - path.frames[i - 1].position();
      EXPECT_LT(step.norm(), options.step * (1 + options.step_wobble) + 1e-9);
      EXPECT_GT(step.norm(), options.step * (1 - options.step_wobble) * 0.5);
    }
    if (i > 0 &&
        i + 1 < path.size()) {  // the trolley rolls along its own forward axis, give or take the wobble
      const Eigen::Vector2d tangent = path.frames[i + 1].position() - path.frames[i - 1].position();
      const double off = std::abs(wrap_angle(std::atan2(tangent.y(), tangent.x()) - f.heading));
      EXPECT_LT(off, radians(options.heading_wobble_deg + 25.0)) << "frame " << i;
    }
  }
  EXPECT_GE(visited.size(), 7u);
  EXPECT_EQ(path.frames[5].file, "frames/000005.jpg");
  AutoWalkOptions limited = options;
  limited.max_frames = 40;
  EXPECT_EQ(auto_walk(plan, limited).size(), 40u);
}

}  // namespace
}  // namespace plenopath

namespace plenopath {
namespace {

// KLT needs corners everywhere: every 45-degree sector of the horizon band of a render, in a room, a
// corridor and the lobby, holds Shi-Tomasi corners.
TEST(SyntheticCamera, CornersEverywhere) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions options;
  options.width = 512;
  options.height = 256;
  for (const PathFrame& pose : {PathFrame{0, "", 4.0, 7.5, 0.0, 1.0, kFrameOk, ""},
                                PathFrame{1, "", 11.0, 10.5, 1.0, 1.0, kFrameOk, ""},
                                PathFrame{2, "", 12.5, 3.0, 2.0, 1.0, kFrameOk, ""}}) {
    cv::Mat grey;
    cv::cvtColor(render_panorama(scene, pose, options).rgb, grey, cv::COLOR_BGR2GRAY);
    for (int sector = 0; sector < 8; ++sector) {
      const cv::Rect band(sector * 64, 64, 64, 128);  // elevations -45 .. +45 degrees
      std::vector<cv::Point2f> corners;
      cv::goodFeaturesToTrack(grey(band), corners, 200, 0.01, 4);
      EXPECT_GE(corners.size(), 20u) << "pose " << pose.index << " sector " << sector;
    }
  }
}

}  // namespace
}  // namespace plenopath

namespace plenopath {
namespace {

// The uniform grid only skips work: images are identical to testing every face, also with people, and
// for a plan with thousands of short segments.
TEST(SyntheticCamera, GridCastingEqualsTestingEveryFace) {
  FloorPlan plan = make_office_sample_plan();
  // Chop the walls into 2 cm pieces so cells hold many faces.
  FloorPlan chopped = plan;
  chopped.segments.clear();
  for (const auto& s : plan.segments) {
    const int n = s.occluder ? std::max(1, static_cast<int>(s.length() / 0.02)) : 1;
    for (int i = 0; i < n; ++i) {
      PlanSegment piece = s;
      piece.a = s.a + (s.b - s.a) * (double(i) / n);
      piece.b = s.a + (s.b - s.a) * (double(i + 1) / n);
      chopped.segments.push_back(piece);
    }
  }
  RenderOptions options;
  options.width = 256;
  options.height = 128;
  options.people = 5;
  for (const FloorPlan* p : {&plan, &chopped}) {
    SceneOptions brute;
    brute.use_grid = false;
    const SyntheticScene with_grid = build_synthetic_scene(*p), without = build_synthetic_scene(*p, brute);
    ASSERT_TRUE(with_grid.grid);
    for (const PathFrame& pose : {PathFrame{3, "", 4.0, 7.5, 0.2, 1.0, kFrameOk, ""},
                                  PathFrame{9, "", 12.4, 2.9, -1.0, 1.0, kFrameOk, ""}}) {
      const RenderedPanorama a = render_panorama(with_grid, pose, options),
                             b = render_panorama(without, pose, options);
      EXPECT_EQ(cv::norm(a.depth, b.depth, cv::NORM_INF), 0.0);
      EXPECT_EQ(cv::norm(a.rgb, b.rgb, cv::NORM_INF), 0.0);
    }
  }
}

}  // namespace
}  // namespace plenopath
