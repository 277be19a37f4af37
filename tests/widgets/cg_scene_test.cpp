// Process > Render CG scene: the author's POV-Ray scene rendered along waypoints becomes the project's
// capture and its true poses the path, as one undo step; online, only the keyframes are rendered and the
// path is theirs, numbered as the capture's frames. The dialog's choices map to the render's options.
#include <gtest/gtest.h>

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QRadioButton>
#include <QSpinBox>
#include <QTest>
#include <QUndoStack>
#include <filesystem>
#include <fstream>

#include "app/studio/studio_tasks.h"
#include "tests/widgets/test_studio.h"
#include "widgets/cg_scene_dialog.h"
#include "widgets/project_document.h"
#include "widgets/task_runner.h"

namespace plenopath {
namespace {

namespace fs = std::filesystem;

struct SceneDir {
  fs::path path = fs::temp_directory_path() / ("plenopath_cg_scene_" + std::to_string(::getpid()));
  SceneDir() {
    fs::create_directories(path);
    std::ofstream(path / "room.pov")
        << "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\nlight_source { <2, 2.8, 1> color rgb 1 }\n"
           "box { <-5, 0, -3>, <5, 3, 3> inverse pigment { checker rgb <0.8, 0.7, 0.6> rgb <0.2, 0.3, 0.4> "
           "scale 0.5 } }\nsphere { <2, 1, 1.5>, 0.5 pigment { rgb 1 } }\n";
  }
  ~SceneDir() { fs::remove_all(path); }
};

widgets::CgSceneChoices room_choices(const SceneDir& dir, const std::string& out, bool online) {
  widgets::CgSceneChoices c;
  c.scene = (dir.path / "room.pov").string();
  c.out_dir = (dir.path / out).string();
  c.use_project_path = false;
  c.waypoints = "-4,0 4,0 4,2";
  c.step_m = 0.25;
  c.options.povray.width = 64;
  c.options.povray.quality = 2;
  c.options.online = online;
  c.options.online_parameters.ratio = 8;
  c.options.coarse_width = 64;
  return c;
}

TEST(CgScene, RenderedFramesBecomeTheCaptureAndTheirPosesThePath) {
  SceneDir dir;
  test::TestStudio s;
  ASSERT_TRUE(s.window.tasks().start("Render CG scene",
                                     studio::render_cg_scene_task(room_choices(dir, "all", false))));
  s.window.tasks().wait();
  ASSERT_TRUE(s.errors.isEmpty()) << s.errors.join("\n").toStdString();
  const Project& p = s.window.document().project();
  ASSERT_EQ(p.path.size(), 41u);  // 8 m and 2 m at 0.25 m, both ends
  EXPECT_EQ(p.capture.frame_names.size(), 41u);
  EXPECT_EQ(p.path.scale_source, "ground_truth");
  EXPECT_DOUBLE_EQ(p.capture.camera_height_m, 1.6);
  EXPECT_NEAR(p.path.frames[0].x, -4.0, 1e-9);
  EXPECT_NEAR(p.path.frames.back().y, 2.0, 1e-9);
  for (std::size_t k = 0; k < p.path.size(); ++k) {
    EXPECT_EQ(p.path.frames[k].index, static_cast<int>(k));
    EXPECT_EQ(p.path.frames[k].file, p.capture.frame_names[k]);
  }
  EXPECT_TRUE(fs::exists(dir.path / "all" / "depth" / "000040.png"));
  EXPECT_EQ(s.window.document().undo_stack()->count(), 1);
  s.window.document().undo_stack()->undo();
  EXPECT_TRUE(s.window.document().project().path.empty());
  EXPECT_TRUE(s.window.document().project().capture.empty());
}

TEST(CgScene, OnlineRendersOnlyTheKeyframes) {
  SceneDir dir;
  test::TestStudio s;
  ASSERT_TRUE(s.window.tasks().start("Render CG scene",
                                     studio::render_cg_scene_task(room_choices(dir, "online", true))));
  s.window.tasks().wait();
  ASSERT_TRUE(s.errors.isEmpty()) << s.errors.join("\n").toStdString();
  const Project& p = s.window.document().project();
  ASSERT_GE(p.path.size(), 2u);
  EXPECT_LE(p.path.size(), 41u / 4);
  EXPECT_EQ(p.capture.frame_names.size(), p.path.size());
  for (std::size_t k = 0; k < p.path.size(); ++k) EXPECT_EQ(p.path.frames[k].index, static_cast<int>(k));
  EXPECT_TRUE(fs::exists(dir.path / "online" / "online_sampling.json"));
  // The frames written are the sampler's keyframes, and stay keyframes: Export works at once.
  ASSERT_EQ(p.keyframes.indices.size(), p.path.size());
  for (std::size_t k = 0; k < p.path.size(); ++k) EXPECT_EQ(p.keyframes.indices[k], static_cast<int>(k));
  EXPECT_EQ(p.keyframes.parameters.method, SamplingMethod::kDepth);
}

// A scene without a DXF: the plan cut from the render at eye height (online, from the coarse pass of every
// frame) is the room's four walls, within a few centimetres; one undo takes plan, capture and path back.
TEST(CgScene, ThePlanCutFromTheRenderIsTheRoomsWalls) {
  SceneDir dir;
  test::TestStudio s;
  widgets::CgSceneChoices c = room_choices(dir, "section", true);
  c.options.section_plan = true;
  c.options.coarse_width = 256;
  ASSERT_TRUE(s.window.tasks().start("Render CG scene", studio::render_cg_scene_task(c)));
  s.window.tasks().wait();
  ASSERT_TRUE(s.errors.isEmpty()) << s.errors.join("\n").toStdString();
  const FloorPlan& plan = s.window.document().project().plan;
  ASSERT_FALSE(plan.occluder_segments().empty());
  // Each traced segment lies on one of the room's walls x = +-5, y = +-3 (POV z) or on the sphere's section
  // (centre (2, 1.5), radius 0.5 at 1 m; the camera cuts it at 1.6 m: none), within 6 cm.
  double length = 0, on_walls = 0;
  for (const PlanSegment& seg : plan.occluder_segments()) {
    for (const Eigen::Vector2d& p : {seg.a, seg.b, Eigen::Vector2d(0.5 * (seg.a + seg.b))}) {
      const double d = std::min({std::abs(std::abs(p.x()) - 5.0), std::abs(std::abs(p.y()) - 3.0)});
      length += seg.length() / 3;
      if (d < 0.06 && std::abs(p.x()) < 5.06 && std::abs(p.y()) < 3.06) on_walls += seg.length() / 3;
    }
  }
  std::printf("plan cut from the render: %zu segments, %.1f m, %.1f %% on the room's walls\n",
              plan.occluder_segments().size(), length, 100 * on_walls / length);
  EXPECT_GT(length, 20.0);  // the path sees all four walls: 32 m in all
  EXPECT_GE(on_walls / length, 0.97);
  s.window.document().undo_stack()->undo();
  EXPECT_TRUE(s.window.document().project().plan.empty());
  EXPECT_TRUE(s.window.document().project().capture.empty());
}

TEST(CgScene, AMissingPovrayIsAMessage) {
  SceneDir dir;
  test::TestStudio s;
  widgets::CgSceneChoices c = room_choices(dir, "none", false);
  c.options.povray.executable = "no-such-povray";
  ASSERT_TRUE(s.window.tasks().start("Render CG scene", studio::render_cg_scene_task(c)));
  s.window.tasks().wait();
  ASSERT_EQ(s.errors.size(), 1);
  EXPECT_TRUE(s.errors[0].contains("apt-get install povray")) << s.errors[0].toStdString();
  EXPECT_TRUE(s.window.document().project().capture.empty());
}

TEST(CgScene, DialogChoicesMapToTheRender) {
  widgets::CgSceneDialog dialog(nullptr, false, "/tmp/scene.pov");
  auto* project_path = dialog.findChildren<QRadioButton*>()[0];
  EXPECT_FALSE(project_path->isEnabled());  // no path in the project: waypoints only
  for (QCheckBox* box : dialog.findChildren<QCheckBox*>())
    if (box->text().startsWith("Online")) box->setChecked(true);
  const widgets::CgSceneChoices c = dialog.choices();
  EXPECT_FALSE(c.use_project_path);
  EXPECT_EQ(c.scene, "/tmp/scene.pov");
  EXPECT_EQ(c.out_dir, "/tmp/scene-capture");
  EXPECT_TRUE(c.options.online);
  EXPECT_EQ(c.options.povray.width, 2048);
  EXPECT_DOUBLE_EQ(c.options.online_parameters.ratio, 50.0);
  EXPECT_DOUBLE_EQ(c.options.online_loss_target, 0.0);
  // A loss target replaces the frames-per-keyframe budget.
  auto* loss_target = dialog.findChild<QDoubleSpinBox*>("cg_loss_target");
  ASSERT_NE(loss_target, nullptr);
  EXPECT_TRUE(loss_target->isEnabled());
  loss_target->setValue(0.08);
  EXPECT_DOUBLE_EQ(dialog.choices().options.online_loss_target, 0.08);
  int ratio_boxes_enabled = 0;
  for (QDoubleSpinBox* box : dialog.findChildren<QDoubleSpinBox*>())
    if (box->toolTip() == "Frames of the path per keyframe" && box->isEnabled()) ++ratio_boxes_enabled;
  EXPECT_EQ(ratio_boxes_enabled, 0);
  // The plan cut from the render needs depth.
  auto* section = dialog.findChild<QCheckBox*>("cg_section_plan");
  ASSERT_NE(section, nullptr);
  section->setChecked(true);
  EXPECT_TRUE(dialog.choices().options.section_plan);
  for (QCheckBox* box : dialog.findChildren<QCheckBox*>())
    if (box->text().startsWith("Depth")) box->setChecked(false);
  EXPECT_FALSE(section->isEnabled());
  EXPECT_FALSE(dialog.choices().options.section_plan);
}

// A Blender scene: its units are its own and it is z up, so those two POV-Ray choices are off; size, height
// and depth go to the Blender render too.
TEST(CgScene, DialogTakesABlenderScene) {
  widgets::CgSceneDialog dialog(nullptr, false, "/tmp/scene.pov");
  QDoubleSpinBox* units = nullptr;
  for (QDoubleSpinBox* box : dialog.findChildren<QDoubleSpinBox*>())
    if (box->toolTip().contains("metre")) units = box;
  QCheckBox* z_up = nullptr;
  for (QCheckBox* box : dialog.findChildren<QCheckBox*>())
    if (box->text().contains("z up")) z_up = box;
  ASSERT_TRUE(units && z_up);
  EXPECT_TRUE(units->isEnabled());
  EXPECT_TRUE(z_up->isEnabled());
  QLineEdit* scene = dialog.findChildren<QLineEdit*>()[0];
  ASSERT_EQ(scene->text(), "/tmp/scene.pov");
  scene->selectAll();
  QTest::keyClicks(scene, "/tmp/room.blend");
  EXPECT_FALSE(units->isEnabled());
  EXPECT_FALSE(z_up->isEnabled());
  QSpinBox* width = dialog.findChildren<QSpinBox*>()[0];
  width->setValue(1024);
  const widgets::CgSceneChoices c = dialog.choices();
  EXPECT_EQ(c.scene, "/tmp/room.blend");
  EXPECT_TRUE(is_blender_scene(c.scene));
  EXPECT_EQ(c.options.blender.width, 1024);
  EXPECT_DOUBLE_EQ(c.options.blender.camera_height_m, 1.6);
  EXPECT_TRUE(c.options.blender.depth);
  EXPECT_DOUBLE_EQ(c.options.blender.units_per_metre, 0.0);  // the scene's own
}

}  // namespace
}  // namespace plenopath
