#include "processing/util/background_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace plenopath {
namespace {

TEST(BackgroundQueue, RunsJobsInOrderAndNeverFallsMoreThanCapacityBehind) {
  for (int capacity : {1, 2, 5}) {
    BackgroundQueue queue(capacity);
    EXPECT_EQ(queue.capacity(), capacity);
    std::mutex mutex;
    std::vector<int> order;
    std::atomic<int> done{0};
    std::vector<std::weak_ptr<int>> captured;
    const int n = 200;
    for (int i = 0; i < n; ++i) {
      auto buffer = std::make_shared<int>(i);
      captured.push_back(buffer);
      queue.submit([&, i, buffer] {
        if (i % 7 == 0) std::this_thread::yield();  // a slow writer now and then
        std::lock_guard<std::mutex> lock(mutex);
        order.push_back(*buffer);
        ++done;
      });
      buffer.reset();
      // Every job queued more than `capacity` submissions ago has run and released what it captured.
      ASSERT_GE(done.load(), i - capacity) << capacity;
      for (int k = 0; k < i - capacity; ++k) ASSERT_TRUE(captured[k].expired()) << k;
    }
    queue.finish();
    ASSERT_EQ(static_cast<int>(order.size()), n);
    for (int i = 0; i < n; ++i) EXPECT_EQ(order[i], i);
  }
}

TEST(BackgroundQueue, RethrowsTheFirstErrorAndSkipsWhatWasQueuedAfterIt) {
  BackgroundQueue queue(3);
  std::atomic<int> ran{0};
  std::promise<void> gate;  // holds the first job until all three are queued
  std::shared_future<void> all_queued = gate.get_future().share();
  queue.submit([&, all_queued] {
    all_queued.wait();
    ++ran;
  });
  queue.submit([&] { throw std::runtime_error("disk full"); });
  queue.submit([&] { ++ran; });
  gate.set_value();
  EXPECT_THROW(queue.finish(), std::runtime_error);
  EXPECT_EQ(ran.load(), 1);
  // The error is reported once; the queue goes on working.
  queue.submit([&] { ran = 100; });
  queue.finish();
  EXPECT_EQ(ran.load(), 100);
}

TEST(BackgroundQueue, ReportsAnErrorAtTheNextSubmit) {
  BackgroundQueue queue(1);
  queue.submit([] { throw std::runtime_error("cannot write"); });
  bool thrown = false;
  for (int i = 0; i < 3 && !thrown; ++i) {
    try {
      queue.submit([] {});
    } catch (const std::runtime_error&) {
      thrown = true;
    }
  }
  if (!thrown) {
    EXPECT_THROW(queue.finish(), std::runtime_error);
  }
}

TEST(BackgroundQueue, DestructorWaitsForQueuedJobs) {
  std::atomic<int> ran{0};
  {
    BackgroundQueue queue(4);
    for (int i = 0; i < 4; ++i) queue.submit([&] { ++ran; });
  }
  EXPECT_EQ(ran.load(), 4);
}

}  // namespace
}  // namespace plenopath
