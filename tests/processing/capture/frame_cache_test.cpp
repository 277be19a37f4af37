#include "processing/capture/frame_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "tests/processing/capture/capture_test_util.h"

namespace plenopath {
namespace {

using test::decode_frame_number;
using test::numbered_frame;

constexpr int kW = 64, kH = 32;
constexpr std::size_t kFrameBytes = std::size_t(kW) * kH * 3;

struct CountingSource {
  std::shared_ptr<std::atomic<int>> decodes = std::make_shared<std::atomic<int>>(0);
  std::shared_ptr<FrameSource> source;
  explicit CountingSource(int count, int bad_frame = -1, int sleep_ms = 0) {
    auto decodes_ = decodes;
    source = FrameSource::from_generator(count, kW, kH, 30.0, [decodes_, bad_frame, sleep_ms](int i) {
      ++*decodes_;
      if (sleep_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(sleep_ms));
      if (i == bad_frame) throw Error("frame " + std::to_string(i) + " is broken");
      return numbered_frame(i % 256, kW, kH);
    });
  }
};

TEST(FrameCache, NeverExceedsItsBoundAndEvictsLeastRecentlyUsed) {
  CountingSource counting(200);
  FrameCacheOptions options;
  options.frame_bytes_bound = 10 * kFrameBytes + kFrameBytes / 2;  // room for 10 frames, not 11
  options.background_prefetch = false;
  FrameCache cache(counting.source, options);

  for (int i = 0; i < 10; ++i) EXPECT_EQ(decode_frame_number(cache.get(i)), i);
  EXPECT_EQ(*counting.decodes, 10);
  EXPECT_EQ(decode_frame_number(cache.get(0)), 0);  // a hit: frame 0 becomes the most recent
  EXPECT_EQ(*counting.decodes, 10);
  cache.get(10);  // evicts frame 1, the least recently used, not frame 0
  EXPECT_TRUE(cache.contains(0));
  EXPECT_FALSE(cache.contains(1));
  for (int i = 2; i <= 10; ++i) EXPECT_TRUE(cache.contains(i)) << i;
  EXPECT_TRUE(cache.peek(1).empty());
  EXPECT_EQ(decode_frame_number(cache.peek(5)), 5);

  for (int i = 11; i < 200; ++i) {
    cache.get(i);
    const FrameCacheStats s = cache.stats();
    ASSERT_LE(s.frame_bytes, options.frame_bytes_bound);
    ASSERT_EQ(s.frame_bytes, std::size_t(s.frames_held) * kFrameBytes);  // counted bytes = held frames
  }
  const FrameCacheStats s = cache.stats();
  EXPECT_EQ(s.frames_held, 10);
  EXPECT_LE(s.peak_frame_bytes, options.frame_bytes_bound);
  EXPECT_EQ(s.hits, 1);
  EXPECT_EQ(s.misses, 200);
  EXPECT_EQ(s.evictions, 190);
  for (int i = 190; i < 200; ++i) EXPECT_TRUE(cache.contains(i));
}

TEST(FrameCache, FrameLargerThanTheBoundIsReturnedButNotKept) {
  CountingSource counting(5);
  FrameCacheOptions options;
  options.frame_bytes_bound = kFrameBytes / 2;
  options.background_prefetch = false;
  FrameCache cache(counting.source, options);
  EXPECT_EQ(decode_frame_number(cache.get(3)), 3);
  EXPECT_FALSE(cache.contains(3));
  EXPECT_EQ(cache.stats().peak_frame_bytes, 0u);
}

TEST(FrameCache, PrefetchesAroundThePlayHeadInTheScrubDirection) {
  CountingSource counting(100);
  FrameCacheOptions options;
  options.frame_bytes_bound = 20 * kFrameBytes;
  options.prefetch_ahead = 4;
  options.prefetch_behind = 1;
  FrameCache cache(counting.source, options);
  cache.get(50);
  cache.prefetch(50, +1);
  cache.wait_for_prefetch();
  for (int i = 51; i <= 54; ++i) EXPECT_TRUE(cache.contains(i)) << i;
  EXPECT_TRUE(cache.contains(49));
  EXPECT_FALSE(cache.contains(55));
  const int decodes = *counting.decodes;
  for (int i = 51; i <= 54; ++i) EXPECT_EQ(decode_frame_number(cache.get(i)), i);
  EXPECT_EQ(*counting.decodes, decodes);  // all hits

  cache.prefetch(20, -1);
  cache.wait_for_prefetch();
  for (int i = 16; i <= 19; ++i) EXPECT_TRUE(cache.contains(i)) << i;
  EXPECT_TRUE(cache.contains(21));
  EXPECT_EQ(cache.stats().prefetched, 10);
}

TEST(FrameCache, PrefetchNeverQueuesMoreThanFits) {
  CountingSource counting(100);
  FrameCacheOptions options;
  options.frame_bytes_bound = 3 * kFrameBytes;  // play head + 2
  options.prefetch_ahead = 10;
  FrameCache cache(counting.source, options);
  cache.get(10);
  cache.prefetch(10, +1);
  cache.wait_for_prefetch();
  EXPECT_TRUE(cache.contains(10));  // the frame on screen survives prefetching
  EXPECT_TRUE(cache.contains(11));
  EXPECT_TRUE(cache.contains(12));
  EXPECT_LE(cache.stats().peak_frame_bytes, options.frame_bytes_bound);
}

TEST(FrameCache, BadFrameIsReportedAndDoesNotStopTheWorker) {
  CountingSource counting(30, 13);
  FrameCacheOptions options;
  options.prefetch_ahead = 5;
  FrameCache cache(counting.source, options);
  cache.prefetch(11, +1);  // includes frame 13
  cache.wait_for_prefetch();
  EXPECT_TRUE(cache.contains(12));
  EXPECT_TRUE(cache.contains(14));
  EXPECT_THROW(cache.get(13), Error);
  const auto failures = cache.failures();
  ASSERT_EQ(failures.size(), 1u);
  EXPECT_EQ(failures[0].first, 13);
  EXPECT_NE(failures[0].second.find("broken"), std::string::npos);
  cache.prefetch(20, +1);  // the worker still runs
  cache.wait_for_prefetch();
  EXPECT_TRUE(cache.contains(21));
  EXPECT_THROW(cache.get(30), Error);  // out of range: an error, not a crash
}

TEST(FrameCache, ThumbnailsAreSmallAndBounded) {
  CountingSource counting(100);
  FrameCacheOptions options;
  options.thumbnail_width = 16;
  options.thumbnail_bytes_bound = 20 * 16 * 8 * 3;
  FrameCache cache(counting.source, options);
  const cv::Mat t = cache.thumbnail(7);
  EXPECT_EQ(t.cols, 16);
  EXPECT_EQ(t.rows, 8);
  cache.prefetch_thumbnails(0, 99, 1);
  cache.wait_for_prefetch();
  const FrameCacheStats s = cache.stats();
  EXPECT_EQ(s.thumbnails_held, 20);
  EXPECT_LE(s.peak_thumbnail_bytes, options.thumbnail_bytes_bound);
  EXPECT_EQ(s.frame_bytes, 0u);  // thumbnails do not fill the frame cache
}

TEST(FrameCache, DestructorCancelsQueuedWorkAndJoins) {
  CountingSource counting(1000, -1, 2);
  {
    FrameCacheOptions options;
    options.prefetch_ahead = 500;
    options.frame_bytes_bound = 600 * kFrameBytes;
    FrameCache cache(counting.source, options);
    cache.prefetch(0, +1);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }  // must not decode the remaining ~500 frames before returning
  EXPECT_LT(*counting.decodes, 400);
}

TEST(FrameCache, ConcurrentReadersSeeTheRightFrames) {
  CountingSource counting(300);
  FrameCacheOptions options;
  options.frame_bytes_bound = 16 * kFrameBytes;
  FrameCache cache(counting.source, options);
  std::atomic<int> wrong{0};
  std::vector<std::thread> readers;
  for (int t = 0; t < 3; ++t) {
    readers.emplace_back([&, t] {
      for (int k = 0; k < 300; ++k) {
        const int i = (k * (t + 1) * 7) % 300;
        cache.prefetch(i, t % 2 ? -1 : 1);
        if (decode_frame_number(cache.get(i)) != i % 256) ++wrong;
      }
    });
  }
  for (auto& r : readers) r.join();
  EXPECT_EQ(wrong, 0);
  EXPECT_LE(cache.stats().peak_frame_bytes, options.frame_bytes_bound);
}

TEST(FrameCacheOptions, CheckReportsBadFields) {
  FrameCacheOptions o;
  o.frame_bytes_bound = 0;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.thumbnail_width = 2;
  EXPECT_THROW(o.check(), Error);
}

}  // namespace
}  // namespace plenopath
