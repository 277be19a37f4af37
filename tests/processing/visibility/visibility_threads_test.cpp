// Worker threads share one VisibilityIndex: its arrangement must only be read while they run. Before the
// index filled CGAL's lazily cached supporting lines at build time, two threads writing the same cache
// crashed 16 of 20 runs of this test; each round here uses a fresh index, because the
// race can only happen the first time each wall is looked at.
#include <gtest/gtest.h>

#include "model/path_io.h"
#include "processing/visibility/visibility.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

TEST(VisibilityThreads, FreshIndexesGiveTheSingleThreadedCellsOnTwoThreads) {
  const FloorPlan plan = make_office_sample_plan();
  const CameraPath path =
      read_path_file(std::string(PLENOPATH_SOURCE_DIR) + "/resources/samples/office/office_path.json");
  VisibilityOptions one_thread;
  one_thread.threads = 1;
  const VisibilityCells expected = VisibilityIndex(plan, one_thread).cells_along_path(path);
  ASSERT_GT(expected.cells.size(), 100u);
  VisibilityOptions two_threads;
  two_threads.threads = 2;
  for (int round = 0; round < 40; ++round) {
    const VisibilityIndex index(plan, two_threads);
    EXPECT_EQ(index.cells_along_path(path), expected) << "round " << round;
  }
}

}  // namespace
}  // namespace plenopath
