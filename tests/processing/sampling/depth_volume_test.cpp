// Depth volume against closed forms: a box room's ray lengths and volume, a sphere's mean range.
#include "processing/sampling/depth_volume.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/error.h"
#include "rig/spherical.h"

namespace plenopath {
namespace {

// Range from c along the pixel centre's ray to the walls of the box [0,size]: the nearest exit plane.
cv::Mat box_room_depth(const Eigen::Vector3d& size, const Eigen::Vector3d& c, int w, int h) {
  cv::Mat depth(h, w, CV_32F);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3d d = equirect_to_bearing({u + 0.5, v + 0.5}, w, h);
      double t = std::numeric_limits<double>::infinity();
      for (int axis = 0; axis < 3; ++axis) {
        if (d[axis] > 1e-12) t = std::min(t, (size[axis] - c[axis]) / d[axis]);
        if (d[axis] < -1e-12) t = std::min(t, -c[axis] / d[axis]);
      }
      depth.at<float>(v, u) = static_cast<float>(t);
    }
  return depth;
}

TEST(DepthVolume, BoxRoomVolumeWithinOnePercent) {
  const Eigen::Vector3d size(6.0, 4.0, 2.8);
  for (const Eigen::Vector3d& c : {Eigen::Vector3d(3.0, 2.0, 1.4), Eigen::Vector3d(1.0, 3.2, 1.6)}) {
    const cv::Mat depth = box_room_depth(size, c, 1024, 512);
    const DepthVolume v = depth_volume(depth);
    EXPECT_NEAR(v.star_volume / (size.x() * size.y() * size.z()), 1.0, 0.01) << c.transpose();
    EXPECT_NEAR(v.covered_solid_angle, 4 * M_PI, 1e-9);
    EXPECT_EQ(v.valid_pixels, 1024 * 512);
    // Millimetres give the same answer.
    cv::Mat mm;
    depth.convertTo(mm, CV_16U, 1000.0);
    EXPECT_NEAR(depth_volume(mm).star_volume / v.star_volume, 1.0, 1e-3);
  }
}

TEST(DepthVolume, SphereMeanRangeAndHoles) {
  cv::Mat depth(256, 512, CV_32F, cv::Scalar(2.5f));
  DepthVolume v = depth_volume(depth);
  EXPECT_NEAR(v.mean_range, 2.5, 1e-9);
  EXPECT_NEAR(v.star_volume, 4.0 / 3.0 * M_PI * std::pow(2.5, 3), 1e-6);
  // The lower half has no hit: half the sphere is covered, half the volume.
  depth(cv::Rect(0, 128, 512, 128)).setTo(0.0f);
  v = depth_volume(depth);
  EXPECT_NEAR(v.covered_solid_angle, 2 * M_PI, 1e-9);
  EXPECT_NEAR(v.star_volume, 2.0 / 3.0 * M_PI * std::pow(2.5, 3), 1e-6);
  EXPECT_THROW(depth_volume(cv::Mat()), Error);
  EXPECT_THROW(depth_volume(cv::Mat(4, 8, CV_8U, cv::Scalar(1))), Error);
}

TEST(DepthVolume, DetectsSignificantChanges) {
  auto vol = [](double star) {
    DepthVolume v;
    v.star_volume = star;
    v.mean_range = std::cbrt(star);
    v.covered_solid_angle = 4 * M_PI;
    return v;
  };
  // Corridor (20 m^3), a slow drift, a hall (100 m^3), a frame without depth, back to a corridor.
  std::vector<DepthVolume> seq = {vol(20), vol(21), vol(22), vol(100), vol(104), DepthVolume(), vol(25)};
  EXPECT_EQ(detect_volume_changes(seq), (std::vector<int>{3, 6}));
  VolumeChangeOptions bad;
  bad.log_ratio_threshold = 0.0;
  EXPECT_THROW(detect_volume_changes(seq, bad), Error);
}

}  // namespace
}  // namespace plenopath
