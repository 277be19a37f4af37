// OpenSfM's reconstruction.json: world points a keyframe sees at known pixels (ARCHITECTURE.md's
// equirectangular convention) must project to those pixels through OpenSfM's spherical camera, written from
// its documentation in tests/processing/export/pose_files_check.py; plan frame and georeferenced alike.
#include "processing/export/opensfm_reconstruction.h"

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

std::string run_check(const fs::path& dir, const nlohmann::json& reconstruction, const std::string& truth) {
  std::ofstream(dir / "reconstruction.json") << reconstruction.dump(1);
  std::ofstream(dir / "truth.json") << truth;
  const std::string cmd = "/usr/bin/python3 '" + std::string(PLENOPATH_SOURCE_DIR) +
                          "/tests/processing/export/pose_files_check.py' opensfm '" +
                          (dir / "reconstruction.json").string() + "' '" + (dir / "truth.json").string() +
                          "' 2>&1";
  const interop_test::CommandResult r = interop_test::run_command(cmd);
  EXPECT_EQ(r.exit_code, 0) << cmd << "\n" << r.output;
  return r.output;
}

class OpenSfmTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("plenopath_opensfm_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(OpenSfmTest, SphericalShotsSeeWorldPointsAtOurPixelsInThePlanFrame) {
  Project p = interop_test::hand_made_project();
  p.geo.valid = false;
  const nlohmann::json rec = opensfm_reconstruction(p, kImages, 2048, 1024);
  ASSERT_EQ(rec.size(), 1u);
  EXPECT_FALSE(rec[0].contains("reference_lla"));
  EXPECT_EQ(rec[0]["shots"].size(), 2u);
  std::cout << run_check(dir_, rec, R"({"camera_height_m": 1.6, "width": 2048, "height": 1024, "frames": [
    {"index": 0, "x": 0, "y": 0, "heading_deg": 0, "shot": "k000000_full.jpg"},
    {"index": 2, "x": 74.6252, "y": 0, "heading_deg": 200, "shot": "k000002_full.jpg"}]})");
}

TEST_F(OpenSfmTest, GeoreferencedShotsAreInTheAnchorsTopocentricFrame) {
  Project p = interop_test::hand_made_project();
  p.geo.plan_rotation = M_PI / 6;  // plan +X 30 deg north of east
  p.geo.scale = 1.25;
  p.geo.plan_origin = {10.0, -4.0};
  const std::vector<std::pair<std::string, std::string>> files = opensfm_files(p, kImages, 512, 256);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[1].first, "reference_lla.json");
  const nlohmann::json lla = nlohmann::json::parse(files[1].second);
  EXPECT_EQ(lla["latitude"], 48.0);
  EXPECT_EQ(lla["longitude"], 2.0);
  EXPECT_EQ(lla["altitude"], 35.0);
  std::cout << run_check(dir_, nlohmann::json::parse(files[0].second),
                         R"({"camera_height_m": 1.6, "width": 512, "height": 256,
    "anchor": {"rotation_deg": 30, "scale": 1.25, "origin": [10, -4],
               "reference_lla": {"latitude": 48, "longitude": 2, "altitude": 35}},
    "frames": [
    {"index": 0, "x": 0, "y": 0, "heading_deg": 0, "shot": "k000000_full.jpg"},
    {"index": 2, "x": 74.6252, "y": 0, "heading_deg": 200, "shot": "k000002_full.jpg"}]})");
}

TEST(OpenSfm, KeyframesWithoutAPoseAreAnError) {
  Project p = interop_test::hand_made_project();
  EXPECT_THROW(opensfm_reconstruction(p, {{5, "images/a.jpg", "images/b.jpg", ""}}, 64, 32), Error);
}

}  // namespace
}  // namespace plenopath
