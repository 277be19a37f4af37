// Frame-exact video (issue 22): 300-frame H.264 and HEVC videos with B-frames (HEVC with open GOPs), each
// frame showing its number. Sequential decoding is checked against the numbers, ffprobe's frame times and
// the ffmpeg command line's own decoding; then 200 random seeks must give exactly the pixels of sequential
// decoding and the right number, and so must reading backwards and with a stride.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <random>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/video_decoder.h"
#include "tests/processing/capture/capture_test_util.h"
#include "tests/processing/capture/video_test_util.h"

namespace plenopath {
namespace {

constexpr int kWidth = 320, kHeight = 160, kBits = 10, kFrames = 300;
// -sc_threshold 0 / scenecut=0 and b-adapt=0: fixed GOPs and every B-frame slot used, whatever the content.
constexpr const char* kH264Options =
    "-c:v libx264 -preset veryfast -bf 3 -g 30 -sc_threshold 0 -x264-params b-adapt=0 -pix_fmt yuv420p";

// Frame k: its number in stripes above, a block moving below (motion for the codec to predict, so a frame
// decoded from the wrong references would differ).
cv::Mat test_frame(int k) {
  cv::Mat f = test::numbered_frame(k, kWidth, kHeight, kBits);
  const int x = (k * 7) % (kWidth - 40);
  cv::rectangle(f, cv::Rect(x, kHeight * 5 / 8, 40, 40), cv::Scalar(40, 200, 90), cv::FILLED);
  cv::circle(f, cv::Point(kWidth - 1 - x, kHeight * 3 / 4), 12, cv::Scalar(200, 60, 200), cv::FILLED);
  return f;
}

bool same_pixels(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

struct SeekCase {
  const char* file;
  const char* options;
};

class VideoSeek : public ::testing::TestWithParam<SeekCase> {};

TEST_P(VideoSeek, RandomSeeksGiveTheFramesOfSequentialDecoding) {
  test::require_ffmpeg();
  if (HasFatalFailure()) return;
  const std::string path =
      test::cached_test_video(GetParam().file, kFrames, "30", GetParam().options, test_frame);
  if (HasFailure()) return;

  // Sequential decoding: every frame in order, no seek, each showing its number.
  VideoDecoder sequential(path);
  ASSERT_EQ(sequential.frame_count(), kFrames);
  const std::vector<double> probe_times = test::ffprobe_frame_times(path);
  ASSERT_EQ(probe_times.size(), static_cast<std::size_t>(kFrames))
      << "ffprobe counts another number of frames";
  std::vector<cv::Mat> frames;
  const VideoDecoderStats before = sequential.stats();
  for (int i = 0; i < kFrames; ++i) {
    frames.push_back(sequential.read(i));
    ASSERT_EQ(test::decode_frame_number(frames.back(), kBits), i) << "sequential frame " << i;
    EXPECT_NEAR(sequential.time_s(i), probe_times[i] - probe_times[0], 2e-6) << "frame " << i;
  }
  EXPECT_EQ(sequential.stats().seeks, before.seeks) << "reading in order must not seek";
  EXPECT_EQ(sequential.stats().frames_decoded - before.frames_decoded, kFrames);

  // The ffmpeg command line decodes the same pixels (same libraries, an independent reading loop).
  const std::string raw =
      test::command_output("ffmpeg -v error -i '" + path + "' -f rawvideo -pix_fmt bgr24 -");
  ASSERT_EQ(raw.size(), static_cast<std::size_t>(kFrames) * kWidth * kHeight * 3);
  int differing = 0;
  for (int i = 0; i < kFrames; ++i) {
    const cv::Mat theirs(kHeight, kWidth, CV_8UC3,
                         const_cast<char*>(raw.data()) + static_cast<std::size_t>(i) * kWidth * kHeight * 3);
    differing += !same_pixels(frames[i], theirs);
  }
  EXPECT_EQ(differing, 0) << "frames that differ from ffmpeg's decoding";

  // 200 random seeks through FrameSource, the way the studio and the tracker read.
  auto source = FrameSource::open(path);
  ASSERT_EQ(source->frame_count(), kFrames);
  std::mt19937 random(22);
  std::uniform_int_distribution<int> pick(0, kFrames - 1);
  for (int n = 0; n < 200; ++n) {
    const int i = pick(random);
    const cv::Mat m = source->read(i);
    ASSERT_EQ(test::decode_frame_number(m, kBits), i) << "seek " << n << " to frame " << i;
    ASSERT_TRUE(same_pixels(m, frames[i])) << "seek " << n << " to frame " << i << " differs from sequential";
  }

  // The same on the decoder itself, counting its work: a seek decodes from the keyframe before, not from
  // the start or a GOP early.
  VideoDecoder seeker(path);
  const VideoDecoderStats start = seeker.stats();
  for (int n = 0; n < 200; ++n) {
    const int i = pick(random);
    ASSERT_TRUE(same_pixels(seeker.read(i), frames[i])) << "decoder seek " << n << " to frame " << i;
  }
  const double decoded_per_seek = double(seeker.stats().frames_decoded - start.frames_decoded) / 200;
  EXPECT_LE(decoded_per_seek, 20.0);  // ~GOP / 2 when each seek lands on the keyframe before
  std::cout << GetParam().file << ": " << decoded_per_seek << " frames decoded per random seek, "
            << seeker.stats().seeks - start.seeks << " seeks for 200 reads\n";

  // Backwards, the hardest order, and forwards with a stride (decodes on within a GOP, seeks across).
  for (int i = kFrames - 1; i >= 0; i -= 3)
    ASSERT_TRUE(same_pixels(seeker.read(i), frames[i])) << "backwards to frame " << i;
  for (int i = 1; i < kFrames; i += 7)
    ASSERT_TRUE(same_pixels(seeker.read(i), frames[i])) << "stride 7 at frame " << i;
}

INSTANTIATE_TEST_SUITE_P(
    Codecs, VideoSeek,
    ::testing::Values(SeekCase{"seek_h264_bf3_v1.mp4", kH264Options},
                      SeekCase{
                          "seek_hevc_bf4_opengop_v1.mp4",
                          "-c:v libx265 -preset veryfast -x265-params "
                          "bframes=4:b-adapt=0:keyint=30:min-keyint=30:open-gop=1:scenecut=0:log-level=error "
                          "-tag:v hvc1 -pix_fmt yuv420p"},
                      SeekCase{"seek_h264_bf3_v1.mkv", kH264Options}),
    [](const auto& info) {
      std::string n = info.param.file;
      for (char& c : n)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

// A recording cut short (the MP4's sample table, written first, lists 300 frames; the file holds 60% of
// them): the missing frames are listed, each frame that decodes shows the number its time stamp says, and
// one that does not gives an Error naming the file.
TEST(VideoSeekDamaged, CutShortRecordingListsMissingFramesAndKeepsTimesRight) {
  test::require_ffmpeg();
  if (HasFatalFailure()) return;
  const std::string full =
      test::cached_test_video("seek_h264_bf3_v1.mp4", kFrames, "30", kH264Options, test_frame);
  if (HasFailure()) return;
  test::TempFolder dir;
  const std::string fast = dir / "faststart.mp4";
  test::command_output("ffmpeg -v error -y -i '" + full + "' -c copy -movflags +faststart '" + fast + "'");
  std::ifstream in(fast, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = dir / "cut.mp4";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() * 6 / 10);

  auto source = FrameSource::open(cut);
  ASSERT_GT(source->frame_count(), 100);
  ASSERT_LT(source->frame_count(), kFrames);
  ASSERT_EQ(source->skipped().size(), 1u);
  EXPECT_NE(source->skipped()[0].reason.find("though the container says 300"), std::string::npos)
      << source->skipped()[0].reason;
  int failed = 0;
  for (int i = 0; i < source->frame_count(); ++i) {
    const int number = static_cast<int>(std::lround(source->timestamp_s(i) * 30));
    try {
      EXPECT_EQ(test::decode_frame_number(source->read(i), kBits), number) << "frame " << i;
    } catch (const Error& e) {
      ++failed;
      EXPECT_NE(std::string(e.what()).find("cut.mp4"), std::string::npos) << e.what();
    }
  }
  EXPECT_LE(failed, 3) << "only frames at the cut may fail";
}

// Variable frame rate: 60 frames at 30 fps, 60 at 15 fps, 60 at 24 fps (a phone slowing down in the dark).
double vfr_truth_s(int k) {
  if (k < 60) return k / 30.0;
  if (k < 120) return 2.0 + (k - 60) / 15.0;
  return 6.0 + (k - 120) / 24.0;
}

std::string vfr_video() {
  return test::cached_test_video(
      "vfr_30_15_24_h264_v1.mp4", 180, "30",
      "-vf "
      "\"settb=1/90000,setpts='if(lt(N\\,60)\\,N/30\\,if(lt(N\\,120)\\,2+(N-60)/15\\,6+(N-120)/24))/TB'\" "
      "-fps_mode passthrough -enc_time_base 1/90000 -video_track_timescale 90000 "
      "-c:v libx264 -preset veryfast -bf 3 -g 30 -pix_fmt yuv420p",
      test_frame);
}

TEST(VideoTimes, VariableFrameRateGivesEachFramesOwnTime) {
  test::require_ffmpeg();
  if (HasFatalFailure()) return;
  const std::string path = vfr_video();
  if (HasFailure()) return;
  auto source = FrameSource::open(path);
  ASSERT_EQ(source->frame_count(), 180);
  double worst = 0.0;
  for (int k = 0; k < 180; ++k) {
    worst = std::max(worst, std::abs(source->timestamp_s(k) - vfr_truth_s(k)));
    EXPECT_NEAR(source->timestamp_s(k), vfr_truth_s(k), 1e-3) << "frame " << k;
  }
  std::cout << "variable rate: worst time error " << worst * 1e3 << " ms\n";
  // Seeking by time is where frame number / rate goes wrong (the old cv::VideoCapture seek by
  // CAP_PROP_POS_FRAMES missed 148 of these 200): exact pixels and numbers.
  std::vector<cv::Mat> frames;
  for (int k = 0; k < 180; ++k) {
    frames.push_back(source->read(k));
    ASSERT_EQ(test::decode_frame_number(frames.back(), kBits), k) << "sequential frame " << k;
  }
  std::mt19937 random(22);
  std::uniform_int_distribution<int> pick(0, 179);
  for (int n = 0; n < 200; ++n) {
    const int k = pick(random);
    const cv::Mat m = source->read(k);
    ASSERT_EQ(test::decode_frame_number(m, kBits), k) << "seek " << n;
    ASSERT_TRUE(same_pixels(m, frames[k])) << "seek " << n << " to frame " << k;
  }

  // The project's Capture keeps the real times, and re-opening it with a range and stride gives them again.
  const Capture capture = capture_from_frame_source(*source);
  ASSERT_EQ(capture.frame_times_s.size(), 180u);
  for (int k = 0; k < 180; k += 11) {
    EXPECT_NEAR(capture.frame_time_s(k), vfr_truth_s(k), 1e-3);
    EXPECT_NEAR(capture.time_at_index_s(k), vfr_truth_s(k), 1e-3);
  }
  FrameSourceOptions options;
  options.first_frame = 50;
  options.stride = 4;
  auto range = FrameSource::open(path, options);
  const Capture ranged = capture_from_frame_source(*range);
  ASSERT_EQ(ranged.frame_times_s.size(), static_cast<std::size_t>(range->frame_count()));
  for (int i = 0; i < range->frame_count(); ++i) {
    EXPECT_NEAR(range->timestamp_s(i), vfr_truth_s(50 + 4 * i), 1e-3);
    EXPECT_EQ(test::decode_frame_number(range->read(i), kBits), 50 + 4 * i);
  }
  EXPECT_NEAR(ranged.time_at_index_s(54), vfr_truth_s(54), 1e-3) << "a kept frame, by its video frame number";
  auto reopened = FrameSource::open_capture(ranged);
  ASSERT_EQ(reopened->frame_count(), range->frame_count());
  EXPECT_NEAR(reopened->timestamp_s(5), vfr_truth_s(70), 1e-3);
}

TEST(VideoTimes, ConstantRateVideoKeepsNoTimeList) {
  test::require_ffmpeg();
  if (HasFatalFailure()) return;
  const std::string path =
      test::cached_test_video("cfr_2997_h264_v1.mp4", 60, "30000/1001",
                              "-c:v libx264 -preset veryfast -bf 3 -g 15 -pix_fmt yuv420p", test_frame);
  if (HasFailure()) return;
  auto source = FrameSource::open(path);
  ASSERT_EQ(source->frame_count(), 60);
  EXPECT_NEAR(source->frame_rate(), 30000.0 / 1001.0, 1e-6);
  for (int k = 0; k < 60; ++k) EXPECT_NEAR(source->timestamp_s(k), k * 1001.0 / 30000.0, 1e-6) << k;
  EXPECT_TRUE(capture_from_frame_source(*source).frame_times_s.empty());
}

}  // namespace
}  // namespace plenopath
