// GPano XMP and EXIF GPS written into a keyframe JPEG in memory: exiftool (the reference reader of these
// tags) and our own photo_metadata reader must both read the project's values back, and the image must be
// intact.
#include "processing/export/keyframe_metadata.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "model/error.h"
#include "processing/capture/photo_metadata.h"
#include "tests/processing/export/interop_test_util.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

std::vector<unsigned char> test_jpeg(int width) {
  cv::Mat image(width / 2, width, CV_8UC3);
  cv::randu(image, 0, 255);
  std::vector<unsigned char> bytes;
  cv::imencode(".jpg", image, bytes, {cv::IMWRITE_JPEG_QUALITY, 90, cv::IMWRITE_JPEG_PROGRESSIVE, 1});
  return bytes;
}

class KeyframeMetadataTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("plenopath_keyframe_metadata_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path save(const std::string& name, const std::vector<unsigned char>& bytes) {
    std::ofstream(dir_ / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return dir_ / name;
  }
  nlohmann::json exiftool(const fs::path& file) {
    const interop_test::CommandResult r =
        interop_test::run_command("exiftool -j -n -G '" + file.string() + "' 2>&1");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return nlohmann::json::parse(r.output).at(0);
  }
  fs::path dir_;
};

TEST_F(KeyframeMetadataTest, ExiftoolAndOurReaderSeeGPanoAndGps) {
  if (!interop_test::have_program("exiftool")) GTEST_SKIP() << "exiftool is not installed";
  // Keyframe 2 of the hand-made project: 1/1000 deg east of the anchor (48 N, 2 E), heading 200 deg from
  // plan +X = east, i.e. facing 250 deg (WSW) on the compass, the camera 1.6 m above the anchor's 35 m.
  const Project p = interop_test::hand_made_project();
  const std::vector<unsigned char> plain = test_jpeg(512);
  const std::vector<unsigned char> tagged = with_photo_tags(plain, keyframe_photo_tags(p, 2), "k2.jpg");
  const fs::path file = save("k2.jpg", tagged);

  const nlohmann::json e = exiftool(file);
  EXPECT_EQ(e.at("XMP:ProjectionType"), "equirectangular");
  EXPECT_EQ(e.at("XMP:UsePanoramaViewer"), true) << e.dump(1);
  EXPECT_EQ(e.at("XMP:FullPanoWidthPixels"), 512);
  EXPECT_EQ(e.at("XMP:FullPanoHeightPixels"), 256);
  EXPECT_EQ(e.at("XMP:CroppedAreaImageWidthPixels"), 512);
  EXPECT_EQ(e.at("XMP:CroppedAreaImageHeightPixels"), 256);
  EXPECT_EQ(e.at("XMP:CroppedAreaLeftPixels"), 0);
  EXPECT_EQ(e.at("XMP:CroppedAreaTopPixels"), 0);
  EXPECT_NEAR(e.at("XMP:PoseHeadingDegrees").get<double>(), 250.0, 0.005);
  EXPECT_NEAR(e.at("Composite:GPSLatitude").get<double>(), 48.0, 1e-8);
  EXPECT_NEAR(e.at("Composite:GPSLongitude").get<double>(), 2.001, 2e-7);
  EXPECT_NEAR(e.at("Composite:GPSAltitude").get<double>(), 36.6, 0.01);
  EXPECT_EQ(e.at("EXIF:GPSImgDirectionRef"), "T");
  EXPECT_NEAR(e.at("EXIF:GPSImgDirection").get<double>(), 250.0, 0.005);
  EXPECT_EQ(e.at("File:ImageWidth"), 512);

  const PhotoMetadata m = read_photo_metadata(file.string());
  EXPECT_TRUE(m.notes.empty()) << m.notes.front();
  EXPECT_EQ(m.projection, "equirectangular");
  EXPECT_EQ(m.partial_reason(), "");
  ASSERT_TRUE(m.pose_heading_deg.has_value());
  EXPECT_NEAR(*m.pose_heading_deg, 250.0, 0.005);
  ASSERT_TRUE(m.has_gps());
  EXPECT_NEAR(*m.latitude_deg, 48.0, 1e-8);
  EXPECT_NEAR(*m.longitude_deg, 2.001, 2e-7);
  EXPECT_NEAR(m.altitude_m, 36.6, 0.01);

  // The pixels are those encoded: exiv2 rewrote the metadata segments only.
  const cv::Mat before = cv::imdecode(plain, cv::IMREAD_COLOR), after = cv::imread(file.string());
  ASSERT_EQ(after.size(), before.size());
  EXPECT_EQ(cv::norm(before, after, cv::NORM_INF), 0.0);
}

TEST_F(KeyframeMetadataTest, WithoutAnAnchorNoGpsAndPlanNorth) {
  if (!interop_test::have_program("exiftool")) GTEST_SKIP() << "exiftool is not installed";
  Project p = interop_test::hand_made_project();
  p.geo.valid = false;
  // Keyframe 0 faces plan +X; with plan +Y as north, that is east: 90 deg.
  const fs::path file = save("k0.jpg", with_photo_tags(test_jpeg(256), keyframe_photo_tags(p, 0), "k0.jpg"));
  const nlohmann::json e = exiftool(file);
  EXPECT_EQ(e.at("XMP:ProjectionType"), "equirectangular");
  EXPECT_NEAR(e.at("XMP:PoseHeadingDegrees").get<double>(), 90.0, 0.005);
  EXPECT_FALSE(e.contains("EXIF:GPSLatitude")) << e.dump(1);
  EXPECT_FALSE(e.contains("EXIF:GPSImgDirection")) << e.dump(1);
  EXPECT_FALSE(read_photo_metadata(file.string()).has_gps());
}

TEST(KeyframeMetadata, SouthWestAndBelowTheEllipsoid) {
  // Hemisphere references and a negative altitude (the Dead Sea shore): read back by our reader.
  Project p = interop_test::hand_made_project();
  p.geo.latitude_deg = -31.5;
  p.geo.longitude_deg = -35.4;  // not the Dead Sea's, but west
  p.geo.altitude_m = -430.0;
  const std::vector<unsigned char> tagged =
      with_photo_tags(test_jpeg(128), keyframe_photo_tags(p, 0), "k.jpg");
  const fs::path file = fs::temp_directory_path() / ("plenopath_sw_" + std::to_string(::getpid()) + ".jpg");
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(tagged.data()), static_cast<std::streamsize>(tagged.size()));
  const PhotoMetadata m = read_photo_metadata(file.string());
  fs::remove(file);
  ASSERT_TRUE(m.has_gps());
  EXPECT_NEAR(*m.latitude_deg, -31.5, 1e-9);
  EXPECT_NEAR(*m.longitude_deg, -35.4, 1e-9);
  EXPECT_NEAR(m.altitude_m, -430.0 + 1.6, 1e-3);
}

TEST(KeyframeMetadata, NotAJpegIsAnErrorNamingTheFile) {
  const std::vector<unsigned char> junk = {'n', 'o', 't', ' ', 'a', ' ', 'j', 'p', 'e', 'g'};
  try {
    with_photo_tags(junk, {}, "images/k000001_full.jpg");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("images/k000001_full.jpg"), std::string::npos) << e.what();
  }
  EXPECT_THROW(keyframe_photo_tags(interop_test::hand_made_project(), 99), Error);
}

}  // namespace
}  // namespace plenopath
