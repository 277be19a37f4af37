// A plan cut from depth at eye height, for scenes without a DXF: judged against the plan the depth was
// rendered from (the synthetic camera's walls), which the section never saw — its walls lie on the plan's,
// and the envelopes it gives along the path are the plan's (CGAL on both).
#include "processing/sampling/depth_section.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "model/error.h"
#include "processing/sampling/polygon_iou.h"
#include "processing/visibility/visibility.h"
#include "rig/synthetic_camera.h"
#include "sampling_test_util.h"

namespace plenopath {
namespace {

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

void expect_section_matches(const FloorPlan& truth, const CameraPath& path, int width, int stride) {
  const SyntheticScene scene = build_synthetic_scene(truth);
  RenderOptions render;
  render.width = width;
  render.height = width / 2;
  CameraPath walked;
  for (std::size_t i = 0; i < path.size(); i += static_cast<std::size_t>(stride))
    walked.frames.push_back(path.frames[i]);
  const DepthSection section = plan_from_depth_section(
      walked, [&](int index) { return render_panorama(scene, *walked.find_frame(index), render).depth; });
  ASSERT_FALSE(section.plan.segments.empty());
  ASSERT_EQ(section.plan.layers.size(), 2u);  // the walls, and the limit of what the path saw
  EXPECT_TRUE(section.plan.layers[0].occluder);
  EXPECT_EQ(section.plan.layers[1].name, "SECTION-UNSEEN");
  double unseen = 0;
  EXPECT_EQ(section.frames_used, static_cast<int>(walked.size()));
  // Every traced wall on a wall of the plan: its length within 6 cm of one, sampled every centimetre.
  const std::vector<PlanSegment> walls = truth.occluder_segments();
  double length = 0, near = 0, worst = 0;
  for (const PlanSegment& s : section.plan.segments) {
    if (s.layer != "SECTION") {
      unseen += s.length();
      continue;
    }
    const int steps = std::max(1, static_cast<int>(s.length() / 0.01));
    for (int k = 0; k <= steps; ++k) {
      const Eigen::Vector2d p = s.a + (s.b - s.a) * (double(k) / steps);
      double d = 1e9;
      for (const PlanSegment& w : walls) d = std::min(d, distance_to_segment(p, w.a, w.b));
      length += s.length() / (steps + 1);
      near += d < 0.06 ? s.length() / (steps + 1) : 0;
      worst = std::max(worst, d);
    }
  }
  // What the section is for: the envelope along the path, against the plan's (exact CGAL on both).
  const VisibilityIndex plan_index(truth), section_index(section.plan);
  double iou_sum = 0, iou_min = 1;
  int compared = 0;
  for (std::size_t i = 0; i < path.size(); i += 7) {
    const Envelope a = plan_index.envelope(path.frames[i].position());
    const Envelope b = section_index.envelope(path.frames[i].position());
    ASSERT_EQ(a.status, EnvelopeStatus::ok);
    if (b.status != EnvelopeStatus::ok)
      std::printf("at (%.2f, %.2f) the section says %s\n", path.frames[i].x, path.frames[i].y,
                  to_string(b.status));
    const double iou = b.status == EnvelopeStatus::ok ? polygon_iou(a.polygon, b.polygon) : 0.0;
    iou_sum += iou;
    iou_min = std::min(iou_min, iou);
    ++compared;
  }
  std::printf(
      "section from %zu frames %d wide: %zu segments, walls %.1f m, %.1f %% within 6 cm of the plan's walls "
      "(worst %.3f m), unseen limit %.1f m; envelope IoU along the path mean %.3f, min %.3f over %d points\n",
      walked.size(), width, section.plan.segments.size(), length, 100 * near / length, worst, unseen,
      iou_sum / compared, iou_min, compared);
  EXPECT_GE(near / length, 0.95);
  EXPECT_GE(iou_sum / compared, 0.93);
  EXPECT_GE(iou_min, 0.75);
}

TEST(DepthSection, ThreeRoomsCutAtEyeHeightAreThePlansRooms) {
  expect_section_matches(sampling_test::three_rooms(), sampling_test::three_rooms_path(), 512, 10);
}

// Wider than max_columns (1024): read every second column, the same rooms.
TEST(DepthSection, WidePanoramasAreReadEveryKthColumn) {
  expect_section_matches(sampling_test::three_rooms(), sampling_test::three_rooms_path(), 2048, 10);
}

TEST(DepthSection, TheOfficeSampleCutAtEyeHeight) {
  const FloorPlan plan = make_office_sample_plan();
  AutoWalkOptions walk;
  walk.max_frames = 300;
  expect_section_matches(plan, auto_walk(plan, walk), 1024, 6);
}

TEST(DepthSection, NoDepthIsAClearError) {
  const CameraPath path = sampling_test::straight_path(3, 0.5);
  EXPECT_THROW(plan_from_depth_section(path, [](int) { return cv::Mat(); }), Error);
  DepthSectionOptions bad;
  bad.cell_m = 0;
  EXPECT_THROW(bad.check(), Error);
  // Sky everywhere (no hit): nothing to trace.
  EXPECT_THROW(plan_from_depth_section(path, [](int) { return cv::Mat(64, 128, CV_32F, cv::Scalar(0)); }),
               Error);
}

}  // namespace
}  // namespace plenopath
