// The one "newest request wins" runner (widgets/coalescing_runner.h): a burst of requests runs at most two
// jobs and delivers only the last; a newer request and cancel() reach the running job through its Progress;
// results arrive on the GUI thread; destroying the runner while a job runs is safe. The sequence is checked,
// never the time.
#include "widgets/coalescing_runner.h"

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QSignalSpy>
#include <QThread>
#include <atomic>
#include <memory>
#include <vector>

#include "model/error.h"
#include "tests/widgets/wait_until.h"

namespace plenopath {
namespace {

using widgets::CoalescingRunner;

// A job that polls for cancellation until it is cancelled (at most a minute), noting that it saw it.
CoalescingRunner::Job until_cancelled(std::atomic<bool>& started, std::atomic<bool>& saw_cancel,
                                      std::vector<int>& delivered, int id) {
  return [&started, &saw_cancel, &delivered, id](Progress& progress) -> CoalescingRunner::Delivery {
    started = true;
    for (int i = 0; i < 60000 && !progress.is_cancelled(); ++i) QThread::msleep(1);
    saw_cancel = progress.is_cancelled();
    progress.throw_if_cancelled();
    return [&delivered, id] { delivered.push_back(id); };
  };
}

TEST(CoalescingRunner, ABurstRunsAtMostTwoJobsAndDeliversOnlyTheLast) {
  CoalescingRunner runner;
  std::vector<int> delivered;
  std::atomic<int> ran{0};
  const QThread* gui = QThread::currentThread();
  bool on_gui_thread = true;
  const int n = 40;
  for (int id = 0; id < n; ++id)
    runner.request(
        [id, &ran, &delivered, gui, &on_gui_thread](Progress& progress) -> CoalescingRunner::Delivery {
          ++ran;
          for (int k = 0; k < 20; ++k) {
            progress.checkpoint(k / 20.0, "step");
            QThread::msleep(1);
          }
          return [id, &delivered, gui, &on_gui_thread] {
            on_gui_thread = on_gui_thread && QThread::currentThread() == gui;
            delivered.push_back(id);
          };
        });
  EXPECT_TRUE(runner.busy());
  EXPECT_TRUE(runner.waiting());
  runner.wait();
  EXPECT_FALSE(runner.busy());
  // The first started at once; the 39 others replaced each other while it ran; the last ran after it.
  EXPECT_EQ(runner.started_count(), 2);
  EXPECT_EQ(ran.load(), 2);
  EXPECT_EQ(delivered, std::vector<int>{n - 1});
  EXPECT_TRUE(on_gui_thread);
}

TEST(CoalescingRunner, ANewerRequestCancelsTheRunningJob) {
  CoalescingRunner runner;
  std::vector<int> delivered;
  std::atomic<bool> started{false}, saw_cancel{false};
  runner.request(until_cancelled(started, saw_cancel, delivered, 1));
  ASSERT_TRUE(test::wait_until([&] { return started.load(); }, 60000));
  EXPECT_FALSE(saw_cancel);
  runner.request([&delivered](Progress&) -> CoalescingRunner::Delivery {
    return [&delivered] { delivered.push_back(2); };
  });
  ASSERT_TRUE(test::wait_until([&] { return !runner.busy(); }, 60000));
  EXPECT_TRUE(saw_cancel) << "the running job was asked to stop";
  EXPECT_EQ(delivered, std::vector<int>{2});
  EXPECT_EQ(runner.started_count(), 2);
}

TEST(CoalescingRunner, CancelReachesTheRunningJobAndDeliversNothing) {
  CoalescingRunner runner;
  std::vector<int> delivered;
  std::atomic<bool> started{false}, saw_cancel{false};
  QSignalSpy finished(&runner, &CoalescingRunner::job_finished);
  QSignalSpy failed(&runner, &CoalescingRunner::failed);
  runner.request(until_cancelled(started, saw_cancel, delivered, 1));
  ASSERT_TRUE(test::wait_until([&] { return started.load(); }, 60000));
  runner.cancel();
  ASSERT_TRUE(test::wait_until([&] { return !runner.busy(); }, 60000));
  EXPECT_TRUE(saw_cancel);
  EXPECT_TRUE(delivered.empty());
  EXPECT_EQ(finished.count(), 1);
  EXPECT_EQ(failed.count(), 0) << "cancelled, not failed";
  // Idle again: the next request runs and delivers.
  runner.request([&delivered](Progress&) -> CoalescingRunner::Delivery {
    return [&delivered] { delivered.push_back(3); };
  });
  runner.wait();
  EXPECT_EQ(delivered, std::vector<int>{3});
}

TEST(CoalescingRunner, OnlyTheNewestRequestsFailureIsReported) {
  CoalescingRunner runner;
  QSignalSpy failed(&runner, &CoalescingRunner::failed);
  std::atomic<bool> release{false};
  // The first fails after a newer request came: dropped. The newest fails: reported.
  runner.request([&release](Progress&) -> CoalescingRunner::Delivery {
    for (int i = 0; i < 60000 && !release; ++i) QThread::msleep(1);
    throw Error("old: bad input");
  });
  runner.request([](Progress&) -> CoalescingRunner::Delivery { throw Error("new: bad input"); });
  release = true;
  runner.wait();
  ASSERT_EQ(failed.count(), 1);
  EXPECT_EQ(failed.at(0).at(0).toString(), "new: bad input");
}

TEST(CoalescingRunner, DestroyedWhileAJobRunsCancelsItAndDeliversNothing) {
  std::vector<int> delivered;
  std::atomic<bool> started{false}, saw_cancel{false};
  {
    CoalescingRunner runner;
    runner.request(until_cancelled(started, saw_cancel, delivered, 1));
    runner.request(until_cancelled(started, saw_cancel, delivered, 2));  // waits; never runs
    ASSERT_TRUE(test::wait_until([&] { return started.load(); }, 60000));
  }
  EXPECT_TRUE(saw_cancel) << "the destructor cancelled the running job and waited for it";
  // A job that finished but whose delivery was still queued when the runner went: never delivered.
  {
    CoalescingRunner runner;
    std::atomic<bool> done{false};
    runner.request([&done, &delivered](Progress&) -> CoalescingRunner::Delivery {
      done = true;
      return [&delivered] { delivered.push_back(3); };
    });
    for (int i = 0; i < 60000 && !done; ++i) QThread::msleep(1);
    QThread::msleep(5);
  }
  QCoreApplication::processEvents();
  EXPECT_TRUE(delivered.empty());
}

}  // namespace
}  // namespace plenopath
