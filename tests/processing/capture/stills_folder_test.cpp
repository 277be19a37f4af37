// A folder of still panoramas ordered and located by their own metadata: JPEGs tagged by ExifTool (an
// independent writer) with times that contradict the names' order and with GPS positions; the expected
// order, times and positions are the ones given to ExifTool.
#include "processing/capture/stills_folder.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "processing/capture/frame_source.h"
#include "processing/capture/gps_track.h"
#include "tests/processing/capture/capture_test_util.h"
#include "tests/processing/capture/video_test_util.h"

namespace plenopath {
namespace {

struct Still {
  std::string name;
  std::string time;                        // EXIF DateTimeOriginal, "" = none
  double latitude = 0.0, longitude = 0.0;  // 0 = no GPS
};

void write_stills(const test::TempFolder& dir, const std::vector<Still>& stills) {
  for (std::size_t k = 0; k < stills.size(); ++k) {
    const std::string path = dir / stills[k].name;
    ASSERT_TRUE(cv::imwrite(path, test::numbered_frame(static_cast<int>(k), 128, 64)));
    std::string args;
    if (!stills[k].time.empty()) args += " '-DateTimeOriginal=" + stills[k].time + "'";
    if (stills[k].latitude != 0.0)
      args += " -GPSLatitude=" + std::to_string(stills[k].latitude) +
              " -GPSLatitudeRef=N -GPSLongitude=" + std::to_string(stills[k].longitude) +
              " -GPSLongitudeRef=E";
    if (args.empty()) continue;
    const std::string command =
        "exiftool -q -q -overwrite_original" + args + " '" + path + "' >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
  }
}

class StillsFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_tool("exiftool", "-ver"))
      GTEST_FAIL() << "exiftool (libimage-exiftool-perl) is needed: cmake/install-deps.sh";
  }
  test::TempFolder dir_;
};

TEST_F(StillsFolderTest, OrderedByTheTimeTheyWereShotWithTheirGps) {
  // Names from two cameras merged: the times interleave them.
  write_stills(dir_, {{"A_001.jpg", "2026:11:30 10:00:00", 47.0001, 8.5001},
                      {"A_002.jpg", "2026:11:30 10:02:30", 47.0003, 8.5003},
                      {"B_001.jpg", "2026:11:30 10:01:10", 47.0002, 8.5002},
                      {"B_002.jpg", "2026:11:30 10:03:00", 0.0, 0.0}});
  const auto source = FrameSource::open(dir_.path().string());
  const StillsFolder folder = stills_folder(*source);
  EXPECT_TRUE(folder.ordered_by_time);
  EXPECT_EQ(folder.order, "by EXIF DateTimeOriginal");
  EXPECT_EQ(folder.capture.frame_names,
            (std::vector<std::string>{"A_001.jpg", "B_001.jpg", "A_002.jpg", "B_002.jpg"}));
  EXPECT_EQ(folder.capture.frame_times_s, (std::vector<double>{0.0, 70.0, 150.0, 180.0}));
  EXPECT_EQ(folder.stills_with_gps, 3);
  ASSERT_EQ(folder.capture.gps_track.size(), 3u);
  EXPECT_NEAR(folder.capture.gps_track[1].latitude_deg, 47.0002, 1e-6);
  // Each still finds its own fix through the GPS matching the anchors use; the one without has none.
  GpsMatchOptions match;
  match.time_offset_s = folder.capture.gps_time_offset_s;
  const double expected_lat[] = {47.0001, 47.0002, 47.0003};
  for (int k = 0; k < 3; ++k) {
    const FrameGps g =
        gps_at_time(folder.capture.gps_track, match.time_offset_s + folder.capture.frame_time_s(k), match);
    ASSERT_TRUE(g.valid) << k;
    EXPECT_NEAR(g.latitude_deg, expected_lat[k], 1e-6) << k;
  }
  EXPECT_FALSE(gps_at_time(folder.capture.gps_track, match.time_offset_s + 180.0, match).valid);

  // Re-opened from the capture (as a project does), the frames come in that order.
  const auto reopened = FrameSource::open_capture(folder.capture);
  ASSERT_EQ(reopened->frame_count(), 4);
  EXPECT_EQ(reopened->frame_name(1), "B_001.jpg");
  EXPECT_EQ(test::decode_frame_number(reopened->read(1)), 2);  // B_001 was written third
}

TEST_F(StillsFolderTest, AStillWithoutTimeKeepsTheNamesOrderAndSaysWhy) {
  write_stills(dir_, {{"s1.jpg", "2026:11:30 10:05:00"}, {"s2.jpg", ""}, {"s10.jpg", "2026:11:30 10:00:00"}});
  const auto source = FrameSource::open(dir_.path().string());
  const StillsFolder folder = stills_folder(*source);
  EXPECT_FALSE(folder.ordered_by_time);
  EXPECT_EQ(folder.order, "by file name: 1 of 3 stills have no EXIF DateTimeOriginal");
  EXPECT_EQ(folder.capture.frame_names, (std::vector<std::string>{"s1.jpg", "s2.jpg", "s10.jpg"}));
  EXPECT_TRUE(folder.capture.frame_times_s.empty());
  EXPECT_TRUE(folder.capture.gps_track.empty());
}

TEST_F(StillsFolderTest, PartialPanoramasAreNamedInTheNotes) {
  write_stills(dir_, {{"p1.jpg", ""}, {"p2.jpg", ""}});
  const std::string command = "exiftool -q -q -overwrite_original -XMP-GPano:ProjectionType=cylindrical '" +
                              (dir_ / "p2.jpg") + "' >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const StillsFolder folder = stills_folder(*FrameSource::open(dir_.path().string()));
  ASSERT_EQ(folder.notes.size(), 1u);
  EXPECT_NE(folder.notes[0].find("p2.jpg: GPano: projection \"cylindrical\""), std::string::npos)
      << folder.notes[0];
}

}  // namespace
}  // namespace plenopath
