// Still panoramas end to end on the studio's own renderer: eight tripod positions 1-3 m apart in the
// office sample's open office at random headings, and one still in the lab next door that sees none of
// them. The open-office stills must come back within 5 cm and 1 deg of the truth after a similarity
// alignment (and at metric scale from the camera height); the lab still must be reported unconnected.
#include "processing/stills/stills.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/error.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/stills/similarity_2d.h"

namespace plenopath {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Scene {
  std::vector<PathFrame> truth;
  std::vector<cv::Mat> images;
};

const Scene& office_stills() {
  static const Scene scene = [] {
    Scene s;
    const std::vector<Eigen::Vector2d> positions = {{2.6, 9.4},  {4.6, 9.6},  {5.5, 11.2}, {3.0, 12.6},
                                                    {1.0, 1.0},  // the lab: its door shows only the corridor
                                                    {5.2, 12.9}, {2.5, 11.0}, {7.3, 12.6}, {4.0, 13.3}};
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> heading(-M_PI, M_PI);
    // The renderer's textures repeat every texture_size / texels_per_metre (4 m by default): seen from
    // metres apart, a floor repeated 4 m away matches as well as the real one. 16 m here, beyond the room.
    SceneOptions scene_options;
    scene_options.texture_size = 2048;
    scene_options.texels_per_metre = 128;
    const SyntheticScene world = build_synthetic_scene(make_office_sample_plan(), scene_options);
    RenderOptions render;
    render.width = 1536;
    render.height = 768;
    render.depth = false;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      PathFrame f;
      f.index = static_cast<int>(i);
      f.x = positions[i].x();
      f.y = positions[i].y();
      f.heading = heading(rng);
      s.truth.push_back(f);
      s.images.push_back(render_panorama(world, f, render).rgb);
    }
    return s;
  }();
  return scene;
}

TEST(Stills, OfficeTripodPositionsComeBackAndTheLabStillIsUnconnected) {
  const Scene& scene = office_stills();
  const int n = static_cast<int>(scene.images.size());
  StillsOptions options;
  options.features.work_width = 1536;
  options.camera_height_m = SceneOptions{}.camera_height;
  const StillsResult r = solve_stills(
      n, [&](int i) { return scene.images[static_cast<std::size_t>(i)]; }, options);

  ASSERT_EQ(r.unconnected, std::vector<int>{4});
  ASSERT_EQ(r.groups.size(), 2u);
  EXPECT_EQ(r.groups[0], (std::vector<int>{0, 1, 2, 3, 5, 6, 7, 8}));
  // Pieces in capture order: stills 0-3 (placed), 4 alone (unplaced), 5-8 (placed, same frame as 0-3).
  ASSERT_EQ(r.path.pieces.size(), 3u);
  EXPECT_TRUE(r.path.pieces[0].placed);
  EXPECT_FALSE(r.path.pieces[1].placed);
  EXPECT_TRUE(r.path.pieces[2].placed);
  EXPECT_EQ(r.path.pieces[1].first_index, 4);
  EXPECT_EQ(r.path.pieces[1].last_index, 4);
  EXPECT_NE(r.path.pieces[1].break_reason.find("connects to no other still"), std::string::npos);
  EXPECT_EQ(r.scale_source, "camera_height");
  EXPECT_GT(r.floor_points, 50);

  // Similarity alignment of the connected stills onto the truth.
  const std::vector<int>& group = r.groups[0];
  std::vector<Eigen::Vector2d> est, truth;
  for (int i : group) {
    est.push_back(r.path.frames[static_cast<std::size_t>(i)].position());
    truth.push_back(scene.truth[static_cast<std::size_t>(i)].position());
  }
  const Similarity2d T = fit_similarity_2d(est, truth);
  const double scale = T.scale;
  EXPECT_NEAR(scale, 1.0, 0.03) << "metric scale from the camera height";
  double worst_position = 0, worst_heading = 0;
  for (std::size_t k = 0; k < group.size(); ++k) {
    worst_position = std::max(worst_position, (T.apply(est[k]) - truth[k]).norm());
    const double h = r.path.frames[static_cast<std::size_t>(group[k])].heading + T.rotation;
    worst_heading = std::max(
        worst_heading, std::abs(wrap_angle(h - scene.truth[static_cast<std::size_t>(group[k])].heading)));
  }
  EXPECT_LT(worst_position, 0.05 * scale);
  EXPECT_LT(worst_heading, 1.0 * kDeg);
  RecordProperty("worst_position_m", std::to_string(worst_position));
  RecordProperty("worst_heading_deg", std::to_string(worst_heading / kDeg));
  std::cout << "stills: worst position " << worst_position << " m, worst heading " << worst_heading / kDeg
            << " deg, scale " << scale << ", " << r.refinement.points << " points, rms "
            << r.refinement.final_rms_deg << " deg, " << r.seconds << " s\n";
}

TEST(Stills, CancelledRunThrowsCancelled) {
  const Scene& scene = office_stills();
  FunctionProgress progress;
  progress.cancel();
  EXPECT_THROW(
      solve_stills(
          3, [&](int i) { return scene.images[static_cast<std::size_t>(i)]; }, StillsOptions{}, progress),
      Cancelled);
}

TEST(Stills, AStillThatIsNotAPanoramaIsNamed) {
  const cv::Mat square(64, 64, CV_8UC3, cv::Scalar::all(100));
  try {
    solve_stills(
        1, [&](int) { return square; }, StillsOptions{});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("still 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plenopath
