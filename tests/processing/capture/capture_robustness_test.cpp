// Bad input never crashes the importers: mutated and truncated GPX text and image files either parse or
// raise plenopath::Error; truncated images are flagged by the header check.
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "model/error.h"
#include "processing/capture/gps_track.h"
#include "processing/capture/image_header.h"
#include "tests/processing/capture/capture_test_util.h"

namespace plenopath {
namespace {

const char* kValidGpx = R"(<?xml version="1.0"?>
<gpx version="1.1" creator="t"><trk><name>a</name><trkseg>
<trkpt lat="47.1" lon="8.2"><ele>400</ele><time>2024-05-01T10:20:30Z</time></trkpt>
<trkpt lat="47.2" lon="8.3"><ele>401</ele><time>2024-05-01T10:20:31.5Z</time></trkpt>
</trkseg></trk></gpx>)";

TEST(CaptureRobustness, MutatedGpxParsesOrThrowsError) {
  std::mt19937 random(7);
  const std::string valid = kValidGpx;
  const std::string alphabet = "<>/=\"' abc09.:-TZ&;!?\n";
  int parsed = 0, rejected = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string text = valid;
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = random() % text.size();
      switch (random() % 3) {
        case 0:
          text[at] = alphabet[random() % alphabet.size()];
          break;
        case 1:
          text.erase(at, 1 + random() % 8);
          break;
        default:
          text.insert(at, 1, alphabet[random() % alphabet.size()]);
          break;
      }
      if (text.empty()) text = "<";
    }
    if (trial % 10 == 0) text = valid.substr(0, random() % valid.size());  // truncated
    try {
      const GpxTrack track = parse_gpx(text, "fuzz.gpx");
      ++parsed;
      ASSERT_FALSE(track.samples.empty());
      for (const GpsSample& s : track.samples) {
        ASSERT_TRUE(std::isfinite(s.time_s) && s.latitude_deg >= -90 && s.latitude_deg <= 90);
      }
    } catch (const Error& e) {
      ++rejected;
      ASSERT_NE(std::string(e.what()).find("fuzz.gpx"), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(parsed, 0);
  EXPECT_GT(rejected, 0);
}

TEST(CaptureRobustness, TruncatedAndMutatedImagesNeverCrashTheHeaderCheck) {
  test::TempFolder dir;
  const cv::Mat frame = test::numbered_frame(77, 128, 64);
  std::vector<std::string> formats = {".jpg", ".png", ".tif", ".exr"};
  std::mt19937 random(11);
  for (const std::string& ext : formats) {
    const std::string path = dir / ("frame" + ext);
    if (ext == ".exr") {
      cv::Mat f;
      frame.convertTo(f, CV_32FC3, 1.0 / 255.0);
      ASSERT_TRUE(cv::imwrite(path, f));
    } else {
      ASSERT_TRUE(cv::imwrite(path, frame));
    }
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const ImageHeader whole = read_image_header(path);
    ASSERT_TRUE(whole.ok) << ext << ": " << whole.problem;
    EXPECT_EQ(whole.width, 128) << ext;
    EXPECT_EQ(whole.height, 64) << ext;

    const std::string damaged = dir / ("damaged" + ext);
    for (int trial = 0; trial < 300; ++trial) {
      std::string copy = bytes;
      if (trial % 2 == 0) {
        copy.resize(random() % copy.size());  // truncated anywhere
      } else {
        for (int e = 0; e < 4; ++e) copy[random() % copy.size()] = static_cast<char>(random() % 256);
      }
      std::ofstream(damaged, std::ios::binary | std::ios::trunc)
          .write(copy.data(), static_cast<std::streamsize>(copy.size()));
      const ImageHeader h = read_image_header(damaged);  // must return, whatever the bytes
      if (h.ok) {
        EXPECT_GE(h.width, 0);
        EXPECT_GE(h.height, 0);
      } else {
        EXPECT_FALSE(h.problem.empty());
      }
      // Truncated JPEGs and PNGs lose their end markers: the header check catches most of them.
      if (trial % 2 == 0 && (ext == ".jpg" || ext == ".png") && copy.size() + 2 < bytes.size()) {
        EXPECT_FALSE(h.ok) << ext << " truncated to " << copy.size() << " of " << bytes.size() << " bytes";
      }
    }
  }
}

}  // namespace
}  // namespace plenopath

namespace plenopath {
namespace {

TEST(ImageHeader, SizesBeyondIntAreCorruptNotNegative) {
  // Found by fuzz.image_header_replay: a TIFF width of 0xFFFFFFFF came back as -1 with ok = true.
  std::string tiff("II*\0\x08\0\0\0\x01\0\0\x01\x04\0\x01\0\0\0\xFF\xFF\xFF\xFF\0\0\0\0", 26);
  const ImageHeader t = read_image_header_from_memory(tiff);
  EXPECT_FALSE(t.ok);
  EXPECT_NE(t.problem.find("bad size"), std::string::npos) << t.problem;

  std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\x80\0\0\0\0\0\0\x10", 24);
  png += std::string(9, '\0') + "IEND" + std::string(4, '\0');
  const ImageHeader p = read_image_header_from_memory(png);
  EXPECT_FALSE(p.ok);
  EXPECT_NE(p.problem.find("bad size"), std::string::npos) << p.problem;

  // An EXR data window from INT_MIN to INT_MAX: its width overflows 32 bits.
  std::string exr("v/1\x01\x02\0\0\0", 8);
  exr += std::string("dataWindow\0box2i\0", 17) + std::string("\x10\0\0\0", 4);
  exr += std::string("\0\0\0\x80\0\0\0\x80\xFF\xFF\xFF\x7F\xFF\xFF\xFF\x7F", 16);
  exr += std::string(1, '\0');
  const ImageHeader e = read_image_header_from_memory(exr);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.problem.find("bad data window"), std::string::npos) << e.problem;

  // The well-formed 32 x 16 TIFF of the fuzz seeds reads with its size (written by ImageMagick).
  std::ifstream in(std::string(PLENOPATH_TEST_DATA_DIR) + "/fuzz/image/a.tif", std::ios::binary);
  const std::string seed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const ImageHeader s = read_image_header_from_memory(seed);
  EXPECT_TRUE(s.ok) << s.problem;
  EXPECT_EQ(s.width, 32);
  EXPECT_EQ(s.height, 16);
}

}  // namespace
}  // namespace plenopath
