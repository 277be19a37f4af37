// End to end: panoramas rendered by the synthetic camera along a walk, written as an H.264 MP4 by OpenCV's
// VideoWriter with a depth folder beside it, imported through FrameSource: right count, each decoded frame
// matches its own render (and not its neighbours'), depth maps matched to video frames by number.
#include <gtest/gtest.h>

#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "processing/capture/frame_source.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/capture/capture_test_util.h"

namespace plenopath {
namespace {

double mean_abs_difference(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  const cv::Scalar m = cv::mean(diff);
  return (m[0] + m[1] + m[2]) / 3.0;
}

TEST(CaptureRenderedVideo, RenderedWalkImportsFromH264WithDepth) {
  const FloorPlan plan = make_office_sample_plan();
  SceneOptions scene_options;
  scene_options.texture_size = 256;
  const SyntheticScene scene = build_synthetic_scene(plan, scene_options);
  AutoWalkOptions walk;
  walk.max_frames = 12;
  walk.step = 0.2;
  walk.scene = scene_options;
  const CameraPath path = auto_walk(plan, walk);
  ASSERT_EQ(path.size(), 12u);

  test::TempFolder dir;
  std::filesystem::create_directories(dir.path() / "depth");
  RenderOptions render;
  render.width = 512;
  render.height = 256;
  std::vector<cv::Mat> rendered, depths;
  cv::VideoWriter writer(dir / "walk.mp4", cv::CAP_FFMPEG, cv::VideoWriter::fourcc('a', 'v', 'c', '1'), 30.0,
                         cv::Size(render.width, render.height));
  ASSERT_TRUE(writer.isOpened()) << "this OpenCV cannot write H.264 MP4";
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    const RenderedPanorama p = render_panorama(scene, path.frames[i], render);
    rendered.push_back(p.rgb.clone());
    depths.push_back(p.depth.clone());
    writer.write(p.rgb);
    cv::Mat mm;
    p.depth.convertTo(mm, CV_16U, 1000.0);  // millimetres, rounded
    char name[32];
    std::snprintf(name, sizeof name, "%06d.png", i);
    ASSERT_TRUE(cv::imwrite((dir.path() / "depth" / name).string(), mm));
  }
  writer.release();

  FrameSourceOptions options;
  options.depth_folder = (dir.path() / "depth").string();
  auto source = FrameSource::open(dir / "walk.mp4", options);
  ASSERT_EQ(source->frame_count(), 12);
  EXPECT_EQ(source->width(), 512);
  EXPECT_EQ(source->height(), 256);
  EXPECT_NEAR(source->frame_rate(), 30.0, 1e-6);
  EXPECT_EQ(source->depth_match_count(), 12);
  double worst_own = 0.0, closest_other = 1e9;
  for (int i = 0; i < 12; ++i) {
    const cv::Mat frame = source->read(i);
    const double own = mean_abs_difference(frame, rendered[i]);
    worst_own = std::max(worst_own, own);
    EXPECT_LT(own, 6.0) << "frame " << i << " differs from its render by " << own << " grey levels";
    for (int j = 0; j < 12; ++j) {
      if (j == i) continue;
      closest_other = std::min(closest_other, mean_abs_difference(frame, rendered[j]));
      EXPECT_LT(own, mean_abs_difference(frame, rendered[j])) << "frame " << i << " looks like " << j;
    }
    const cv::Mat depth = source->read_depth(i);
    cv::Mat error;
    cv::absdiff(depth, depths[i], error);
    double worst = 0;
    cv::minMaxLoc(error, nullptr, &worst);
    EXPECT_LT(worst, 0.0006) << "depth of frame " << i;  // rounding to whole millimetres
  }
  std::cout << "decoded vs own render: worst mean |diff| " << worst_own
            << " grey levels; vs another frame's render: " << closest_other << " at least\n";
}

}  // namespace
}  // namespace plenopath
