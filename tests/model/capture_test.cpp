// The Capture's frame index <-> kept frame mapping (issue 17), against values worked out by hand.
#include "model/capture.h"

#include <gtest/gtest.h>

namespace plenopath {
namespace {

Capture video(int first, int stride, int count) {
  Capture c;
  c.kind = CaptureKind::kVideo;
  c.first_frame = first;
  c.stride = stride;
  c.frame_count = count;
  return c;
}

TEST(CaptureMapping, VideoKeptFramesAreFirstPlusStrideSteps) {
  // Frames 10, 13, 16, 19 of the video are kept.
  const Capture c = video(10, 3, 4);
  EXPECT_EQ(c.frame_index_of_kept(0), 10);
  EXPECT_EQ(c.frame_index_of_kept(1), 13);
  EXPECT_EQ(c.frame_index_of_kept(3), 19);
  EXPECT_EQ(c.kept_of_frame_index(10), 0);
  EXPECT_EQ(c.kept_of_frame_index(13), 1);
  EXPECT_EQ(c.kept_of_frame_index(19), 3);
  EXPECT_EQ(c.kept_of_frame_index(11), -1);  // between strides
  EXPECT_EQ(c.kept_of_frame_index(9), -1);   // before the first kept frame
  EXPECT_EQ(c.kept_of_frame_index(7), -1);   // a stride before it
  EXPECT_EQ(c.kept_of_frame_index(22), -1);  // a fifth kept frame would be 22: beyond frame_count
  EXPECT_EQ(c.kept_of_frame_index(-3), -1);
}

TEST(CaptureMapping, VideoStrideZeroCountsAsOne) {
  const Capture c = video(5, 0, 3);
  EXPECT_EQ(c.frame_index_of_kept(2), 7);
  EXPECT_EQ(c.kept_of_frame_index(6), 1);
  EXPECT_EQ(c.kept_of_frame_index(8), -1);
}

TEST(CaptureMapping, FolderIndexIsThePositionInTheCapture) {
  // A folder's first_frame and stride chose the files; the kept ones are numbered 0..n-1.
  Capture c;
  c.kind = CaptureKind::kImageFolder;
  c.first_frame = 2;
  c.stride = 2;
  c.frame_count = 3;
  c.frame_names = {"b.jpg", "d.jpg", "f.jpg"};
  EXPECT_EQ(c.frame_index_of_kept(0), 0);
  EXPECT_EQ(c.frame_index_of_kept(2), 2);
  EXPECT_EQ(c.kept_of_frame_index(1), 1);
  EXPECT_EQ(c.kept_of_frame_index(3), -1);
  EXPECT_EQ(c.kept_of_frame_index(-1), -1);
}

TEST(CaptureMapping, RoundTripsEveryKeptFrame) {
  const Capture c = video(1, 4, 25);
  for (int k = 0; k < c.frame_count; ++k) EXPECT_EQ(c.kept_of_frame_index(c.frame_index_of_kept(k)), k);
}

TEST(CaptureMapping, TimesFollowTheMapping) {
  // 25 fps, kept frame 2 is video frame 10 + 2 * 3 = 16: 0.64 s.
  Capture c = video(10, 3, 4);
  c.frame_rate = 25.0;
  EXPECT_DOUBLE_EQ(c.frame_time_s(2), 0.64);
  EXPECT_DOUBLE_EQ(c.time_at_index_s(c.frame_index_of_kept(2)), 16 / 25.0);
}

}  // namespace
}  // namespace plenopath
