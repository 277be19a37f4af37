// The packed track history: every observation the tracker keeps is within half a packing unit (1/128 px at
// 512 wide ... 1/64 px at 1024: width / 65536 / 2) of where it followed the feature at full precision, and
// takes about 4 bytes, not the 12 (plus a vector per track) of TrackObservation.
#include "processing/egomotion/klt_tracks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "model/error.h"

namespace plenopath {
namespace {

TEST(KltTracks, PackedHistoryKeepsTheFollowedPositions) {
  const cv::Mat image = cv::imread(std::string(PLENOPATH_TEST_DATA_DIR) + "/convention/pano_heading0.png");
  ASSERT_FALSE(image.empty());
  KltOptions options;
  options.work_width = 0;
  options.quality_level = 0.0005;
  options.min_distance_px = 5;
  options.max_track_frames = 8;  // cut often: closed tracks as well as live ones
  KltTracker tracker(options);
  const double half_unit = image.cols / 65536.0 / 2.0;
  std::size_t compared = 0;
  for (int i = 0; i < 40; ++i) {
    // A turn of 3 columns a frame (the corners themselves are sub-pixel, off the packing grid).
    const int shift = (3 * i) % image.cols;
    cv::Mat turned = image.clone();
    if (shift > 0)
      cv::hconcat(image.colRange(image.cols - shift, image.cols), image.colRange(0, image.cols - shift),
                  turned);
    tracker.add_frame(turned);
    const std::vector<int>& live = tracker.live_tracks();
    const std::vector<cv::Point2f>& followed = tracker.live_positions();
    ASSERT_EQ(live.size(), followed.size());
    for (std::size_t k = 0; k < live.size(); ++k) {
      const TrackObservation o = tracker.last_observation(live[k]);
      EXPECT_EQ(o.frame, i);
      EXPECT_LE(std::abs(o.x - followed[k].x), half_unit + 1e-4);
      EXPECT_LE(std::abs(o.y - followed[k].y), half_unit + 1e-4);
      ++compared;
    }
  }
  EXPECT_GT(compared, 500u);
  // The unpacked history agrees with the packed accessors, and tracks are consecutive frames.
  const std::vector<FeatureTrack> all = tracker.tracks();
  ASSERT_EQ(static_cast<int>(all.size()), tracker.track_count());
  std::size_t observations = 0;
  for (int t = 0; t < tracker.track_count(); ++t) {
    const auto& obs = all[static_cast<std::size_t>(t)].observations;
    ASSERT_EQ(static_cast<int>(obs.size()), tracker.last_frame(t) - tracker.first_frame(t) + 1);
    for (std::size_t k = 0; k < obs.size(); ++k)
      EXPECT_EQ(obs[k].frame, tracker.first_frame(t) + static_cast<int>(k));
    EXPECT_TRUE(tracker.seen(t, tracker.first_frame(t)));
    EXPECT_FALSE(tracker.seen(t, tracker.last_frame(t) + 1));
    observations += obs.size();
  }
  const TrackMemory memory = tracker.memory();
  EXPECT_EQ(memory.observations, observations);
  // TrackObservation alone is 12 bytes, and each track had a vector of them.
  EXPECT_LT(double(memory.bytes) / double(memory.observations), 10.0);
  std::printf("track history: %zu observations of %zu tracks in %zu bytes (%.2f a observation)\n",
              memory.observations, memory.tracks, memory.bytes, double(memory.bytes) / memory.observations);
}

// A bad exposure-jump threshold is refused, naming the field.
TEST(KltTracks, ABadExposureJumpIsRefused) {
  KltOptions options;
  options.exposure_jump = 0.0;
  try {
    options.check();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("exposure_jump"), std::string::npos) << e.what();
  }
}

TEST(KltTracks, ABadRetryShareIsRefusedByName) {
  for (const double bad : {-0.1, 1.5, std::nan("")}) {
    KltOptions options;
    options.retry_share = bad;
    try {
      options.check();
      ADD_FAILURE() << "no error for " << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("KltOptions.retry_share must be in [0, 1]"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace plenopath
