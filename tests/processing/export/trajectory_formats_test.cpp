// The TUM trajectory, read back by an independent reader (tests/processing/export/pose_files_check.py, which
// builds the rotation from the quaternion itself) and checked against the path's headings and positions.
#include "processing/export/trajectory_formats.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/LU>
#include <filesystem>
#include <fstream>

#include "tests/processing/export/interop_test_util.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

TEST(TumTrajectory, PythonReadsPosesThatFaceThePathsHeadings) {
  const fs::path dir = fs::temp_directory_path() / ("plenopath_tum_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Project p = interop_test::hand_made_project();
  // A fourth frame facing backwards along -X and a fifth just below +X: the quaternion's sign and wrap.
  p.path.frames.push_back({7, "", -2.5, 3.25, M_PI, 1.0, 0, ""});
  p.path.frames.push_back({8, "", 1.0, -1.0, -0.001, 1.0, 0, ""});
  std::ofstream(dir / "trajectory.tum") << tum_trajectory(p);
  // The truth, as written by hand above (frame rate 10: frame k at k / 10 s; camera 1.6 m high).
  std::ofstream(dir / "truth.json") << R"({"frame_rate": 10, "camera_height_m": 1.6, "frames": [
    {"index": 0, "x": 0, "y": 0, "heading_deg": 0},
    {"index": 1, "x": 0, "y": 111.1903, "heading_deg": 90},
    {"index": 2, "x": 74.6252, "y": 0, "heading_deg": 200},
    {"index": 7, "x": -2.5, "y": 3.25, "heading_deg": 180},
    {"index": 8, "x": 1.0, "y": -1.0, "heading_deg": -0.0572957795}]})";
  const std::string cmd = "/usr/bin/python3 '" + std::string(PLENOPATH_SOURCE_DIR) +
                          "/tests/processing/export/pose_files_check.py' tum '" +
                          (dir / "trajectory.tum").string() + "' '" + (dir / "truth.json").string() +
                          "' 2>&1";
  const interop_test::CommandResult r = interop_test::run_command(cmd);
  EXPECT_EQ(r.exit_code, 0) << cmd << "\n" << r.output;
  std::cout << r.output;
  fs::remove_all(dir);
}

TEST(TumTrajectory, CameraAxesAreRightDownForward) {
  // Heading 90 deg (facing plan +Y): right of the centre is +X, down is -Z.
  const Eigen::Matrix3d r = world_from_pano_camera(M_PI / 2);
  EXPECT_TRUE(r.col(0).isApprox(Eigen::Vector3d(1, 0, 0), 1e-12)) << r;
  EXPECT_TRUE(r.col(1).isApprox(Eigen::Vector3d(0, 0, -1), 1e-12)) << r;
  EXPECT_TRUE(r.col(2).isApprox(Eigen::Vector3d(0, 1, 0), 1e-12)) << r;
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
}

}  // namespace
}  // namespace plenopath
