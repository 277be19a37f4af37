// Telling tripod stills from video frames: a rendered trolley walk (8 cm steps) is video, tripod stills
// 2 m apart at random headings are stills.
#include "processing/stills/stills_detection.h"

#include <gtest/gtest.h>

#include <random>

#include "model/error.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

std::vector<cv::Mat> render(const std::vector<PathFrame>& poses) {
  static const SyntheticScene scene = build_synthetic_scene(make_office_sample_plan());
  RenderOptions options;
  options.width = 768;
  options.height = 384;
  options.depth = false;
  std::vector<cv::Mat> out;
  for (const PathFrame& f : poses) out.push_back(render_panorama(scene, f, options).rgb);
  return out;
}

TEST(StillsDetection, AWalkIsVideoAndTripodStillsAreStills) {
  AutoWalkOptions walk;
  walk.max_frames = 40;
  const CameraPath path = auto_walk(make_office_sample_plan(), walk);
  const std::vector<cv::Mat> video = render(path.frames);
  const StillsDetection v = detect_stills(static_cast<int>(video.size()),
                                          [&](int i) { return video[static_cast<std::size_t>(i)]; });
  EXPECT_FALSE(v.stills) << v.reason;
  EXPECT_GT(v.followed_fraction, 0.6) << v.reason;
  EXPECT_EQ(v.pairs, 6);

  std::mt19937 rng(6);
  std::uniform_real_distribution<double> heading(-M_PI, M_PI);
  std::vector<PathFrame> tripod;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {2.6, 9.4}, {4.6, 9.6}, {5.5, 11.4}, {3.4, 12.6}, {5.4, 13.0}}) {
    PathFrame f;
    f.x = x;
    f.y = y;
    f.heading = heading(rng);
    tripod.push_back(f);
  }
  const std::vector<cv::Mat> stills = render(tripod);
  const StillsDetection s = detect_stills(static_cast<int>(stills.size()),
                                          [&](int i) { return stills[static_cast<std::size_t>(i)]; });
  EXPECT_TRUE(s.stills) << s.reason;
  EXPECT_LT(s.followed_fraction, 0.2) << s.reason;
  EXPECT_EQ(s.pairs, 4);
  // Four stills are too few to judge.
  const StillsDetection few = detect_stills(4, [&](int i) { return stills[static_cast<std::size_t>(i)]; });
  EXPECT_FALSE(few.stills);
  EXPECT_EQ(few.pairs, 0);
}

TEST(StillsDetection, BadOptionsAreNamed) {
  StillsDetectionOptions o;
  o.min_followed_fraction = 1.5;
  try {
    o.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("min_followed_fraction"), std::string::npos);
  }
}

}  // namespace
}  // namespace plenopath
