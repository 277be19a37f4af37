// Features on the sphere: the seam and the poles. A rendered panorama and the same panorama rolled by a
// quarter turn (the camera turned by 90 deg) must give the same features at the same directions, the ones at
// the seam of one lying in the middle of the other.
#include "processing/stills/sphere_features.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/features2d.hpp>

#include "model/error.h"
#include "rig/spherical.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

constexpr double kDeg = M_PI / 180.0;

cv::Mat render_office(double x, double y, double heading, int width) {
  static const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions render;
  render.width = width;
  render.height = width / 2;
  render.depth = false;
  PathFrame pose;
  pose.x = x;
  pose.y = y;
  pose.heading = heading;
  return render_panorama(scene, pose, render).rgb;
}

// Column x of the result shows column (x + shift) mod w of `image`.
cv::Mat roll(const cv::Mat& image, int shift) {
  cv::Mat out(image.size(), image.type());
  const int w = image.cols;
  image.colRange(shift, w).copyTo(out.colRange(0, w - shift));
  image.colRange(0, shift).copyTo(out.colRange(w - shift, w));
  return out;
}

TEST(SphereFeatures, SameDirectionsWhenTheCameraTurnsAndAcrossTheSeam) {
  const int w = 1536;
  // In the open office, the seam (behind the camera) looking at the desks and a pillar.
  const cv::Mat image = render_office(3.2, 10.4, 0.4, w);
  const cv::Mat turned = roll(image, w / 4);  // column x shows azimuth + 90 deg
  SphereFeatureOptions options;
  options.work_width = w;
  const SphereFeatures f = detect_sphere_features(image, options);
  const SphereFeatures g = detect_sphere_features(turned, options);
  ASSERT_GT(f.keypoints.size(), 1000u);
  ASSERT_EQ(f.keypoints.size(), f.bearings.size());
  ASSERT_EQ(f.descriptors.rows, static_cast<int>(f.keypoints.size()));

  // g's bearing turned back by the 90 deg: azimuth + 90 deg is a rotation of -90 deg about +z.
  const Eigen::Matrix3d back = world_from_camera_rotation(-M_PI / 2);
  cv::BFMatcher matcher(cv::NORM_L2, true);
  std::vector<cv::DMatch> matches;
  matcher.match(f.descriptors, g.descriptors, matches);
  int same = 0, seam = 0, seam_features = 0;
  for (const Eigen::Vector3d& b : f.bearings)
    seam_features += std::abs(bearing_to_angles(b).azimuth) > 170 * kDeg;
  for (const cv::DMatch& m : matches) {
    const Eigen::Vector3d& a = f.bearings[static_cast<std::size_t>(m.queryIdx)];
    const Eigen::Vector3d b = back * g.bearings[static_cast<std::size_t>(m.trainIdx)];
    if (std::acos(std::min(1.0, a.dot(b))) < 0.02 * kDeg) {
      ++same;
      seam += std::abs(bearing_to_angles(a).azimuth) > 170 * kDeg;
    }
  }
  EXPECT_GT(same, 0.9 * static_cast<double>(f.keypoints.size()));
  // The seam is covered as well as anywhere (20 deg of 360 hold about 1/18 of the features) and found
  // again in the turned view, where it lies at azimuth -90.
  EXPECT_GT(seam_features, static_cast<int>(f.keypoints.size()) / 40);
  EXPECT_GT(seam, 0.9 * seam_features);
}

TEST(SphereFeatures, PolesAreLeftOutAndNothingIsDescribedTwice) {
  const int w = 1024;
  const cv::Mat image = render_office(5.0, 12.5, -1.0, w);
  SphereFeatureOptions options;
  options.work_width = w;
  options.max_abs_elevation_deg = 50.0;
  const SphereFeatures f = detect_sphere_features(image, options);
  ASSERT_GT(f.keypoints.size(), 300u);
  for (std::size_t k = 0; k < f.keypoints.size(); ++k) {
    const SphericalAngles angles = bearing_to_angles(f.bearings[k]);
    EXPECT_LE(std::abs(angles.elevation), 50.0 * kDeg + 1e-9);
    // The bearing is the keypoint's pixel centre (OpenCV's integer coordinates are pixel centres).
    const Eigen::Vector2d pixel = angles_to_equirect(angles, w, w / 2);
    EXPECT_NEAR(std::remainder(pixel.x() - 0.5 - f.keypoints[k].pt.x, w), 0.0, 1e-6);
    EXPECT_NEAR(pixel.y() - 0.5, f.keypoints[k].pt.y, 1e-6);
  }
  // The two copies keep disjoint halves: no keypoint twice (same place, size and orientation).
  for (std::size_t i = 0; i < f.keypoints.size(); ++i)
    for (std::size_t j = i + 1; j < f.keypoints.size(); ++j) {
      const cv::KeyPoint &a = f.keypoints[i], &b = f.keypoints[j];
      const bool same = std::abs(a.pt.x - b.pt.x) < 0.5f && std::abs(a.pt.y - b.pt.y) < 0.5f &&
                        std::abs(a.size - b.size) < 0.01f * a.size && std::abs(a.angle - b.angle) < 1.0f;
      EXPECT_FALSE(same) << i << " and " << j;
    }
}

TEST(SphereFeatures, RejectsAnImageThatIsNotEquirectangular) {
  const cv::Mat square(256, 256, CV_8UC3, cv::Scalar(128, 128, 128));
  EXPECT_THROW(detect_sphere_features(square), Error);
  EXPECT_THROW(detect_sphere_features(cv::Mat()), Error);
}

}  // namespace
}  // namespace plenopath
