#include "processing/capture/frame_source.h"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "model/error.h"
#include "tests/processing/capture/capture_test_util.h"

namespace plenopath {
namespace {

using test::decode_frame_number;
using test::numbered_frame;
using test::TempFolder;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(NaturalSort, NumbersCompareByValue) {
  EXPECT_TRUE(natural_less("frame9.jpg", "frame10.jpg"));
  EXPECT_FALSE(natural_less("frame10.jpg", "frame9.jpg"));
  EXPECT_TRUE(natural_less("img2_b", "img10_a"));
  EXPECT_TRUE(natural_less("a007", "a8"));      // leading zeros do not make a number bigger
  EXPECT_TRUE(natural_less("Shot1", "shot2"));  // case does not matter
  EXPECT_TRUE(natural_less("x99999999999999999999", "x100000000000000000000"));  // longer than 64 bits
  EXPECT_FALSE(natural_less("same", "same"));
}

TEST(FrameSourceFolder, NaturalOrderWithOddNamesAndContent) {
  TempFolder dir;
  // Written in scrambled order, mixed formats, odd names; plus files that are not frames.
  const std::vector<std::pair<std::string, int>> files = {
      {"IMG 10.jpg", 10}, {"IMG 9.png", 9}, {"IMG 100.tif", 100}, {"IMG 11.jpeg", 11}, {"IMG 2.JPG", 2}};
  for (const auto& [name, number] : files) ASSERT_TRUE(cv::imwrite(dir / name, numbered_frame(number)));
  std::ofstream(dir / "notes.txt") << "not a frame";
  std::ofstream(dir / ".hidden.jpg") << "hidden";

  auto source = FrameSource::open(dir.path().string());
  ASSERT_EQ(source->frame_count(), 5);
  EXPECT_EQ(source->kind(), CaptureKind::kImageFolder);
  EXPECT_EQ(source->width(), 256);
  EXPECT_EQ(source->height(), 128);
  const std::vector<std::string> expected = {"IMG 2.JPG", "IMG 9.png", "IMG 10.jpg", "IMG 11.jpeg",
                                             "IMG 100.tif"};
  const std::vector<int> numbers = {2, 9, 10, 11, 100};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(source->frame_name(i), expected[i]);
    const cv::Mat frame = source->read(i);
    ASSERT_EQ(frame.type(), CV_8UC3);
    EXPECT_EQ(decode_frame_number(frame), numbers[i]) << expected[i];
    const cv::Mat thumb = source->read_thumbnail(i, 64);
    EXPECT_EQ(thumb.cols, 64);
    EXPECT_EQ(thumb.rows, 32);
    EXPECT_EQ(decode_frame_number(thumb), numbers[i]) << "thumbnail of " << expected[i];
  }
  // Numbers this sparse (5 files over 2..100) are not a frame counter: no "missing" frames, and time
  // stamps follow the order.
  EXPECT_TRUE(source->skipped().empty());
  EXPECT_NEAR(source->timestamp_s(4), 4 / 30.0, 1e-12);
}

TEST(FrameSourceFolder, CorruptAndMissingFramesAreSkippedAndListed) {
  TempFolder dir;
  char name[32];
  for (int k = 0; k < 10; ++k) {
    if (k == 4) continue;  // missing frame
    std::snprintf(name, sizeof name, "frame_%04d.jpg", k);
    ASSERT_TRUE(cv::imwrite(dir / name, numbered_frame(k)));
  }
  {  // frame 6: truncated to half its length
    const std::string path = dir / "frame_0006.jpg";
    const auto size = std::filesystem::file_size(path);
    std::filesystem::resize_file(path, size / 2);
  }
  std::ofstream(dir / "frame_0008.jpg") << "this is not a JPEG at all";  // frame 8: garbage
  std::ofstream(dir / "frame_0009.jpg");                                 // frame 9: empty file

  auto source = FrameSource::open(dir.path().string());
  const std::vector<int> kept = {0, 1, 2, 3, 5, 7};
  ASSERT_EQ(source->frame_count(), static_cast<int>(kept.size()));
  for (int i = 0; i < source->frame_count(); ++i) {
    EXPECT_EQ(decode_frame_number(source->read(i)), kept[i]);
    EXPECT_EQ(source->frame_number(i), kept[i]);
    // Time follows the numbering, so a missing frame does not shift the later ones.
    EXPECT_NEAR(source->timestamp_s(i), kept[i] / 30.0, 1e-12);
  }
  const std::vector<SkippedFrame> skipped = source->skipped();
  ASSERT_EQ(skipped.size(), 4u);
  EXPECT_EQ(skipped[0].name, "frame_0004.jpg");
  EXPECT_NE(skipped[0].reason.find("missing"), std::string::npos) << skipped[0].reason;
  EXPECT_EQ(skipped[0].number, 4);
  EXPECT_EQ(skipped[1].name, "frame_0006.jpg");
  EXPECT_NE(skipped[1].reason.find("truncated"), std::string::npos) << skipped[1].reason;
  EXPECT_EQ(skipped[2].name, "frame_0008.jpg");
  EXPECT_NE(skipped[2].reason.find("not a JPEG"), std::string::npos) << skipped[2].reason;
  EXPECT_EQ(skipped[3].name, "frame_0009.jpg");
  EXPECT_NE(skipped[3].reason.find("empty"), std::string::npos) << skipped[3].reason;

  // A frame that goes bad after the scan: read() throws an Error naming the file, nothing aborts.
  std::filesystem::remove(dir / "frame_0005.jpg");
  const std::string message = error_of([&] { source->read(4); });
  EXPECT_NE(message.find("frame_0005.jpg"), std::string::npos) << message;
  EXPECT_EQ(decode_frame_number(source->read(5)), 7);
}

TEST(FrameSourceFolder, ClockTimeNamesAreNotReportedAsGaps) {
  TempFolder dir;
  // One frame a second named by clock time: 10:59:58, 10:59:59, 11:00:00, 11:00:01.
  for (const char* name : {"VID_105958.png", "VID_105959.png", "VID_110000.png", "VID_110001.png"})
    ASSERT_TRUE(cv::imwrite(dir / name, numbered_frame(1, 64, 32)));
  auto source = FrameSource::open(dir.path().string());
  EXPECT_EQ(source->frame_count(), 4);
  EXPECT_TRUE(source->skipped().empty());
  EXPECT_NEAR(source->timestamp_s(3), 3 / 30.0, 1e-12);
}

TEST(FrameSourceFolder, RangeStrideAndCaptureRoundTrip) {
  TempFolder dir;
  char name[32];
  for (int k = 0; k < 12; ++k) {
    std::snprintf(name, sizeof name, "p%d.png", k);  // unpadded numbers: natural sort matters
    ASSERT_TRUE(cv::imwrite(dir / name, numbered_frame(k, 64, 32)));
  }
  FrameSourceOptions options;
  options.first_frame = 1;
  options.last_frame = 10;
  options.stride = 3;
  options.folder_frame_rate = 10.0;
  auto source = FrameSource::open(dir.path().string(), options);
  const std::vector<int> kept = {1, 4, 7, 10};
  ASSERT_EQ(source->frame_count(), 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(decode_frame_number(source->read(i)), kept[i]);
    EXPECT_NEAR(source->timestamp_s(i), kept[i] / 10.0, 1e-12);
  }
  EXPECT_TRUE(source->skipped().empty());  // stride gaps are not missing frames

  const Capture capture = capture_from_frame_source(*source);
  EXPECT_EQ(capture.kind, CaptureKind::kImageFolder);
  EXPECT_EQ(capture.frame_count, 4);
  EXPECT_EQ(capture.width, 64);
  EXPECT_EQ(capture.height, 32);
  EXPECT_EQ(capture.first_frame, 1);
  EXPECT_EQ(capture.stride, 3);
  EXPECT_EQ(capture.frame_names, (std::vector<std::string>{"p1.png", "p4.png", "p7.png", "p10.png"}));

  auto reopened = FrameSource::open_capture(capture);
  ASSERT_EQ(reopened->frame_count(), 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(decode_frame_number(reopened->read(i)), kept[i]);
    EXPECT_NEAR(reopened->timestamp_s(i), source->timestamp_s(i), 1e-12);
  }
}

TEST(FrameSourceFolder, WrongAspectGivesAClearMessage) {
  TempFolder dir;
  ASSERT_TRUE(cv::imwrite(dir / "a1.jpg", cv::Mat(90, 160, CV_8UC3, cv::Scalar(1, 2, 3))));
  ASSERT_TRUE(cv::imwrite(dir / "a2.jpg", cv::Mat(90, 160, CV_8UC3, cv::Scalar(1, 2, 3))));
  const std::string message = error_of([&] { FrameSource::open(dir.path().string()); });
  EXPECT_NE(message.find(dir.path().string()), std::string::npos) << message;
  EXPECT_NE(message.find("160x90"), std::string::npos) << message;
  EXPECT_NE(message.find("not 2:1"), std::string::npos) << message;

  FrameSourceOptions any;
  any.require_2to1 = false;
  EXPECT_EQ(FrameSource::open(dir.path().string(), any)->frame_count(), 2);
}

TEST(FrameSourceFolder, FramesOfAnotherSizeAreSkipped) {
  TempFolder dir;
  for (int k = 0; k < 4; ++k)
    ASSERT_TRUE(cv::imwrite(dir / ("f" + std::to_string(k) + ".png"), numbered_frame(k, 64, 32)));
  ASSERT_TRUE(cv::imwrite(dir / "f4.png", numbered_frame(4, 128, 64)));
  auto source = FrameSource::open(dir.path().string());
  EXPECT_EQ(source->frame_count(), 4);
  ASSERT_EQ(source->skipped().size(), 1u);
  EXPECT_EQ(source->skipped()[0].name, "f4.png");
  EXPECT_NE(source->skipped()[0].reason.find("128x64"), std::string::npos);
}

TEST(FrameSourceFolder, BadPathsGiveErrorsNamingThem) {
  TempFolder dir;
  EXPECT_NE(error_of([&] { FrameSource::open(dir / "absent"); }).find("absent"), std::string::npos);
  EXPECT_NE(error_of([&] { FrameSource::open(dir.path().string()); }).find("no frames"), std::string::npos);
  std::ofstream(dir / "only.jpg") << "garbage";
  const std::string message = error_of([&] { FrameSource::open(dir.path().string()); });
  EXPECT_NE(message.find("no usable frame"), std::string::npos) << message;
  EXPECT_NE(message.find("only.jpg"), std::string::npos) << message;
  FrameSourceOptions bad;
  bad.stride = 0;
  EXPECT_NE(error_of([&] { bad.check(); }).find("stride"), std::string::npos);
}

TEST(FrameSourceFolder, DepthMapsMatchedByName) {
  TempFolder frames, depth;
  for (int k = 0; k < 4; ++k) {
    ASSERT_TRUE(cv::imwrite(frames / ("frame_00" + std::to_string(k) + ".jpg"), numbered_frame(k, 64, 32)));
  }
  // Frame 0: 16-bit PNG in millimetres, same stem. Frame 1: float EXR in metres, other stem, same number.
  // Frame 2: none. Frame 3: a depth map of the wrong size.
  cv::Mat mm(32, 64, CV_16U, cv::Scalar(1500));
  mm.at<uint16_t>(3, 5) = 0;  // no hit
  ASSERT_TRUE(cv::imwrite(depth / "frame_000.png", mm));
  ASSERT_TRUE(cv::imwrite(depth / "depth_1.exr", cv::Mat(32, 64, CV_32F, cv::Scalar(2.25))));
  ASSERT_TRUE(cv::imwrite(depth / "frame_003.png", cv::Mat(16, 32, CV_16U, cv::Scalar(1000))));

  FrameSourceOptions options;
  options.depth_folder = depth.path().string();
  auto source = FrameSource::open(frames.path().string(), options);
  EXPECT_EQ(source->depth_match_count(), 3);
  EXPECT_TRUE(source->has_depth(0));
  EXPECT_TRUE(source->has_depth(1));
  EXPECT_FALSE(source->has_depth(2));
  const cv::Mat d0 = source->read_depth(0);
  ASSERT_EQ(d0.type(), CV_32F);
  EXPECT_FLOAT_EQ(d0.at<float>(0, 0), 1.5f);
  EXPECT_FLOAT_EQ(d0.at<float>(3, 5), 0.0f);
  EXPECT_EQ(source->depth_name(1), "depth_1.exr");
  EXPECT_FLOAT_EQ(source->read_depth(1).at<float>(10, 10), 2.25f);
  EXPECT_NE(error_of([&] { source->read_depth(2); }).find("no depth map"), std::string::npos);
  EXPECT_NE(error_of([&] { source->read_depth(3); }).find("frame_003.png"), std::string::npos);
}

// Writes `count` numbered frames with the given codec; false if this OpenCV cannot write it.
bool write_video(const std::string& path, const char* fourcc, int count, double fps) {
  cv::VideoWriter writer(path, cv::CAP_FFMPEG,
                         cv::VideoWriter::fourcc(fourcc[0], fourcc[1], fourcc[2], fourcc[3]), fps,
                         cv::Size(256, 128));
  if (!writer.isOpened()) return false;
  for (int k = 0; k < count; ++k) writer.write(numbered_frame(k));
  writer.release();
  return true;
}

struct VideoCase {
  const char* fourcc;
  const char* file;
};

class FrameSourceVideo : public ::testing::TestWithParam<VideoCase> {};

TEST_P(FrameSourceVideo, ImportsWithRightCountContentRangeAndSeeking) {
  TempFolder dir;
  const std::string path = dir / GetParam().file;
  ASSERT_TRUE(write_video(path, GetParam().fourcc, 40, 25.0)) << "cannot write " << GetParam().fourcc;

  auto source = FrameSource::open(path);
  EXPECT_EQ(source->kind(), CaptureKind::kVideo);
  ASSERT_EQ(source->frame_count(), 40);
  EXPECT_EQ(source->width(), 256);
  EXPECT_EQ(source->height(), 128);
  EXPECT_NEAR(source->frame_rate(), 25.0, 1e-6);
  for (int i = 0; i < 40; ++i) ASSERT_EQ(decode_frame_number(source->read(i)), i) << "sequential frame " << i;
  for (int i : {33, 2, 17, 18, 39, 0, 25})
    EXPECT_EQ(decode_frame_number(source->read(i)), i) << "seek to " << i;

  FrameSourceOptions options;
  options.first_frame = 5;
  options.last_frame = 30;
  options.stride = 3;
  auto range = FrameSource::open(path, options);
  ASSERT_EQ(range->frame_count(), 9);  // 5, 8, ..., 29
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(decode_frame_number(range->read(i)), 5 + 3 * i);
    EXPECT_EQ(range->frame_number(i), 5 + 3 * i);
    EXPECT_NEAR(range->timestamp_s(i), (5 + 3 * i) / 25.0, 1e-9);
  }
  const Capture capture = capture_from_frame_source(*range);
  EXPECT_EQ(capture.kind, CaptureKind::kVideo);
  EXPECT_EQ(capture.first_frame, 5);
  EXPECT_EQ(capture.stride, 3);
  auto reopened = FrameSource::open_capture(capture);
  EXPECT_EQ(reopened->frame_count(), 9);
  EXPECT_EQ(decode_frame_number(reopened->read(8)), 29);
}

INSTANTIATE_TEST_SUITE_P(Codecs, FrameSourceVideo,
                         ::testing::Values(VideoCase{"MJPG", "capture.avi"}, VideoCase{"mp4v", "capture.mp4"},
                                           VideoCase{"avc1", "capture_h264.mp4"},
                                           VideoCase{"H264", "capture.mkv"},
                                           VideoCase{"mp4v", "capture.mov"}),
                         [](const auto& info) {
                           std::string n = info.param.file;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

TEST(FrameSourceVideoErrors, BadVideosGiveErrorsNamingThem) {
  TempFolder dir;
  std::ofstream(dir / "broken.mp4") << "not a video";
  EXPECT_NE(error_of([&] { FrameSource::open(dir / "broken.mp4"); }).find("broken.mp4"), std::string::npos);

  ASSERT_TRUE(write_video(dir / "v.avi", "MJPG", 10, 10.0));
  FrameSourceOptions beyond;
  beyond.first_frame = 50;
  const std::string message = error_of([&] { FrameSource::open(dir / "v.avi", beyond); });
  EXPECT_NE(message.find("beyond"), std::string::npos) << message;
  auto source = FrameSource::open(dir / "v.avi");
  EXPECT_NE(error_of([&] { source->read(10); }).find("out of range"), std::string::npos);
}

TEST(FrameSourceGenerator, ServesGeneratedFrames) {
  auto source =
      FrameSource::from_generator(1000, 64, 32, 10.0, [](int i) { return numbered_frame(i % 256, 64, 32); });
  EXPECT_EQ(source->frame_count(), 1000);
  EXPECT_EQ(decode_frame_number(source->read(300)), 300 % 256);
  EXPECT_NEAR(source->timestamp_s(300), 30.0, 1e-12);
}

}  // namespace
}  // namespace plenopath
