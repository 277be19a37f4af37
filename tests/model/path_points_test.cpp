// The tracker's points sidecar (model/path_points.h): version 2 with each point's frame, version 1 still
// read.
#include "model/path_points.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "model/error.h"

namespace plenopath {
namespace {

std::string temp_file(const std::string& name, const std::string& text) {
  const std::string file = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(file) << text;
  return file;
}

TEST(PathPoints, AVersion2FileKeepsEachPointsFrame) {
  std::vector<PathPoint> points(2);
  points[0].position = {1.25, -2.5, 0.75};
  points[0].piece = 0;
  points[0].observations = 4;
  points[0].frame = 12;
  points[1].position = {3, 4, -1};
  points[1].piece = 1;
  points[1].observations = 7;
  points[1].frame = -1;
  const std::string file = (std::filesystem::temp_directory_path() / "pp_v2.points.json").string();
  write_path_points_file(points, file);
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"version\":2"), std::string::npos);
  EXPECT_NE(text.find("[1.25000,-2.50000,0.75000,0,4,12]"), std::string::npos) << text;
  EXPECT_EQ(read_path_points_file(file), points);
}

TEST(PathPoints, AVersion1FileReadsWithoutFrames) {
  const std::string file = temp_file(
      "pp_v1.points.json",
      R"({"format":"plenopath-path-points","version":1,"units":"m","points":[[1,2,3,0,5],[4,5,6,1,3]]})");
  const std::vector<PathPoint> points = read_path_points_file(file);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].frame, -1);
  EXPECT_EQ(points[1].piece, 1);
  EXPECT_EQ(points[1].observations, 3);
}

TEST(PathPoints, ANewerVersionOrABadFrameIsAClearError) {
  const std::string newer = temp_file(
      "pp_v3.points.json", R"({"format":"plenopath-path-points","version":3,"units":"m","points":[]})");
  try {
    read_path_points_file(newer);
    FAIL() << "a version 3 file was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("newer"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("pp_v3.points.json"), std::string::npos) << e.what();
  }
  const std::string bad =
      temp_file("pp_bad.points.json",
                R"({"format":"plenopath-path-points","version":2,"units":"m","points":[[1,2,3,0,5,-7]]})");
  EXPECT_THROW(read_path_points_file(bad), Error);
  const std::string huge = temp_file(
      "pp_huge.points.json",
      R"({"format":"plenopath-path-points","version":2,"units":"m","points":[[1,2,3,0,5,99999999999999]]})");
  EXPECT_THROW(read_path_points_file(huge), Error);
}

TEST(PathPoints, RenumberingFollowsTheCapturePositions) {
  std::vector<PathPoint> points(3);
  points[0].frame = 0;
  points[1].frame = 2;
  points[2].frame = 5;  // outside the three positions: no longer known
  renumber_point_frames(&points, {10, 20, 30});
  EXPECT_EQ(points[0].frame, 10);
  EXPECT_EQ(points[1].frame, 30);
  EXPECT_EQ(points[2].frame, -1);
}

}  // namespace
}  // namespace plenopath
