// Depth sampling: cells from significant volume changes, counts by the rule, and depth rendered by the
// synthetic camera.
#include "processing/sampling/depth_sampler.h"

#include <gtest/gtest.h>

#include <tuple>

#include "model/error.h"
#include "processing/sampling/polygon_iou.h"
#include "processing/visibility/visibility.h"
#include "rig/synthetic_camera.h"
#include "sampling_test_util.h"

namespace plenopath {
namespace {

DepthVolume volume(double v) {
  DepthVolume d;
  d.star_volume = v;
  d.mean_range = std::cbrt(v);
  d.covered_solid_angle = 4 * M_PI;
  d.valid_pixels = 1;
  return d;
}

TEST(DepthSampler, CellsStartAtSignificantChanges) {
  // 10 m, 101 frames: V = 8 m^3 up to x = 3.95, 64 m^3 after (a jump of ln 8 > 0.25).
  const CameraPath path = sampling_test::straight_path(101, 0.1);
  std::vector<DepthVolume> volumes;
  for (const PathFrame& f : path.frames) volumes.push_back(volume(f.x < 4.0 ? 8.0 : 64.0));
  const std::vector<SamplingCell> cells = sampling_cells_from_depth(path, volumes);
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_NEAR(cells[0].s_begin, 0.0, 1e-12);
  EXPECT_NEAR(cells[0].s_end, 3.95, 1e-9);  // halfway between frames 39 and 40
  EXPECT_NEAR(cells[1].s_end, 10.0, 1e-9);
  EXPECT_NEAR(cells[0].size, 8.0, 1e-12);
  EXPECT_NEAR(cells[1].size, 64.0, 1e-12);

  // e = 3: masses 3.95^3 / 8 = 7.70 and 6.05^3 / 64 = 3.46; count 12 -> steps k/11, boundary at
  // 7.70 / 11.16 = 0.690: k = 0..7 in the first cell (8), k = 8..11 in the second (4).
  SamplingParameters p;
  p.method = SamplingMethod::kDepth;
  p.exponent = 3.0;
  p.transition_boost = 0.0;
  p.count = 12;
  const Keyframes k = sample_by_depth(path, volumes, p, {});
  ASSERT_EQ(k.indices.size(), 12u);
  int first = 0;
  for (int i : k.indices) first += path.find_frame(i)->x < 3.95;
  EXPECT_EQ(first, 8);
  EXPECT_EQ(k.parameters.method, SamplingMethod::kDepth);
  EXPECT_THROW(sample_by_depth(path, std::vector<DepthVolume>(5), p, {}), Error);
}

TEST(DepthSampler, RenderedDepthFindsTheDoor) {
  // A 3 m x 3 m room opening through a 1 m door (x = 3, y in [1, 2]) onto a 12 m x 11 m hall; the path
  // walks from the room into the hall along y = 1.5. Rendered at 64 x 32 by the synthetic camera.
  FloorPlan plan;
  PlanLayer layer;
  layer.name = "WALLS";
  layer.occluder = true;
  plan.layers.push_back(layer);
  using sampling_test::add_wall;
  add_wall(&plan, {0, 0}, {3, 0});
  add_wall(&plan, {3, 0}, {3, 1});
  add_wall(&plan, {3, 2}, {3, 3});
  add_wall(&plan, {3, 3}, {0, 3});
  add_wall(&plan, {0, 3}, {0, 0});
  add_wall(&plan, {3, 0}, {3, -4});
  add_wall(&plan, {3, -4}, {15, -4});
  add_wall(&plan, {15, -4}, {15, 7});
  add_wall(&plan, {15, 7}, {3, 7});
  add_wall(&plan, {3, 7}, {3, 3});
  const SyntheticScene scene = build_synthetic_scene(plan);
  const CameraPath path = sampling_test::straight_path(39, 0.25, 0.5, 1.5);  // x = 0.5 .. 10
  RenderOptions render;
  render.width = 64;
  render.height = 32;
  render.threads = 1;
  const std::vector<DepthVolume> volumes = depth_volumes_along_path(
      path, [&](int index) { return render_panorama(scene, path.frames[index], render).depth; });
  ASSERT_EQ(volumes.size(), path.size());
  // The hall (12 x 11 x 2.8 = 370 m^3) is bigger than what the room sees (its 25 m^3 and a wedge through the
  // door, which V's d^3 weighting makes count: about 130 m^3).
  EXPECT_NEAR(volumes.back().star_volume, 370.0, 40.0);
  EXPECT_GT(volumes.back().star_volume, 2.0 * volumes.front().star_volume);
  const std::vector<SamplingCell> cells = sampling_cells_from_depth(path, volumes);
  ASSERT_GE(cells.size(), 2u);
  double nearest = 1e9;  // cell boundary nearest the door (x = 3, s = 2.5)
  for (std::size_t c = 1; c < cells.size(); ++c)
    nearest = std::min(nearest, std::abs(cells[c].s_begin - 2.5));
  EXPECT_LT(nearest, 1.0);
  SamplingParameters p;
  p.method = SamplingMethod::kDepth;
  p.count = 10;
  EXPECT_EQ(sample_by_depth(path, volumes, p, {}).indices.size(), 10u);
}

// The eye-level envelope read from a rendered depth map matches the plan's envelope (CGAL), whatever the
// heading: the renderer and the visibility index are independent.
TEST(DepthSampler, EnvelopeFromDepthMatchesThePlan) {
  const FloorPlan plan = sampling_test::three_rooms();
  const SyntheticScene scene = build_synthetic_scene(plan);
  const VisibilityIndex index(plan);
  RenderOptions render;
  render.width = 512;
  render.height = 256;
  render.threads = 1;
  for (const auto& [x, y, heading] :
       {std::tuple{3.0, 2.0, 0.0}, std::tuple{8.0, 1.0, 2.0}, std::tuple{13.0, 2.5, -1.2}}) {
    const PathFrame pose{0, "", x, y, heading, 1.0, kFrameOk, ""};
    const Envelope from_depth = envelope_from_depth(render_panorama(scene, pose, render).depth, pose);
    const Envelope from_plan = index.envelope(pose.position());
    ASSERT_EQ(from_depth.status, EnvelopeStatus::ok);
    EXPECT_GT(polygon_iou(from_depth.polygon, from_plan.polygon), 0.97)
        << x << ", " << y << " heading " << heading;
    EXPECT_NEAR(from_depth.area, from_plan.area, 0.04 * from_plan.area);
  }
  EXPECT_THROW(envelope_from_depth(cv::Mat(4, 8, CV_16U), PathFrame{}), Error);
}

}  // namespace
}  // namespace plenopath
