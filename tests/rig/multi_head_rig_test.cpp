// The multi-head rig: calibration files, head geometry, stitching against the direct panorama render,
// parallax with offsets, cube maps.
#include "rig/multi_head_rig.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "rig/spherical.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

// A rig whose heads have about the panorama's angular resolution (256 x 128 panorama: 0.71 px/degree).
MultiHeadRig small_rig(double offset_radius = 0.0) {
  DefaultRigOptions o;
  o.ring_width = 48;
  o.ring_height = 104;
  o.cap_size = 90;
  o.offset_radius = offset_radius;
  return make_default_rig(o);
}

TEST(MultiHeadRig, DefaultRigHasTenHeadsCoveringTheSphere) {
  const MultiHeadRig rig = make_default_rig();
  ASSERT_EQ(rig.heads.size(), 10u);
  EXPECT_NO_THROW(rig.check());
  StitchOptions so;
  so.width = 360;
  so.height = 180;
  const StitchMaps maps = make_stitch_maps(rig, so);
  double min_cov, max_cov;
  cv::minMaxLoc(maps.coverage, &min_cov, &max_cov);
  EXPECT_GE(min_cov, 1.0);  // every direction is seen
  EXPECT_GE(max_cov, 2.0);  // and there are overlaps to feather
}

TEST(MultiHeadRig, HeadGeometryFollowsTheConvention) {
  const MultiHeadRig rig = make_default_rig();
  // ring2 looks at yaw 90 deg: azimuth +90 is to the right, i.e. the rig's -y.
  const PinholeHead& ring2 = rig.heads[2];
  const Eigen::Vector3d axis = ring2.bearing({ring2.cx, ring2.cy});
  EXPECT_NEAR((axis - Eigen::Vector3d(0, -1, 0)).norm(), 0.0, 1e-12);
  // Image up is the rig's up for ring heads, image right is clockwise.
  EXPECT_GT(ring2.bearing({ring2.cx, 0}).z(), 0.5);
  EXPECT_LT(ring2.bearing({ring2.width - 1.0, ring2.cy}).x(), -0.3);
  EXPECT_NEAR(rig.heads[8].bearing({rig.heads[8].cx, rig.heads[8].cy}).z(), 1.0, 1e-12);   // up
  EXPECT_NEAR(rig.heads[9].bearing({rig.heads[9].cx, rig.heads[9].cy}).z(), -1.0, 1e-12);  // down
  for (const auto& head : rig.heads) {
    Eigen::Vector2d p;
    ASSERT_TRUE(head.project(head.bearing({10.25, 20.5}), &p));
    EXPECT_NEAR((p - Eigen::Vector2d(10.25, 20.5)).norm(), 0.0, 1e-9);
  }
}

TEST(MultiHeadRig, CalibrationFileRoundTripsAndReportsErrors) {
  MultiHeadRig rig = make_default_rig();
  rig.heads[3].offset = Eigen::Vector3d(0.01, -0.02, 0.003);
  rig.heads[3].roll_deg = 1.5;
  const std::string file = testing::TempDir() + "/rig.json";
  write_rig_file(rig, file);
  const MultiHeadRig back = read_rig_file(file);
  ASSERT_EQ(back.heads.size(), rig.heads.size());
  EXPECT_EQ(back.heads[3].name, "ring3");
  EXPECT_NEAR((back.heads[3].rig_from_head() - rig.heads[3].rig_from_head()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((back.heads[3].offset - rig.heads[3].offset).norm(), 0.0, 1e-12);

  std::ofstream(file) << R"({"format":"plenopath-rig","heads":[{"name":"a","width":10,"height":10,"fy":5}]})";
  try {
    read_rig_file(file);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("rig.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/heads/0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fx"), std::string::npos) << e.what();
  }
  std::ofstream(file) << R"({"heads":[{"name":"a","width":10,"height":10,"fx":5,"fy":-5}]})";
  try {
    read_rig_file(file);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fx and fy"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_rig_file(testing::TempDir() + "/absent_rig.json"), Error);
}

// The renderer does not anti-alias silhouettes, so both sides are compared the way a camera would see
// them: rendered at twice the resolution (heads too) and box-filtered down to 256 x 128. The plain
// 256 x 128 comparison is checked too, with a lower bar (aliased edges resample differently).
TEST(MultiHeadRig, StitchWithoutOffsetsMatchesTheDirectRender) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  const PathFrame pose{0, "", 11.2, 9.9, 0.4, 1.0, kFrameOk, ""};
  double db[2];
  for (int scale : {1, 2}) {
    RenderOptions options;
    options.width = 256 * scale;
    options.height = 128 * scale;
    const RenderedPanorama direct = render_panorama(scene, pose, options);
    DefaultRigOptions ro;
    ro.ring_width = 48 * scale;
    ro.ring_height = 104 * scale;
    ro.cap_size = 90 * scale;
    const MultiHeadRig rig = make_default_rig(ro);
    StitchOptions so;
    so.width = options.width;
    so.height = options.height;
    cv::Mat stitched = stitch_heads(make_stitch_maps(rig, so), render_heads(scene, rig, pose, options));
    cv::Mat reference = direct.rgb;
    if (scale > 1) {
      cv::resize(stitched, stitched, cv::Size(256, 128), 0, 0, cv::INTER_AREA);
      cv::resize(reference, reference, cv::Size(256, 128), 0, 0, cv::INTER_AREA);
    }
    db[scale - 1] = psnr(stitched, reference);
    EXPECT_LT(seam_parallax(rig, direct.depth, so).max_px, 1e-9);
  }
  std::printf(
      "stitch PSNR without offsets: %.2f dB at 256x128, %.2f dB rendered at 512x256 and box-filtered\n",
      db[0], db[1]);
  RecordProperty("stitch_psnr_db", std::to_string(db[1]));
  EXPECT_GE(db[0], 32.0);
  EXPECT_GE(db[1], 35.0);
}

TEST(MultiHeadRig, OffsetsCauseParallaxAtTheSeams) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  const PathFrame pose{0, "", 11.2, 9.9, 0.4, 1.0, kFrameOk, ""};
  RenderOptions options;
  options.width = 256;
  options.height = 128;
  const RenderedPanorama direct = render_panorama(scene, pose, options);
  const MultiHeadRig rig = small_rig(0.06);
  StitchOptions so;
  so.width = 256;
  so.height = 128;
  const SeamParallax far = seam_parallax(rig, direct.depth, so);
  so.stitch_distance = 2.5;
  const SeamParallax tuned = seam_parallax(rig, direct.depth, so);
  std::printf(
      "seam parallax with 6 cm offsets: mean %.3f px, max %.3f px (stitched at infinity); "
      "mean %.3f px, max %.3f px (at 2.5 m); overlap %.1f%%\n",
      far.mean_px, far.max_px, tuned.mean_px, tuned.max_px, 100 * far.overlap_fraction);
  EXPECT_GT(far.max_px, 0.1);
  EXPECT_LT(tuned.mean_px, far.mean_px);  // compensating at a typical distance helps
  EXPECT_GT(far.overlap_fraction, 0.1);
  const cv::Mat stitched = stitch_heads(make_stitch_maps(rig, so), render_heads(scene, rig, pose, options));
  const double db = psnr(stitched, direct.rgb);
  std::printf("stitch PSNR with 6 cm offsets (stitched at 2.5 m): %.2f dB\n", db);
  EXPECT_GT(db, 20.0);
}

TEST(CubeMap, FacesMatchDirectRendersAndRoundTrip) {
  const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  const PathFrame pose{0, "", 4.0, 7.5, -0.3, 1.0, kFrameOk, ""};
  RenderOptions options;
  options.width = 512;
  options.height = 256;
  const cv::Mat pano = render_panorama(scene, pose, options).rgb;
  const int size = 128;
  const std::array<cv::Mat, 6> faces = equirect_to_cube(pano, size);
  const Eigen::Matrix3d world_from_camera = world_from_camera_rotation(pose.heading);
  for (int f = 0; f < 6; ++f) {
    cv::Mat dirs(size, size, CV_64FC3);
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        const Eigen::Vector3d d =
            world_from_camera * cube_face_to_bearing(static_cast<CubeFace>(f), {i + 0.5, j + 0.5}, size);
        dirs.at<cv::Vec3d>(j, i) = cv::Vec3d(d.x(), d.y(), d.z());
      }
    const cv::Mat direct =
        render_directions(scene, {pose.x, pose.y, 1.6}, dirs, 2 * M_PI / options.width, options).rgb;
    const double db = psnr(faces[f], direct);
    EXPECT_GT(db, 24.0) << to_string(static_cast<CubeFace>(f));  // same view; resampling differences only
  }
  const cv::Mat back = cube_to_equirect(faces, 512, 256);
  EXPECT_GT(psnr(back, pano), 24.0);
}

}  // namespace
}  // namespace plenopath
