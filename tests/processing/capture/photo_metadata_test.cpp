// Still panoramas' metadata: JPEGs tagged by ExifTool (an independent writer: Perl, not exiv2), read back
// by read_photo_metadata. Expected times are hand-computed (`date -u -d ... +%s`), positions the values
// given to ExifTool.
#include "processing/capture/photo_metadata.h"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "tests/processing/capture/capture_test_util.h"
#include "tests/processing/capture/video_test_util.h"

namespace plenopath {
namespace {

// A small JPEG tagged with `exiftool_args` (ExifTool's -TAG=VALUE arguments).
std::string tagged_jpeg(const test::TempFolder& dir, const std::string& name,
                        const std::string& exiftool_args) {
  const std::string path = dir / name;
  EXPECT_TRUE(cv::imwrite(path, test::numbered_frame(3, 64, 32)));
  if (!exiftool_args.empty()) {
    const std::string command =
        "exiftool -q -q -overwrite_original " + exiftool_args + " '" + path + "' > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
  }
  return path;
}

class PhotoMetadataTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_tool("exiftool", "-ver"))
      GTEST_FAIL() << "exiftool (libimage-exiftool-perl) is needed: cmake/install-deps.sh";
  }
  test::TempFolder dir_;
};

TEST_F(PhotoMetadataTest, ATimeWithSubSecondsAndZoneIsUtc) {
  const std::string file = tagged_jpeg(dir_, "a.jpg",
                                       "'-DateTimeOriginal=2026:11:30 14:05:09' -SubSecTimeOriginal=25 "
                                       "-OffsetTimeOriginal=+01:00");
  const PhotoMetadata m = read_photo_metadata(file);
  ASSERT_TRUE(m.capture_time_s.has_value());
  EXPECT_TRUE(m.time_is_utc);
  EXPECT_NEAR(*m.capture_time_s, 1796043909.25, 1e-6);  // 2026-11-30 13:05:09.25 UTC
  EXPECT_TRUE(m.notes.empty());
  EXPECT_FALSE(m.has_gps());
}

TEST_F(PhotoMetadataTest, ATimeWithoutZoneReadsAsTheClockShows) {
  const std::string file = tagged_jpeg(dir_, "b.jpg", "'-DateTimeOriginal=2000:02:29 00:00:00'");
  const PhotoMetadata m = read_photo_metadata(file);
  ASSERT_TRUE(m.capture_time_s.has_value());
  EXPECT_FALSE(m.time_is_utc);
  EXPECT_DOUBLE_EQ(*m.capture_time_s, 951782400.0);  // a leap day
}

TEST_F(PhotoMetadataTest, GpsNorthEastAndSouthWestBelowSeaLevel) {
  const PhotoMetadata ne = read_photo_metadata(
      tagged_jpeg(dir_, "ne.jpg",
                  "-GPSLatitude=47.376887 -GPSLatitudeRef=N -GPSLongitude=8.541694 -GPSLongitudeRef=E "
                  "-GPSAltitude=408.5 -GPSAltitudeRef#=0"));
  ASSERT_TRUE(ne.has_gps());
  EXPECT_NEAR(*ne.latitude_deg, 47.376887, 1e-6);
  EXPECT_NEAR(*ne.longitude_deg, 8.541694, 1e-6);
  EXPECT_NEAR(ne.altitude_m, 408.5, 1e-6);
  const PhotoMetadata sw = read_photo_metadata(
      tagged_jpeg(dir_, "sw.jpg",
                  "-GPSLatitude=33.868820 -GPSLatitudeRef=S -GPSLongitude=151.209296 -GPSLongitudeRef=W "
                  "-GPSAltitude=28 -GPSAltitudeRef#=1"));
  ASSERT_TRUE(sw.has_gps());
  EXPECT_NEAR(*sw.latitude_deg, -33.868820, 1e-6);
  EXPECT_NEAR(*sw.longitude_deg, -151.209296, 1e-6);
  EXPECT_NEAR(sw.altitude_m, -28.0, 1e-6);
}

TEST_F(PhotoMetadataTest, GPanoOfAFullAndOfACroppedPanorama) {
  const PhotoMetadata full = read_photo_metadata(
      tagged_jpeg(dir_, "full.jpg",
                  "-XMP-GPano:ProjectionType=equirectangular -XMP-GPano:PoseHeadingDegrees=123.5 "
                  "-XMP-GPano:FullPanoWidthPixels=64 -XMP-GPano:FullPanoHeightPixels=32 "
                  "-XMP-GPano:CroppedAreaImageWidthPixels=64 -XMP-GPano:CroppedAreaImageHeightPixels=32 "
                  "-XMP-GPano:CroppedAreaLeftPixels=0 -XMP-GPano:CroppedAreaTopPixels=0"));
  EXPECT_EQ(full.projection, "equirectangular");
  ASSERT_TRUE(full.pose_heading_deg.has_value());
  EXPECT_DOUBLE_EQ(*full.pose_heading_deg, 123.5);
  EXPECT_EQ(full.full_width, 64);
  EXPECT_EQ(full.cropped_height, 32);
  EXPECT_EQ(full.partial_reason(), "");

  const PhotoMetadata cropped = read_photo_metadata(
      tagged_jpeg(dir_, "cropped.jpg",
                  "-XMP-GPano:ProjectionType=equirectangular -XMP-GPano:FullPanoWidthPixels=8000 "
                  "-XMP-GPano:FullPanoHeightPixels=4000 -XMP-GPano:CroppedAreaImageWidthPixels=8000 "
                  "-XMP-GPano:CroppedAreaImageHeightPixels=3000 -XMP-GPano:CroppedAreaTopPixels=500"));
  EXPECT_EQ(cropped.cropped_top, 500);
  EXPECT_EQ(cropped.partial_reason(), "GPano: cropped to 8000 x 3000 of 8000 x 4000");

  const PhotoMetadata cylinder =
      read_photo_metadata(tagged_jpeg(dir_, "cyl.jpg", "-XMP-GPano:ProjectionType=cylindrical"));
  EXPECT_EQ(cylinder.partial_reason(), "GPano: projection \"cylindrical\", not equirectangular");
}

TEST_F(PhotoMetadataTest, NoMetadataIsNoNote) {
  const PhotoMetadata m = read_photo_metadata(tagged_jpeg(dir_, "plain.jpg", ""));
  EXPECT_FALSE(m.capture_time_s.has_value());
  EXPECT_FALSE(m.has_gps());
  EXPECT_EQ(m.projection, "");
  EXPECT_TRUE(m.notes.empty());
}

TEST_F(PhotoMetadataTest, DamagedOrMissingFilesGiveANoteNotAThrow) {
  const std::string junk = dir_ / "junk.jpg";
  const std::string bytes(
      "\xff\xd8\xff\xe1\x00\x10"
      "Exif\x00\x00"
      "garbage that is not TIFF",
      36);
  std::ofstream(junk, std::ios::binary) << bytes;
  const PhotoMetadata damaged = read_photo_metadata(junk);
  EXPECT_FALSE(damaged.capture_time_s.has_value());
  const PhotoMetadata missing = read_photo_metadata(dir_ / "missing.jpg");
  ASSERT_FALSE(missing.notes.empty());
  EXPECT_NE(missing.notes.front().find("unreadable"), std::string::npos) << missing.notes.front();
}

TEST(ExifDateTime, ParsesAndRefusesByHand) {
  EXPECT_DOUBLE_EQ(*parse_exif_date_time("1970:01:01 00:00:00"), 0.0);
  EXPECT_DOUBLE_EQ(*parse_exif_date_time("2026-11-30 13:05:09"), 1796043909.0);
  EXPECT_DOUBLE_EQ(*parse_exif_date_time("2000:02:29 00:00:00 "), 951782400.0);
  for (const char* bad :
       {"", "    :  :     :  :  ", "2026:13:01 00:00:00", "2026:02:29 00:00:00", "2026:11:30 24:00:00",
        "2026:11:30", "2026:11-30 10:00:00", "2026:11:30 10:00:00x", "0000:00:00 00:00:00"})
    EXPECT_FALSE(parse_exif_date_time(bad).has_value()) << bad;
  EXPECT_DOUBLE_EQ(*parse_exif_time_offset("+05:30"), 19800.0);
  EXPECT_DOUBLE_EQ(*parse_exif_time_offset("-08:00"), -28800.0);
  EXPECT_FALSE(parse_exif_time_offset("08:00").has_value());
  EXPECT_FALSE(parse_exif_time_offset("+25:00").has_value());
}

}  // namespace
}  // namespace plenopath
