// nerfstudio's transforms.json: the ray nerfstudio's EQUIRECTANGULAR camera shoots through a pixel (its
// cameras.py, written out in tests/processing/export/pose_files_check.py) must be the bearing
// ARCHITECTURE.md's convention gives that pixel, in the plan and in the anchor's topocentric frame.
#include "processing/export/nerfstudio_transforms.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "model/error.h"
#include "tests/processing/export/interop_test_util.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

const std::vector<KeyframeImageFiles> kImages = {
    {0, "images/k000000_preview.js", "images/k000000_full.jpg", ""},
    {2, "images/k000002_preview.js", "images/k000002_full.jpg", ""}};

void check(const nlohmann::json& transforms, const std::string& truth) {
  const fs::path dir = fs::temp_directory_path() / ("plenopath_nerfstudio_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "transforms.json") << transforms.dump(1);
  std::ofstream(dir / "truth.json") << truth;
  const std::string cmd = "/usr/bin/python3 '" + std::string(PLENOPATH_SOURCE_DIR) +
                          "/tests/processing/export/pose_files_check.py' nerfstudio '" +
                          (dir / "transforms.json").string() + "' '" + (dir / "truth.json").string() +
                          "' 2>&1";
  const interop_test::CommandResult r = interop_test::run_command(cmd);
  EXPECT_EQ(r.exit_code, 0) << cmd << "\n" << r.output;
  std::cout << r.output;
  fs::remove_all(dir);
}

TEST(NerfstudioTransforms, RaysThroughPixelsAreOurBearingsInThePlan) {
  Project p = interop_test::hand_made_project();
  p.geo.valid = false;
  const nlohmann::json t = nerfstudio_transforms(p, kImages, 1024, 512);
  EXPECT_EQ(t["frames"].size(), 2u);
  check(t, R"({"camera_height_m": 1.6, "width": 1024, "height": 512, "frames": [
    {"index": 0, "x": 0, "y": 0, "heading_deg": 0, "shot": "k000000_full.jpg"},
    {"index": 2, "x": 74.6252, "y": 0, "heading_deg": 200, "shot": "k000002_full.jpg"}]})");
}

TEST(NerfstudioTransforms, GeoreferencedRaysAreInTheAnchorsFrame) {
  Project p = interop_test::hand_made_project();
  p.geo.plan_rotation = -M_PI / 4;
  p.geo.scale = 0.8;
  p.geo.plan_origin = {-3.0, 2.0};
  check(nerfstudio_transforms(p, kImages, 256, 128),
        R"({"camera_height_m": 1.6, "width": 256, "height": 128,
    "anchor": {"rotation_deg": -45, "scale": 0.8, "origin": [-3, 2]}, "frames": [
    {"index": 0, "x": 0, "y": 0, "heading_deg": 0, "shot": "k000000_full.jpg"},
    {"index": 2, "x": 74.6252, "y": 0, "heading_deg": 200, "shot": "k000002_full.jpg"}]})");
}

TEST(NerfstudioTransforms, KeyframesWithoutAPoseAreAnError) {
  EXPECT_THROW(
      nerfstudio_transforms(interop_test::hand_made_project(), {{4, "a.jpg", "images/b.jpg", ""}}, 64, 32),
      Error);
}

}  // namespace
}  // namespace plenopath
