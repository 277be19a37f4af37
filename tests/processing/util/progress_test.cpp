// The one progress contract: sub-range arithmetic by hand, the stage text carried up, cancellation seen
// through every level, the null progress, and Cancelled as the error that ends a run.
#include "processing/util/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>
#include <utility>
#include <vector>

#include "model/error.h"

namespace plenopath {
namespace {

// Records every report it gets.
struct Recorder {
  std::vector<std::pair<double, std::string>> reports;
  FunctionProgress progress{[this](double f, const std::string& stage) { reports.emplace_back(f, stage); }};
};

TEST(Progress, SubRangeMapsOntoItsPartOfTheParent) {
  Recorder r;
  SubProgress sub(r.progress, 0.2, 0.6);
  sub.report(0.0);
  sub.report(0.5);
  sub.report(1.0);
  ASSERT_EQ(r.reports.size(), 3u);
  EXPECT_DOUBLE_EQ(r.reports[0].first, 0.2);
  EXPECT_DOUBLE_EQ(r.reports[1].first, 0.4);  // 0.2 + 0.5 * (0.6 - 0.2)
  EXPECT_DOUBLE_EQ(r.reports[2].first, 0.6);
  // Out of range and not-a-number are clamped, never passed on.
  sub.report(1.5);
  sub.report(-3.0);
  sub.report(std::nan(""));
  EXPECT_DOUBLE_EQ(r.reports[3].first, 0.6);
  EXPECT_DOUBLE_EQ(r.reports[4].first, 0.2);
  EXPECT_DOUBLE_EQ(r.reports[5].first, 0.2);
}

TEST(Progress, NestedSubRangesCompose) {
  Recorder r;
  SubProgress outer(r.progress, 0.5, 1.0);  // the second half
  SubProgress inner(outer, 0.25, 0.75);     // its middle half: [0.625, 0.875] of the whole
  inner.report(0.0);
  inner.report(0.5);
  inner.report(1.0);
  ASSERT_EQ(r.reports.size(), 3u);
  EXPECT_DOUBLE_EQ(r.reports[0].first, 0.625);
  EXPECT_DOUBLE_EQ(r.reports[1].first, 0.75);
  EXPECT_DOUBLE_EQ(r.reports[2].first, 0.875);
  EXPECT_DOUBLE_EQ(inner.parent_fraction(0.5), 0.5);  // into `outer`'s own [0, 1]
  EXPECT_DOUBLE_EQ(outer.parent_fraction(0.5), 0.75);
}

TEST(Progress, SubRangeEndsAreClampedAndOrdered) {
  Recorder r;
  SubProgress reversed(r.progress, 0.8, 0.3);  // an empty range at 0.8, never backwards
  reversed.report(0.5);
  SubProgress wide(r.progress, -1.0, 2.0);  // the whole range
  wide.report(0.25);
  ASSERT_EQ(r.reports.size(), 2u);
  EXPECT_DOUBLE_EQ(r.reports[0].first, 0.8);
  EXPECT_DOUBLE_EQ(r.reports[1].first, 0.25);
}

TEST(Progress, StageTextIsCarriedToTheParent) {
  Recorder r;
  SubProgress sub(r.progress, 0.0, 0.5, "refinement");
  sub.report(0.0);                 // no text yet: the range's stage, once
  sub.report(0.1);                 // then nothing new
  sub.report(0.2, "iteration 3");  // the child's text under the range's stage
  SubProgress plain(r.progress, 0.5, 1.0);
  plain.report(0.5, "resection");  // a range without a stage passes the child's text on
  plain.report(0.6);
  ASSERT_EQ(r.reports.size(), 5u);
  EXPECT_EQ(r.reports[0].second, "refinement");
  EXPECT_EQ(r.reports[1].second, "");
  EXPECT_EQ(r.reports[2].second, "refinement: iteration 3");
  EXPECT_EQ(r.reports[3].second, "resection");
  EXPECT_EQ(r.reports[4].second, "");
}

TEST(Progress, CancelIsSeenThroughEverySubRangeAndCheckpointThrows) {
  Recorder r;
  SubProgress outer(r.progress, 0.0, 0.5);
  SubProgress inner(outer, 0.5, 1.0);
  EXPECT_FALSE(inner.is_cancelled());
  EXPECT_NO_THROW(inner.checkpoint(0.5));
  r.progress.cancel();
  EXPECT_TRUE(inner.is_cancelled());
  EXPECT_THROW(inner.throw_if_cancelled(), Cancelled);
  // checkpoint reports first, then throws: the last fraction reaches the display.
  EXPECT_THROW(inner.checkpoint(1.0, "last"), Cancelled);
  ASSERT_EQ(r.reports.size(), 2u);
  EXPECT_DOUBLE_EQ(r.reports[1].first, 0.5);
  EXPECT_EQ(r.reports[1].second, "last");
}

TEST(Progress, CancelledIsAnErrorThatSaysCancelled) {
  try {
    FunctionProgress p;
    p.cancel();
    p.checkpoint(0.1);
    FAIL() << "no throw";
  } catch (const Error& e) {  // a handler that only knows Error still ends the run cleanly
    EXPECT_STREQ(e.what(), "cancelled");
    EXPECT_NE(dynamic_cast<const Cancelled*>(&e), nullptr);
  }
}

TEST(Progress, NullProgressIsNeverCancelled) {
  Progress& none = null_progress();
  none.report(0.5, "anything");
  EXPECT_FALSE(none.is_cancelled());
  EXPECT_NO_THROW(none.checkpoint(1.0));
  SubProgress sub(none, 0.0, 0.5, "stage");
  EXPECT_NO_THROW(sub.checkpoint(0.5, "more"));
}

// Reports from several threads reach the function one at a time; a cancel from another thread is seen.
TEST(Progress, ReportsFromThreadsAreSerialisedAndCancelCrossesThreads) {
  int in_function = 0, most = 0, calls = 0;
  FunctionProgress p([&](double, const std::string&) {
    most = std::max(most, ++in_function);
    ++calls;
    std::this_thread::yield();
    --in_function;
  });
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&p] {
      SubProgress sub(p, 0.0, 1.0, "worker");
      for (int i = 0; i < 500; ++i) sub.report(i / 500.0);
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(calls, 2000);
  EXPECT_EQ(most, 1);
  std::atomic<bool> seen{false};
  std::thread watcher([&] {
    while (!p.is_cancelled()) std::this_thread::yield();
    seen = true;
  });
  p.cancel();
  watcher.join();
  EXPECT_TRUE(seen.load());
}

}  // namespace
}  // namespace plenopath
