// 360 video metadata: MP4 files made by ffmpeg, given Spherical Video V2 boxes or V1 XML by a test-side
// writer (spherical_mp4_writer.py, written from the specifications), then read by read_spherical_video_info
// and checked against two independent readers: ffprobe (FFmpeg's mov demuxer) and ExifTool. A file whose
// boxes ffmpeg itself wrote (a remux) must read the same. Damaged metadata gives an Error, never a crash.
#include "processing/capture/spherical_video.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "model/error.h"
#include "processing/capture/mp4_boxes.h"
#include "tests/processing/capture/capture_test_util.h"
#include "tests/processing/capture/video_test_util.h"

namespace plenopath {
namespace {

const std::string kWriter =
    std::string(PLENOPATH_SOURCE_DIR) + "/tests/processing/capture/spherical_mp4_writer.py";

void require_tools() {
  test::require_ffmpeg();
  ASSERT_TRUE(test::have_tool("exiftool", "-ver"))
      << "exiftool (libimage-exiftool-perl) is needed: cmake/install-deps.sh";
  ASSERT_EQ(std::system("python3 -c '' > /dev/null 2>&1"), 0) << "python3 is needed: cmake/install-deps.sh";
}

// A small 2:1 H.264 MP4 (moov after mdat, as ffmpeg writes it).
std::string base_video() {
  return test::cached_test_video("spherical_base_v1.mp4", 8, "10",
                                 "-c:v libx264 -preset veryfast -pix_fmt yuv420p",
                                 [](int k) { return test::numbered_frame(k, 128, 64); });
}

// `base` with metadata added by the test-side writer.
std::string with_metadata(const test::TempFolder& dir, const std::string& name, const std::string& args) {
  const std::string out = dir / name;
  const std::string command = "python3 '" + kWriter + "' '" + base_video() + "' '" + out + "' " + args;
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return out;
}

// ffprobe's "Spherical Mapping" and "Stereo 3D" side data of the first video stream (null if none).
nlohmann::json ffprobe_side_data(const std::string& file, const std::string& type) {
  const nlohmann::json j = nlohmann::json::parse(
      test::command_output("ffprobe -v error -select_streams v:0 -show_streams -of json '" + file + "'"));
  for (const auto& s : j["streams"][0].value("side_data_list", nlohmann::json::array()))
    if (s["side_data_type"] == type) return s;
  return nullptr;
}

// ExifTool's numeric tags of the file, keyed "Group:Tag" (-G1 -n).
nlohmann::json exiftool_tags(const std::string& file) {
  return nlohmann::json::parse(test::command_output("exiftool -j -n -G1 '" + file + "'"))[0];
}

TEST(SphericalVideo, V2EquirectangularPoseStereoAndBoundsAgreeWithFfprobeAndExifTool) {
  require_tools();
  if (HasFatalFailure()) return;
  test::TempFolder dir;
  const std::string file = with_metadata(
      dir, "v2.mp4", "--v2 --yaw 12.5 --pitch -7.25 --roll 3.75 --stereo 1 --bounds 0.25,0.125,0,0.5");
  const SphericalVideoInfo info = read_spherical_video_info(file);
  EXPECT_TRUE(info.iso_file);
  EXPECT_TRUE(info.spherical);
  EXPECT_TRUE(info.equirectangular());
  EXPECT_EQ(info.metadata, "Spherical Video V2");
  EXPECT_EQ(info.stereo, StereoMode::kTopBottom);
  EXPECT_EQ(info.software, "plenopath test writer");
  EXPECT_EQ(info.track, 0);

  const nlohmann::json exif = exiftool_tags(file);
  EXPECT_DOUBLE_EQ(info.yaw_deg, exif["Track1:PoseYawDegrees"].get<double>());
  EXPECT_DOUBLE_EQ(info.pitch_deg, exif["Track1:PosePitchDegrees"].get<double>());
  EXPECT_DOUBLE_EQ(info.roll_deg, exif["Track1:PoseRollDegrees"].get<double>());
  EXPECT_NEAR(info.crop_top, exif["Track1:ProjectionBoundsTop"].get<double>(), 1e-9);
  EXPECT_NEAR(info.crop_bottom, exif["Track1:ProjectionBoundsBottom"].get<double>(), 1e-9);
  EXPECT_NEAR(info.crop_left, exif["Track1:ProjectionBoundsLeft"].get<double>(), 1e-9);
  EXPECT_NEAR(info.crop_right, exif["Track1:ProjectionBoundsRight"].get<double>(), 1e-9);
  EXPECT_EQ(exif["Track1:Stereoscopic3D"].get<int>(), 1);

  // ffprobe: whole degrees, and the bounds in pixels of the full panorama the 128x64 tile is cut from.
  const nlohmann::json mapping = ffprobe_side_data(file, "Spherical Mapping");
  ASSERT_FALSE(mapping.is_null());
  EXPECT_EQ(mapping["projection"], "tiled equirectangular");
  EXPECT_EQ(mapping["yaw"].get<int>(), static_cast<int>(info.yaw_deg));
  EXPECT_EQ(mapping["pitch"].get<int>(), static_cast<int>(info.pitch_deg));
  EXPECT_EQ(mapping["roll"].get<int>(), static_cast<int>(info.roll_deg));
  const double full_h = 64 / (1 - info.crop_top - info.crop_bottom);
  const double full_w = 128 / (1 - info.crop_left - info.crop_right);
  EXPECT_NEAR(mapping["bound_top"].get<double>(), info.crop_top * full_h, 1.0);
  EXPECT_NEAR(mapping["bound_bottom"].get<double>(), info.crop_bottom * full_h, 1.0);
  EXPECT_NEAR(mapping["bound_right"].get<double>(), info.crop_right * full_w, 1.0);
  EXPECT_EQ(ffprobe_side_data(file, "Stereo 3D")["type"], "top and bottom");
}

TEST(SphericalVideo, BoxesWrittenByFfmpegItselfReadTheSame) {
  require_tools();
  if (HasFatalFailure()) return;
  test::TempFolder dir;
  const std::string ours = with_metadata(dir, "v2.mp4", "--v2 --yaw 90 --pitch -10 --roll 5 --stereo 2");
  const std::string remux = dir / "remux.mp4";
  // The mov muxer writes sv3d and st3d from the stream's side data (unofficial boxes: -strict unofficial).
  test::command_output("ffmpeg -v error -y -i '" + ours + "' -c copy -strict unofficial '" + remux + "'");
  const SphericalVideoInfo a = read_spherical_video_info(ours);
  const SphericalVideoInfo b = read_spherical_video_info(remux);
  EXPECT_EQ(b.software.rfind("Lavf", 0), 0u)
      << "the boxes should be ffmpeg's own, not copied: " << b.software;
  EXPECT_TRUE(b.equirectangular());
  EXPECT_EQ(b.stereo, StereoMode::kLeftRight);
  EXPECT_DOUBLE_EQ(b.yaw_deg, 90.0);
  EXPECT_DOUBLE_EQ(b.pitch_deg, -10.0);
  EXPECT_DOUBLE_EQ(b.roll_deg, 5.0);
  EXPECT_DOUBLE_EQ(a.yaw_deg, b.yaw_deg);
  EXPECT_EQ(b.crop_top + b.crop_bottom + b.crop_left + b.crop_right, 0.0);
}

TEST(SphericalVideo, V2CubemapIsSphericalButNotEquirectangular) {
  require_tools();
  if (HasFatalFailure()) return;
  test::TempFolder dir;
  const std::string file = with_metadata(dir, "cube.mp4", "--v2 --projection cubemap --yaw -30");
  const SphericalVideoInfo info = read_spherical_video_info(file);
  EXPECT_TRUE(info.spherical);
  EXPECT_EQ(info.projection, SphericalProjection::kCubemap);
  EXPECT_FALSE(info.equirectangular());
  EXPECT_DOUBLE_EQ(info.yaw_deg, -30.0);
  EXPECT_EQ(ffprobe_side_data(file, "Spherical Mapping")["projection"], "cubemap");
}

TEST(SphericalVideo, V1XmlOrientationAndCropAgreeWithExifTool) {
  require_tools();
  if (HasFatalFailure()) return;
  test::TempFolder dir;
  const std::string file =
      with_metadata(dir, "v1.mp4", "--v1 --yaw 45 --pitch 10 --roll -3 --crop 4096,2048,512,256,2048,1024");
  const SphericalVideoInfo info = read_spherical_video_info(file);
  EXPECT_TRUE(info.equirectangular());
  EXPECT_EQ(info.metadata, "Spherical Video V1");
  const nlohmann::json exif = exiftool_tags(file);
  EXPECT_DOUBLE_EQ(info.yaw_deg, exif["XMP-GSpherical:InitialViewHeadingDegrees"].get<double>());
  EXPECT_DOUBLE_EQ(info.pitch_deg, exif["XMP-GSpherical:InitialViewPitchDegrees"].get<double>());
  EXPECT_DOUBLE_EQ(info.roll_deg, exif["XMP-GSpherical:InitialViewRollDegrees"].get<double>());
  EXPECT_EQ(info.software, exif["XMP-GSpherical:StitchingSoftware"].get<std::string>());
  // 2048 x 1024 of a 4096 x 2048 panorama from (512, 256): by hand.
  EXPECT_DOUBLE_EQ(info.crop_left, 0.125);
  EXPECT_DOUBLE_EQ(info.crop_right, 0.375);
  EXPECT_DOUBLE_EQ(info.crop_top, 0.125);
  EXPECT_DOUBLE_EQ(info.crop_bottom, 0.375);
  // FFmpeg 5.1 sees the projection (its V1 orientation parse reads 0 for every angle, so not that).
  EXPECT_EQ(ffprobe_side_data(file, "Spherical Mapping")["projection"], "equirectangular");

  // Both versions: V2 wins.
  const std::string both = with_metadata(dir, "both.mp4", "--v1 --v2 --yaw 60");
  const SphericalVideoInfo b = read_spherical_video_info(both);
  EXPECT_EQ(b.metadata, "Spherical Video V2");
  EXPECT_DOUBLE_EQ(b.yaw_deg, 60.0);
}

TEST(SphericalVideo, FilesWithoutMetadataAndOtherContainers) {
  require_tools();
  if (HasFatalFailure()) return;
  const SphericalVideoInfo plain = read_spherical_video_info(base_video());
  EXPECT_TRUE(plain.iso_file);
  EXPECT_FALSE(plain.spherical);
  EXPECT_EQ(plain.track, 0) << "the video track is found even without metadata";
  EXPECT_TRUE(ffprobe_side_data(base_video(), "Spherical Mapping").is_null());

  test::TempFolder dir;
  const std::string mkv = dir / "plain.mkv";
  test::command_output("ffmpeg -v error -y -i '" + base_video() + "' -c copy '" + mkv + "'");
  EXPECT_FALSE(read_spherical_video_info(mkv).iso_file);
  std::ofstream(dir / "text.mp4") << "not a video at all";
  EXPECT_FALSE(read_spherical_video_info(dir / "text.mp4").iso_file);
  try {
    read_spherical_video_info(dir / "absent.mp4");
    ADD_FAILURE() << "a missing file must throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("absent.mp4"), std::string::npos) << e.what();
  }
}

std::vector<uint8_t> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The moov payload of an MP4 whose top-level boxes have 32-bit sizes.
std::vector<uint8_t> moov_payload(const std::vector<uint8_t>& file) {
  for (const Mp4Box& b : mp4_child_boxes(file.data(), file.size(), "file"))
    if (b.type == "moov") return std::vector<uint8_t>(b.payload, b.payload + b.payload_size);
  ADD_FAILURE() << "no moov";
  return {};
}

TEST(SphericalVideo, DamagedBoxesGiveErrorsNamingTheBoxNeverACrash) {
  require_tools();
  if (HasFatalFailure()) return;
  test::TempFolder dir;
  const std::string file = with_metadata(dir, "v2.mp4", "--v2 --v1 --yaw 12 --stereo 1 --bounds 0.1,0.1,0,0");
  const std::vector<uint8_t> bytes = file_bytes(file);
  const std::vector<uint8_t> moov = moov_payload(bytes);
  ASSERT_TRUE(parse_spherical_moov(moov.data(), moov.size()).equirectangular());

  // An sv3d box claiming more bytes than its sample entry holds.
  std::vector<uint8_t> bad = moov;
  const uint8_t sv3d[4] = {'s', 'v', '3', 'd'};
  const auto at = std::search(bad.begin(), bad.end(), sv3d, sv3d + 4);
  ASSERT_NE(at, bad.end());
  at[-4] = 0x7f;
  try {
    parse_spherical_moov(bad.data(), bad.size());
    ADD_FAILURE() << "an overrunning box must throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("moov/trak[0]/mdia/minf/stbl/stsd/avc1: box 'sv3d' says it has"),
              std::string::npos)
        << e.what();
  }
  // The same in a file: the message names it.
  std::vector<uint8_t> bad_file = bytes;
  const auto file_at = std::search(bad_file.begin(), bad_file.end(), sv3d, sv3d + 4);
  file_at[-4] = 0x7f;
  std::ofstream(dir / "bad.mp4", std::ios::binary)
      .write(reinterpret_cast<const char*>(bad_file.data()), static_cast<std::streamsize>(bad_file.size()));
  try {
    read_spherical_video_info(dir / "bad.mp4");
    ADD_FAILURE() << "a damaged file must throw";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(dir / "bad.mp4", 0), 0u) << e.what();
  }

  // Every truncation and 20 000 random byte changes: a result or an Error, nothing else (ASan builds check
  // the reads; the fuzz target does this at scale).
  int errors = 0, parsed = 0;
  const auto attempt = [&](const std::vector<uint8_t>& m) {
    try {
      parse_spherical_moov(m.data(), m.size());
      ++parsed;
    } catch (const Error&) {
      ++errors;
    }
  };
  for (std::size_t n = 0; n <= moov.size(); ++n)
    attempt(std::vector<uint8_t>(moov.begin(), moov.begin() + n));
  std::mt19937 random(22);
  std::uniform_int_distribution<std::size_t> where(0, moov.size() - 1);
  std::uniform_int_distribution<int> value(0, 255);
  for (int n = 0; n < 20000; ++n) {
    std::vector<uint8_t> m = moov;
    for (int k = 0; k < 1 + n % 4; ++k) m[where(random)] = static_cast<uint8_t>(value(random));
    attempt(m);
  }
  EXPECT_GT(errors, 0);
  EXPECT_GT(parsed, 0);
}

}  // namespace
}  // namespace plenopath
