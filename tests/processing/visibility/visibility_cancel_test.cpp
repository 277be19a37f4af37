// cells_along_path reports progress and stops with Cancelled when its Progress is cancelled (the studio's
// Cancel, Ctrl+C on the command line).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <string>
#include <vector>

#include "processing/util/progress.h"
#include "processing/visibility/visibility.h"

namespace plenopath {
namespace {

// A hall of square pillars: many vertices, so the per-vertex windows take a while.
FloorPlan pillar_hall(int n) {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  auto box = [&](double x0, double y0, double x1, double y1) {
    const Eigen::Vector2d c[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (int k = 0; k < 4; ++k) plan.segments.push_back({c[k], c[(k + 1) % 4], "WALLS", true});
  };
  box(0, 0, 2.0 * n + 1, 2.0 * n + 1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) box(1.5 + 2 * i, 1.5 + 2 * j, 1.8 + 2 * i, 1.8 + 2 * j);
  return plan;
}

CameraPath diagonal_path(double length, int frames) {
  CameraPath path;
  for (int i = 0; i < frames; ++i) {
    const double t = 0.6 + length * i / (frames - 1);
    path.frames.push_back({i, "", t, 1.0 + 0.3 * t, 0.3, 1.0, 0, ""});
  }
  return path;
}

TEST(VisibilityCancel, ProgressIsReportedAndACancelStopsTheWork) {
  const FloorPlan plan = pillar_hall(12);
  const VisibilityIndex index(plan);
  const CameraPath path = diagonal_path(18.0, 400);

  double lowest = 2, highest = -1;
  int calls = 0;
  std::vector<std::string> stages;
  FunctionProgress progress([&](double f, const std::string& stage) {  // one call at a time
    lowest = std::min(lowest, f);
    highest = std::max(highest, f);
    ++calls;
    if (!stage.empty()) stages.push_back(stage);
  });
  const VisibilityCells full = index.cells_along_path(path, progress);
  EXPECT_GT(calls, 3);
  EXPECT_GE(lowest, 0.0);
  EXPECT_LE(highest, 1.0);
  EXPECT_GT(highest, 0.6);  // the cells' envelopes report too
  EXPECT_GT(full.cells.size(), 10u);
  EXPECT_NE(std::find(stages.begin(), stages.end(), "visibility windows"), stages.end());

  // Cancelled at the third report (from the worker threads): Cancelled reaches the caller.
  std::atomic<int> seen{0};
  const auto t0 = std::chrono::steady_clock::now();
  FunctionProgress cancelling([&](double, const std::string&) {
    if (++seen > 2) cancelling.cancel();
  });
  EXPECT_THROW(index.cells_along_path(path, cancelling), Cancelled);
  const double cancelled_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("visibility: %d progress calls; a cancel returned after %.3f s\n", calls, cancelled_s);
}

// Cancelled at the first report: Cancelled, and nothing after it (one thread, so the count is exact).
TEST(VisibilityCancel, CancelAfterTheFirstReport) {
  VisibilityOptions one_thread;
  one_thread.threads = 1;
  const VisibilityIndex index(pillar_hall(6), one_thread);
  const CameraPath path = diagonal_path(10.0, 100);
  std::atomic<int> seen{0};
  FunctionProgress progress([&](double, const std::string&) {
    ++seen;
    progress.cancel();
  });
  EXPECT_THROW(index.cells_along_path(path, progress), Cancelled);
  EXPECT_EQ(seen.load(), 1);
}

}  // namespace
}  // namespace plenopath
