// Checks the project's reading of directions against panoramas from an independent renderer (POV-Ray,
// tests/data/convention/README.md): four coloured boxes at known world directions.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "rig/spherical.h"

namespace plenopath {
namespace {

struct Box {
  const char* name;
  double world_angle_deg;
  cv::Vec3b bgr_min, bgr_max;  // colour test
};

// Circular mean azimuth (radians) of the pixels near the horizon whose colour matches.
double measured_azimuth(const cv::Mat& img, const Box& box) {
  double sx = 0, sy = 0;
  int n = 0;
  for (int v = 0; v < img.rows; ++v) {
    const double elevation = equirect_to_angles({0.0, v + 0.5}, img.cols, img.rows).elevation;
    if (std::abs(elevation) > 0.3) continue;
    for (int u = 0; u < img.cols; ++u) {
      const cv::Vec3b p = img.at<cv::Vec3b>(v, u);
      bool match = true;
      for (int k = 0; k < 3; ++k) match = match && p[k] >= box.bgr_min[k] && p[k] <= box.bgr_max[k];
      if (!match) continue;
      const double a = equirect_to_angles({u + 0.5, v + 0.5}, img.cols, img.rows).azimuth;
      sx += std::cos(a);
      sy += std::sin(a);
      ++n;
    }
  }
  EXPECT_GT(n, 20) << box.name << " not found";
  return std::atan2(sy, sx);
}

TEST(ConventionFixture, BoxesAppearWhereTheConventionSays) {
  const Box boxes[] = {
      {"red", 0.0, {0, 0, 120}, {90, 90, 255}},
      {"green", 90.0, {0, 120, 0}, {90, 255, 90}},
      {"blue", 180.0, {120, 0, 0}, {255, 90, 90}},
      {"yellow", -90.0, {0, 120, 120}, {90, 255, 255}},
  };
  for (double heading_deg : {0.0, 30.0, 90.0}) {
    const std::string file = std::string(PLENOPATH_TEST_DATA_DIR) + "/convention/pano_heading" +
                             std::to_string(int(heading_deg)) + ".png";
    const cv::Mat img = cv::imread(file, cv::IMREAD_COLOR);
    ASSERT_FALSE(img.empty()) << file;
    for (const Box& box : boxes) {
      const double expected =
          azimuth_of_world_angle(heading_deg * M_PI / 180, box.world_angle_deg * M_PI / 180);
      const double measured = measured_azimuth(img, box);
      EXPECT_NEAR(std::remainder(measured - expected, 2 * M_PI) * 180 / M_PI, 0.0, 0.5)
          << file << " " << box.name;
    }
  }
}

}  // namespace
}  // namespace plenopath
