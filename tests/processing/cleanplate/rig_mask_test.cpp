// The rig for clean plates: the tracker's static mask made again from the capture, joined by the author's
// mask image; errors name the file.
#include "processing/cleanplate/rig_mask.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "model/error.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

namespace fs = std::filesystem;

struct Capture {
  FloorPlan plan = make_office_sample_plan();
  SyntheticScene scene = build_synthetic_scene(plan);
  CameraPath path;
  RenderOptions render;
  explicit Capture(bool trolley) {
    AutoWalkOptions walk;
    walk.max_frames = 70;
    path = auto_walk(plan, walk);
    render.width = 512;
    render.height = 256;
    render.depth = false;
    render.trolley = render.operator_person = trolley;
  }
  cv::Mat frame(int k) const { return render_panorama(scene, path.frames[k], render).rgb; }
};

TEST(RigMask, TheTrolleyIsFoundAndTheAuthorsMaskJoinsIt) {
  const Capture capture(true);
  const cv::Size size(512, 256);
  const cv::Mat found = rig_mask_of_capture([&](int k) { return capture.frame(k); }, 70, size, std::string());
  ASSERT_FALSE(found.empty());
  // The trolley covers the bottom rows (the nadir) in every frame; the zenith side is the scene.
  EXPECT_GT(cv::countNonZero(found.row(size.height - 2)), size.width * 9 / 10);
  // (the few rows at the zenith are one point of the ceiling each: they never change either)
  EXPECT_LT(cv::countNonZero(found.rowRange(size.height / 20, size.height / 3)), size.width / 4);
  // The author's mask (black = rig), at another size, joins it: a block at the top left.
  const fs::path file =
      fs::temp_directory_path() / ("plenopath_rig_mask_" + std::to_string(getpid()) + ".png");
  cv::Mat author(128, 256, CV_8U, cv::Scalar(255));
  author(cv::Rect(0, 0, 32, 16)).setTo(0);
  cv::imwrite(file.string(), author);
  const cv::Mat joined =
      rig_mask_of_capture([&](int k) { return capture.frame(k); }, 70, size, file.string());
  EXPECT_EQ(joined.at<std::uint8_t>(10, 20), 255);
  EXPECT_EQ(cv::countNonZero(found & ~joined), 0);
  fs::remove(file);
}

TEST(RigMask, NoRigNoMaskAndAMissingFileIsNamed) {
  const Capture capture(false);
  EXPECT_TRUE(
      rig_mask_of_capture([&](int k) { return capture.frame(k); }, 70, {512, 256}, std::string()).empty());
  try {
    rig_mask_of_capture([&](int k) { return capture.frame(k); }, 70, {512, 256}, "/nonexistent/rig.png");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/rig.png"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plenopath
