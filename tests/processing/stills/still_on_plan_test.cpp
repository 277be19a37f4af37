// One click places a still on the plan: stills rendered by the studio's renderer at known poses in the
// office sample (open office, lab, lobby, corridor), the click 0.3-0.5 m off the truth in a random
// direction; the pose found must be within 10 cm and 1 deg of the render's truth (issue 20's target for
// the assisted placement).
#include "processing/stills/still_on_plan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "model/error.h"
#include "processing/plan/dxf_import.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

double heading_error_deg(double a_deg, double b_rad) {
  double d = std::fmod(a_deg - b_rad * 180.0 / M_PI, 360.0);
  if (d > 180) d -= 360;
  if (d < -180) d += 360;
  return std::abs(d);
}

const SyntheticScene& office() {
  static const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan(), SceneOptions{});
  return scene;
}

cv::Mat render_still(const PathFrame& pose) {
  RenderOptions render;
  render.width = 1440;
  render.height = 720;
  render.depth = false;
  return render_panorama(office(), pose, render).rgb;
}

TEST(StillOnPlan, OneClickNearTheTripodGivesItsPose) {
  const FloorPlan plan = make_office_sample_plan();
  const std::vector<Eigen::Vector2d> spots = {{1.0, 1.0}, {2.6, 9.4}, {5.5, 11.2}, {12.5, 4.0}, {3.0, 3.2}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), offset(0.3, 0.5);
  for (std::size_t k = 0; k < spots.size(); ++k) {
    PathFrame truth;
    truth.x = spots[k].x();
    truth.y = spots[k].y();
    truth.heading = angle(rng);
    const double off_angle = angle(rng), off = offset(rng);
    const Eigen::Vector2d click = spots[k] + off * Eigen::Vector2d(std::cos(off_angle), std::sin(off_angle));
    StillOnPlanOptions options;
    options.camera_height_m = SceneOptions{}.camera_height;
    const StillPlacement placed = place_still_on_plan(render_still(truth), plan, click, options);
    const double position_error = (Eigen::Vector2d(placed.x, placed.y) - spots[k]).norm();
    const double heading_error = heading_error_deg(placed.heading_deg, truth.heading);
    std::printf("spot (%.1f, %.1f): %.3f m, %.2f deg, fit %.2f px, runner-up %.2f px at %.0f deg, %.2f s\n",
                spots[k].x(), spots[k].y(), position_error, heading_error, placed.score_px,
                placed.runner_up_score_px, placed.runner_up_heading_deg, placed.seconds);
    EXPECT_LT(position_error, 0.10) << placed.summary;
    EXPECT_LT(heading_error, 1.0) << placed.summary;
  }
}

// Two POV-Ray stills of the gallery hall (tests/data/stills-gallery/README.md: its chequered, glossy floor,
// columns, walls 8-13 m away), one click 0.4 m off each (the clicks of bench_povray_stills' seeded run).
// Matched with every edge, the columns drawn over the floor's tile edges fit best 0.8 and 1.0 m away (the
// premise, checked); matched by orientation, each lands within 10 cm and 1 deg of the render's pose.
TEST(StillOnPlan, ATiledFloorDoesNotPullTheWallsOverIt) {
  const std::string dir = std::string(PLENOPATH_TEST_DATA_DIR) + "/stills-gallery/";
  const FloorPlan plan = import_dxf(dir + "plan.dxf");
  struct Case {
    const char* file;
    Eigen::Vector2d truth;
    double heading_deg;
    double click_angle;  // radians
  };
  const std::vector<Case> cases = {{"still_13.jpg", {3.5, 8.0}, -155.064685, -1.136382242594137},
                                   {"still_16.jpg", {12.0, 13.5}, -96.229817, -1.8305898768053617}};
  for (const Case& c : cases) {
    const cv::Mat still = cv::imread(dir + c.file, cv::IMREAD_COLOR);
    ASSERT_FALSE(still.empty()) << c.file;
    const Eigen::Vector2d click =
        c.truth + 0.4 * Eigen::Vector2d(std::cos(c.click_angle), std::sin(c.click_angle));
    StillOnPlanOptions options;
    options.camera_height_m = 1.6;
    options.oriented_edges = false;
    const StillPlacement every_edge = place_still_on_plan(still, plan, click, options);
    options.oriented_edges = true;
    const StillPlacement placed = place_still_on_plan(still, plan, click, options);
    const double every_edge_error = (Eigen::Vector2d(every_edge.x, every_edge.y) - c.truth).norm();
    const double position_error = (Eigen::Vector2d(placed.x, placed.y) - c.truth).norm();
    const double heading_error = heading_error_deg(placed.heading_deg, c.heading_deg * M_PI / 180.0);
    std::printf("%s: every edge %.3f m; oriented %.3f m, %.2f deg, fit %.2f px\n", c.file, every_edge_error,
                position_error, heading_error, placed.score_px);
    EXPECT_GT(every_edge_error, 0.5) << c.file;
    EXPECT_LT(position_error, 0.10) << placed.summary;
    EXPECT_LT(heading_error, 1.0) << placed.summary;
  }
}

TEST(StillOnPlan, AHeadingHintKeepsToItsSide) {
  const FloorPlan plan = make_office_sample_plan();
  PathFrame truth;
  truth.x = 2.6;
  truth.y = 9.4;
  truth.heading = 40.0 * M_PI / 180.0;
  StillOnPlanOptions options;
  // A hint 20 deg off the truth: still found; a hint opposite: the best pose that way, far worse a fit.
  options.heading_hint_deg = 60.0;
  const cv::Mat still = render_still(truth);
  const StillPlacement near = place_still_on_plan(still, plan, {2.8, 9.2}, options);
  EXPECT_LT(heading_error_deg(near.heading_deg, truth.heading), 1.0) << near.summary;
  options.heading_hint_deg = 220.0;
  const StillPlacement far = place_still_on_plan(still, plan, {2.8, 9.2}, options);
  EXPECT_GT(heading_error_deg(far.heading_deg, truth.heading), 100.0) << far.summary;
  EXPECT_GT(far.score_px, 1.5 * near.score_px) << far.summary;
}

TEST(StillOnPlan, BadInputIsAClearError) {
  const FloorPlan plan = make_office_sample_plan();
  PathFrame truth;
  truth.x = 2.6;
  truth.y = 9.4;
  const cv::Mat still = render_still(truth);
  FloorPlan no_walls = plan;
  for (PlanSegment& segment : no_walls.segments) segment.occluder = false;
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message([&] {
              place_still_on_plan(still, no_walls, {2.6, 9.4});
            }).find("no sight-blocking"),
            std::string::npos);
  EXPECT_NE(message([&] {
              place_still_on_plan(cv::Mat(), plan, {2.6, 9.4});
            }).find("empty"),
            std::string::npos);
  StillOnPlanOptions tight;
  tight.search_radius_m = 0.0;
  tight.min_wall_distance_m = 50.0;  // nowhere is 50 m from a wall
  EXPECT_NE(message([&] {
              place_still_on_plan(still, plan, {2.6, 9.4}, tight);
            }).find("clear of the walls"),
            std::string::npos);
  StillOnPlanOptions bad;
  bad.work_width = 100;
  EXPECT_NE(message([&] {
              place_still_on_plan(still, plan, {2.6, 9.4}, bad);
            }).find("work_width"),
            std::string::npos);
}

}  // namespace
}  // namespace plenopath
