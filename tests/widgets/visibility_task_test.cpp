// The studio's Compute visibility on a large plan: Cancel reaches the cells' workers and leaves the document
// as it was (no undo step).
#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QSignalSpy>
#include <QThread>
#include <QUndoStack>
#include <atomic>

#include "app/studio/studio_tasks.h"
#include "tests/widgets/wait_until.h"
#include "widgets/project_document.h"
#include "widgets/task_runner.h"

namespace plenopath {
namespace {

Project pillar_hall_project(int n) {
  Project p;
  p.plan.layers = {{"WALLS", 7, true, true, 0}};
  auto box = [&](double x0, double y0, double x1, double y1) {
    const Eigen::Vector2d c[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (int k = 0; k < 4; ++k) p.plan.segments.push_back({c[k], c[(k + 1) % 4], "WALLS", true});
  };
  box(0, 0, 2.0 * n + 1, 2.0 * n + 1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) box(1.5 + 2 * i, 1.5 + 2 * j, 1.8 + 2 * i, 1.8 + 2 * j);
  for (int i = 0; i < 3000; ++i) {
    const double t = 0.6 + 2.0 * n * i / 3000.0;
    p.path.frames.push_back({i, "", t, 1.0 + 0.45 * t, 0.4, 1.0, 0, ""});
  }
  return p;
}

TEST(VisibilityTask, CancelReachesTheCellsAndChangesNothing) {
  widgets::ProjectDocument document;
  document.reset(pillar_hall_project(25), QString());
  widgets::TaskRunner runner(document);
  QSignalSpy finished(&runner, &widgets::TaskRunner::finished);
  QSignalSpy cancelled(&runner, &widgets::TaskRunner::cancelled);
  // The first report from inside the cells (past 0.3: the index is built) holds its worker until the cancel
  // is sent: the cancel lands in the middle of the run whatever the load. No wall-clock assertion; the time
  // the stop took is printed.
  std::atomic<bool> inside{false}, cancel_sent{false};
  runner.set_report_hook([&](double fraction, const std::string&) {
    if (fraction <= 0.3) return;
    inside = true;
    for (int i = 0; i < 60000 && !cancel_sent; ++i) QThread::msleep(1);
  });
  ASSERT_TRUE(runner.start("Compute visibility", studio::compute_visibility_task()));
  const bool reached = test::wait_until([&] { return inside.load() || !runner.is_running(); }, 120000);
  QElapsedTimer clock;
  clock.start();
  runner.cancel();
  cancel_sent = true;
  ASSERT_TRUE(reached);
  ASSERT_TRUE(inside) << "the task finished before it reported from the cells";
  ASSERT_TRUE(test::wait_until([&] { return !runner.is_running(); }, 120000));
  std::printf("compute visibility cancelled after %lld ms\n", static_cast<long long>(clock.elapsed()));
  EXPECT_EQ(cancelled.count(), 1);
  ASSERT_EQ(finished.count(), 1);
  EXPECT_FALSE(finished.at(0).at(0).toBool());
  EXPECT_TRUE(document.project().visibility.empty());
  EXPECT_EQ(document.undo_stack()->count(), 0);
}

}  // namespace
}  // namespace plenopath
