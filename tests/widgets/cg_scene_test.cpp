// Process > Render CG scene: the author's POV-Ray scene rendered along waypoints becomes the project's
// capture and its true poses the path, as one undo step; online, only the keyframes are rendered and the
// path is theirs, numbered as the capture's frames. The dialog's choices map to the render's options.
// The walk is drawn on the map with real clicks (Backspace, Enter, a double-click, Esc), or is the
// studio's automatic walk thinned to its corners, or is a path file.
#include <gtest/gtest.h>

#include <QAction>
#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QRadioButton>
#include <QSpinBox>
#include <QTest>
#include <QUndoStack>
#include <QWheelEvent>
#include <filesystem>
#include <fstream>

#include "app/studio/studio_tasks.h"
#include "model/path_io.h"
#include "processing/visibility/visibility.h"
#include "rig/synthetic_camera.h"
#include "tests/widgets/test_studio.h"
#include "widgets/cg_scene_dialog.h"
#include "widgets/map_view.h"
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

// The studio on the office sample plan with Process > Render CG scene open.
struct StudioWithDialog {
  test::TestStudio s;
  widgets::CgSceneDialog* dialog = nullptr;
  widgets::MapView* map = nullptr;
  explicit StudioWithDialog(bool plan = true) {
    Project start;
    if (plan) start.plan = make_office_sample_plan();
    s.window.document().reset(start, QString());
    map = s.window.map_view();
    QAction* render = s.window.findChild<QAction*>("render_cg_scene");
    EXPECT_NE(render, nullptr);
    render->trigger();
    dialog = s.window.findChild<widgets::CgSceneDialog*>();
    EXPECT_NE(dialog, nullptr);
    EXPECT_TRUE(QTest::qWaitForWindowExposed(dialog));
  }
  QLineEdit* waypoints() const { return dialog->findChild<QLineEdit*>("cg_waypoints"); }
  QPushButton* button(const char* name) const { return dialog->findChild<QPushButton*>(name); }
  void click_on_plan(const Eigen::Vector2d& p) const {
    const QPoint pixel = map->widget_pixel_of(p);
    ASSERT_TRUE(map->rect().contains(pixel)) << p.transpose();
    QTest::mouseClick(map, Qt::LeftButton, Qt::NoModifier, pixel);
  }
  // Metres per pixel of the map (from two pixels 100 apart).
  double metres_per_pixel() const {
    const QPoint c = map->rect().center();
    return (map->plan_point_at(c + QPoint(100, 0)) - map->plan_point_at(c)).norm() / 100.0;
  }
};

// Distance from p to the polyline through the path's frames (brute force).
double distance_to_path(const Eigen::Vector2d& p, const CameraPath& path) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const Eigen::Vector2d a = path.frames[k].position(), ab = path.frames[k + 1].position() - a;
    const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

TEST(CgScene, WaypointsClickedOnThePlanFillTheDialog) {
  StudioWithDialog d;
  ASSERT_NE(d.waypoints(), nullptr);
  ASSERT_TRUE(d.button("cg_draw_on_plan")->isEnabled());
  QTest::mouseClick(d.button("cg_draw_on_plan"), Qt::LeftButton);
  EXPECT_FALSE(d.dialog->isVisible());
  ASSERT_TRUE(d.map->is_drawing_waypoints());
  // Zoom in with the wheel (it still zooms while drawing) until a pixel is well under a centimetre.
  d.map->render_now();
  const double before = d.metres_per_pixel();
  for (int k = 0; k < 20 && d.metres_per_pixel() > 0.006; ++k) {
    const QPoint centre = d.map->rect().center();
    QWheelEvent wheel(QPointF(centre), QPointF(d.map->mapToGlobal(centre)), QPoint(), QPoint(0, 120),
                      Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(d.map, &wheel);
    d.map->render_now();
  }
  ASSERT_LT(d.metres_per_pixel(), 0.006) << "the wheel did not zoom: " << before;
  // Waypoints about the middle of the view (the plan's middle: the corridor, y 6.5 .. 8.5), at fractions
  // of the half view.
  const QRect r = d.map->rect();
  const Eigen::Vector2d c = d.map->plan_point_at(r.center());
  const Eigen::Vector2d half =
      0.5 * (d.map->plan_point_at(r.topRight()) - d.map->plan_point_at(r.bottomLeft())).cwiseAbs();
  const auto at = [&](double fx, double fy) {
    return Eigen::Vector2d(c + half.cwiseProduct(Eigen::Vector2d(fx, fy)));
  };
  const std::vector<Eigen::Vector2d> clicked = {at(-0.8, 0.1), at(-0.25, -0.3), at(0.2, 0.45), at(0.6, -0.1)};
  d.click_on_plan(clicked[0]);
  d.click_on_plan(clicked[1]);
  d.click_on_plan(clicked[2]);
  EXPECT_EQ(d.map->drawn_waypoints().size(), 3u);
  QTest::keyClick(d.map, Qt::Key_Backspace);  // the third goes
  EXPECT_EQ(d.map->drawn_waypoints().size(), 2u);
  d.click_on_plan(clicked[3]);
  // The cursor a little beyond the last waypoint: the rubber band follows it.
  const QPoint cursor = d.map->widget_pixel_of(at(0.9, 0.5));
  QMouseEvent move(QEvent::MouseMove, cursor, d.map->mapToGlobal(cursor), Qt::NoButton, Qt::NoButton,
                   Qt::NoModifier);
  QApplication::sendEvent(d.map, &move);
  QTest::qWait(50);
  d.map->render_now();
  // The legs are drawn in green on the map: look at the middle of each.
  const QImage shot = d.s.window.grab().toImage();
  if (qEnvironmentVariableIsSet("PLENOPATH_TEST_SAVE")) shot.save("/tmp/cg_waypoints_drawing.png");
  const auto green = [](QRgb p) { return qGreen(p) > 120 && qRed(p) < 60 && qBlue(p) < 140; };
  for (const auto& [a, b] : {std::pair{clicked[0], clicked[1]}, std::pair{clicked[1], clicked[3]}}) {
    const QPoint middle = d.map->mapTo(&d.s.window, d.map->widget_pixel_of(0.5 * (a + b)));
    EXPECT_GT(test::count_near(shot, middle, 4, green), 4)
        << "no green leg at " << (0.5 * (a + b)).transpose();
  }
  QTest::keyClick(d.map, Qt::Key_Return);

  EXPECT_FALSE(d.map->is_drawing_waypoints());
  EXPECT_TRUE(d.dialog->isVisible());
  if (qEnvironmentVariableIsSet("PLENOPATH_TEST_SAVE")) d.dialog->grab().save("/tmp/cg_scene_dialog.png");
  const widgets::CgSceneChoices c1 = d.dialog->choices();
  EXPECT_FALSE(c1.use_project_path);
  EXPECT_TRUE(c1.path_file.empty());
  const std::vector<Eigen::Vector2d> typed = parse_waypoints(c1.waypoints);
  const std::vector<Eigen::Vector2d> expected = {clicked[0], clicked[1], clicked[3]};
  ASSERT_EQ(typed.size(), expected.size()) << c1.waypoints;
  for (std::size_t k = 0; k < expected.size(); ++k)
    EXPECT_LT((typed[k] - expected[k]).norm(), 0.02) << k << ": " << c1.waypoints;
  // walk_waypoints reads it: a walk from the first point clicked, every frame on the clicked polyline, as
  // long as it (to within a step: the last frame is the last whole step).
  const CameraPath walk = walk_waypoints(c1.waypoints, c1.step_m);
  CameraPath clicked_line;
  for (const Eigen::Vector2d& p : expected) {
    clicked_line.frames.emplace_back();
    clicked_line.frames.back().x = p.x();
    clicked_line.frames.back().y = p.y();
  }
  EXPECT_LT((walk.frames.front().position() - clicked[0]).norm(), 0.02);
  for (const PathFrame& f : walk.frames) EXPECT_LT(distance_to_path(f.position(), clicked_line), 0.02);
  EXPECT_NEAR(walk.length(), clicked_line.length(), c1.step_m + 0.04);
  EXPECT_TRUE(d.dialog->findChild<QLabel*>("cg_waypoints_note")->text().startsWith("3 waypoint"));

  // Drawn again, finished by a double-click (its click adds the last waypoint; its release adds none).
  QTest::mouseClick(d.button("cg_draw_on_plan"), Qt::LeftButton);
  ASSERT_TRUE(d.map->is_drawing_waypoints());
  d.click_on_plan(clicked[0]);
  d.click_on_plan(clicked[2]);
  const QPoint last = d.map->widget_pixel_of(clicked[3]);
  QTest::mouseClick(d.map, Qt::LeftButton, Qt::NoModifier, last);
  QTest::mouseDClick(d.map, Qt::LeftButton, Qt::NoModifier, last);
  QTest::mouseRelease(d.map, Qt::LeftButton, Qt::NoModifier, last);
  EXPECT_FALSE(d.map->is_drawing_waypoints());
  EXPECT_TRUE(d.dialog->isVisible());
  EXPECT_EQ(parse_waypoints(d.dialog->choices().waypoints).size(), 3u) << d.dialog->choices().waypoints;
  d.dialog->reject();
}

TEST(CgScene, EscOnTheMapKeepsTheWaypointsTyped) {
  StudioWithDialog d;
  d.waypoints()->setText("1,1 2,2");
  QTest::mouseClick(d.button("cg_draw_on_plan"), Qt::LeftButton);
  ASSERT_TRUE(d.map->is_drawing_waypoints());
  d.map->render_now();
  d.click_on_plan({12.0, 7.5});
  d.click_on_plan({14.0, 7.5});
  QTest::keyClick(d.map, Qt::Key_Escape);
  EXPECT_FALSE(d.map->is_drawing_waypoints());
  EXPECT_TRUE(d.map->drawn_waypoints().empty());
  EXPECT_TRUE(d.dialog->isVisible());
  EXPECT_EQ(d.dialog->choices().waypoints, "1,1 2,2");
  // Enter with one waypoint is not the end: two at least.
  QTest::mouseClick(d.button("cg_draw_on_plan"), Qt::LeftButton);
  d.click_on_plan({12.0, 7.5});
  QTest::keyClick(d.map, Qt::Key_Enter);
  EXPECT_TRUE(d.map->is_drawing_waypoints());
  EXPECT_FALSE(d.dialog->isVisible());
  QTest::keyClick(d.map, Qt::Key_Escape);
  EXPECT_EQ(d.dialog->choices().waypoints, "1,1 2,2");
  d.dialog->reject();
}

// Whether b lies inside the polygon (even-odd rule).
bool inside(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& b) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d &p = polygon[i], &q = polygon[j];
    if ((p.y() > b.y()) != (q.y() > b.y()) &&
        b.x() < (q.x() - p.x()) * (b.y() - p.y()) / (q.y() - p.y()) + p.x())
      in = !in;
  }
  return in;
}

TEST(CgScene, ALegThroughAWallIsWarnedAbout) {
  StudioWithDialog d;
  // From the corridor into a room straight through its wall: b is not in a's visibility polygon.
  const Eigen::Vector2d a(7.0, 7.5), b(7.5, 3.0), c(10.0, 7.5);
  const VisibilityIndex index(make_office_sample_plan());
  const Envelope seen = index.envelope(a);
  ASSERT_EQ(seen.status, EnvelopeStatus::ok);
  ASSERT_FALSE(inside(seen.polygon, b)) << "the oracle: a wall stands between a and b";
  ASSERT_TRUE(inside(seen.polygon, c));
  QTest::mouseClick(d.button("cg_draw_on_plan"), Qt::LeftButton);
  d.map->render_now();
  d.click_on_plan(a);
  d.click_on_plan(c);
  EXPECT_EQ(d.map->waypoint_legs_crossing_walls(), 0);
  QTest::keyClick(d.map, Qt::Key_Backspace);
  d.click_on_plan(b);
  EXPECT_EQ(d.map->waypoint_legs_crossing_walls(), 1);
  QTest::keyClick(d.map, Qt::Key_Enter);
  const QString note = d.dialog->findChild<QLabel*>("cg_waypoints_note")->text();
  EXPECT_TRUE(note.contains("cross a wall")) << note.toStdString();
  d.dialog->reject();
}

TEST(CgScene, AutoWalkWaypointsStayInTheFreeSpaceOfThePlan) {
  StudioWithDialog d;
  ASSERT_TRUE(d.button("cg_auto_walk")->isEnabled());
  QTest::mouseClick(d.button("cg_auto_walk"), Qt::LeftButton);
  const widgets::CgSceneChoices c = d.dialog->choices();
  EXPECT_FALSE(c.use_project_path);
  const std::vector<Eigen::Vector2d> points = parse_waypoints(c.waypoints);
  std::printf("auto walk: %zu waypoints, %zu characters\n", points.size(), c.waypoints.size());
  ASSERT_GE(points.size(), 10u);
  const FloorPlan plan = make_office_sample_plan();
  const CameraPath truth = auto_walk(plan);
  EXPECT_LT(points.size(), truth.size() / 4) << "thinned to the corners";
  const CameraPath walk = walk_waypoints(c.waypoints, 0.05);
  const VisibilityIndex index(plan);
  int outside = 0;
  double worst = 0.0;
  for (const PathFrame& f : walk.frames) {
    outside += index.classify(f.position()) != EnvelopeStatus::ok;
    worst = std::max(worst, distance_to_path(f.position(), truth));
  }
  EXPECT_EQ(outside, 0) << "of " << walk.size() << " frames";
  EXPECT_LT(worst, 0.05);
  EXPECT_GT(walk.length(), 0.95 * truth.length());
  d.dialog->reject();

  // Without a plan there is no automatic walk; drawing is still possible.
  StudioWithDialog empty(false);
  EXPECT_FALSE(empty.button("cg_auto_walk")->isEnabled());
  EXPECT_TRUE(empty.button("cg_draw_on_plan")->isEnabled());
  empty.dialog->reject();
}

TEST(CgScene, APathFileChoiceRendersAlongTheFilesPoses) {
  SceneDir dir;
  CameraPath file_path;
  for (int k = 0; k < 4; ++k) {
    PathFrame f;
    f.index = 10 + 3 * k;  // the file's own numbering; the capture numbers the frames 0..3
    f.x = -3.0 + 1.5 * k;
    f.y = 0.4 * k - 0.5;
    f.heading = 0.3 * k - 0.2;
    file_path.frames.push_back(f);
  }
  const std::string file = (dir.path / "walk.json").string();
  write_path_file(file_path, file);

  StudioWithDialog d(false);
  auto* choice = d.dialog->findChild<QRadioButton*>("cg_path_file_choice");
  ASSERT_NE(choice, nullptr);
  auto* file_edit = d.dialog->findChild<QLineEdit*>("cg_path_file");
  EXPECT_FALSE(file_edit->isEnabled());
  QTest::mouseClick(choice, Qt::LeftButton);
  ASSERT_TRUE(choice->isChecked());
  EXPECT_TRUE(file_edit->isEnabled());
  file_edit->setText(QString::fromStdString(file));
  widgets::CgSceneChoices c = d.dialog->choices();
  EXPECT_FALSE(c.use_project_path);
  EXPECT_EQ(c.path_file, file);
  d.dialog->reject();

  widgets::CgSceneChoices room = room_choices(dir, "from_file", false);
  room.path_file = c.path_file;
  room.waypoints.clear();
  ASSERT_TRUE(d.s.window.tasks().start("Render CG scene", studio::render_cg_scene_task(room)));
  d.s.window.tasks().wait();
  ASSERT_TRUE(d.s.errors.isEmpty()) << d.s.errors.join("\n").toStdString();
  const CameraPath& rendered = d.s.window.document().project().path;
  ASSERT_EQ(rendered.size(), file_path.size());
  for (std::size_t k = 0; k < rendered.size(); ++k) {
    EXPECT_EQ(rendered.frames[k].index, static_cast<int>(k));
    EXPECT_NEAR(rendered.frames[k].x, file_path.frames[k].x, 1e-6);
    EXPECT_NEAR(rendered.frames[k].y, file_path.frames[k].y, 1e-6);
    EXPECT_NEAR(rendered.frames[k].heading, file_path.frames[k].heading, 1e-6);
  }
  EXPECT_EQ(d.s.window.document().project().capture.frame_names.size(), file_path.size());
}

}  // namespace
}  // namespace plenopath
