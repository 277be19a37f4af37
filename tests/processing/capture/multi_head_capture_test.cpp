// Multi-head import: per-head folders rendered by the synthetic camera plus rig.json, opened as one capture
// and stitched on the fly; a frame one head lacks is skipped and listed.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "rig/multi_head_rig.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/capture/capture_test_util.h"

namespace plenopath {
namespace {

TEST(MultiHeadCapture, HeadFoldersAndRigFileImportAsStitchedFrames) {
  const FloorPlan plan = make_office_sample_plan();
  SceneOptions scene_options;
  scene_options.texture_size = 256;
  const SyntheticScene scene = build_synthetic_scene(plan, scene_options);
  AutoWalkOptions walk;
  walk.max_frames = 4;
  walk.step = 0.5;
  walk.scene = scene_options;
  const CameraPath path = auto_walk(plan, walk);
  ASSERT_EQ(path.size(), 4u);

  DefaultRigOptions rig_options;
  rig_options.ring_width = 96;
  rig_options.ring_height = 120;
  rig_options.cap_size = 96;
  const MultiHeadRig rig = make_default_rig(rig_options);
  test::TempFolder dir;
  write_rig_file(rig, dir / FrameSource::kRigFileName);
  RenderOptions render;
  render.depth = false;
  std::vector<std::vector<cv::Mat>> heads_per_frame;
  for (int f = 0; f < 4; ++f) {
    heads_per_frame.push_back(render_heads(scene, rig, path.frames[f], render));
    for (std::size_t k = 0; k < rig.heads.size(); ++k) {
      const std::filesystem::path folder = dir.path() / rig.heads[k].name;
      std::filesystem::create_directories(folder);
      if (f == 2 && k == 3) continue;  // head 3 lost frame 2
      char name[32];
      std::snprintf(name, sizeof name, "IMG_%04d.png", 100 + f);
      ASSERT_TRUE(cv::imwrite((folder / name).string(), heads_per_frame[f][k]));
    }
  }

  FrameSourceOptions options;
  options.stitch_width = 256;
  auto source = FrameSource::open(dir.path().string(), options);
  EXPECT_EQ(source->head_count(), static_cast<int>(rig.heads.size()));
  ASSERT_EQ(source->frame_count(), 3);
  EXPECT_EQ(source->width(), 256);
  EXPECT_EQ(source->height(), 128);
  EXPECT_EQ(source->frame_name(2), "IMG_0103.png");
  ASSERT_EQ(source->skipped().size(), 1u);
  EXPECT_EQ(source->skipped()[0].name, "IMG_0102.png");
  EXPECT_NE(source->skipped()[0].reason.find(rig.heads[3].name), std::string::npos)
      << source->skipped()[0].reason;

  // Each imported frame is the stitch of its own heads (lossless PNG: exactly), and resembles the direct
  // panorama render of its own pose more than any other pose's.
  StitchOptions stitch;
  stitch.width = 256;
  stitch.height = 128;
  const StitchMaps maps = make_stitch_maps(rig, stitch);
  RenderOptions pano;
  pano.width = 256;
  pano.height = 128;
  pano.depth = false;
  const std::vector<int> poses = {0, 1, 3};
  for (int i = 0; i < 3; ++i) {
    const cv::Mat frame = source->read(i);
    const cv::Mat expected = stitch_heads(maps, heads_per_frame[poses[i]]);
    EXPECT_EQ(cv::norm(frame, expected, cv::NORM_INF), 0.0) << "frame " << i;
    const double own = psnr(frame, render_panorama(scene, path.frames[poses[i]], pano).rgb);
    for (int other : poses) {
      if (other == poses[i]) continue;
      EXPECT_GT(own, psnr(frame, render_panorama(scene, path.frames[other], pano).rgb)) << "frame " << i;
    }
  }

  // The project remembers it as an image folder with head 0's names; it reopens as the same rig capture.
  const Capture capture = capture_from_frame_source(*source);
  auto reopened = FrameSource::open_capture(capture);
  EXPECT_EQ(reopened->head_count(), static_cast<int>(rig.heads.size()));
  ASSERT_EQ(reopened->frame_count(), 3);
  EXPECT_EQ(cv::norm(reopened->read(1), source->read(1), cv::NORM_INF), 0.0);

  // A head folder of the wrong size is an error naming the folder and the rig file.
  cv::imwrite((dir.path() / rig.heads[0].name / "IMG_0100.png").string(), cv::Mat(10, 10, CV_8UC3));
  for (const char* n : {"IMG_0101.png", "IMG_0102.png", "IMG_0103.png"})
    cv::imwrite((dir.path() / rig.heads[0].name / n).string(), cv::Mat(10, 10, CV_8UC3));
  try {
    FrameSource::open(dir.path().string(), options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(rig.heads[0].name), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rig calibration"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plenopath
