// Every long task the studio runs, cancelled from the status bar's Cancel button: each is started as the
// author starts it (menu action or import), held at its first progress report until Cancel has been
// clicked, and must end as "<task> cancelled" in the status bar - never an error - with the document as it
// was (no undo step, nothing written).
#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QDialog>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QStatusBar>
#include <QTest>
#include <QTimer>
#include <QToolButton>
#include <QUndoStack>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <thread>

#include "app/studio/main_window.h"
#include "app/studio/studio_tasks.h"
#include "processing/export/tour_export.h"
#include "tests/processing/registration/synthetic_walls.h"
#include "tests/widgets/test_project.h"
#include "tests/widgets/test_studio.h"
#include "tests/widgets/wait_until.h"
#include "widgets/project_document.h"
#include "widgets/task_runner.h"

namespace plenopath {
namespace {

using test::wait_until;

QAction* action_named(studio::MainWindow& window, const QString& text) {
  for (QAction* a : window.findChildren<QAction*>())
    if (a->text().remove('&') == text) return a;
  return nullptr;
}

QToolButton* cancel_button(studio::MainWindow& window) {
  for (QToolButton* b : window.statusBar()->findChildren<QToolButton*>())
    if (b->text() == "Cancel") return b;
  return nullptr;
}

// Starts a task with `start`, holds the worker inside its first report, clicks Cancel, lets it go on, and
// checks the outcome.
void cancel_from_the_status_bar(test::TestStudio& s, const QString& title,
                                const std::function<void()>& start) {
  widgets::ProjectDocument& doc = s.window.document();
  const Project before = doc.project();
  const int undo_steps = doc.undo_stack()->count();
  std::atomic<int> reports{0};
  std::atomic<bool> release{false};
  s.window.tasks().set_report_hook([&](double, const std::string&) {
    if (reports.fetch_add(1) == 0)
      while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  start();
  ASSERT_TRUE(s.window.tasks().is_running()) << title.toStdString() << " did not start";
  ASSERT_TRUE(wait_until([&] { return reports.load() > 0 || !s.window.tasks().is_running(); }, 20000));
  ASSERT_GT(reports.load(), 0) << title.toStdString() << " ended without reporting";

  QToolButton* cancel = cancel_button(s.window);
  ASSERT_NE(cancel, nullptr);
  ASSERT_TRUE(cancel->isVisible());
  QTest::mouseClick(cancel, Qt::LeftButton);
  release = true;
  ASSERT_TRUE(wait_until([&] { return !s.window.tasks().is_running(); }, 20000));
  s.window.tasks().set_report_hook({});

  EXPECT_TRUE(s.errors.isEmpty()) << s.errors.join("\n").toStdString();
  const QString message = s.window.statusBar()->currentMessage();
  EXPECT_TRUE(message.startsWith(title + " cancelled")) << message.toStdString();
  EXPECT_FALSE(message.contains("failed")) << message.toStdString();
  EXPECT_EQ(doc.project(), before) << title.toStdString();
  EXPECT_EQ(doc.undo_stack()->count(), undo_steps) << title.toStdString();
  EXPECT_FALSE(cancel->isVisible());
}

TEST(TaskCancel, ImportCapture) {
  const auto& t = test::test_project("cancel-import");
  test::TestStudio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  cancel_from_the_status_bar(s, "Import capture", [&] {
    // The import dialog is modal: accept it (with its defaults for the folder) as soon as it shows.
    QTimer::singleShot(0, [] {
      if (auto* dialog = qobject_cast<QDialog*>(QApplication::activeModalWidget())) dialog->accept();
    });
    s.window.import_capture(QDir(t.folder).filePath("frames"));
  });
}

TEST(TaskCancel, TrackCameraPath) {
  const auto& t = test::test_project("cancel-track");
  test::TestStudio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  // No path yet, so the action does not ask whether to replace one.
  s.window.document().modify([](Project& p) { p.path = {}; }, widgets::kPathChanged);
  QAction* track = action_named(s.window, "Track camera path");
  ASSERT_NE(track, nullptr);
  ASSERT_TRUE(track->isEnabled());
  cancel_from_the_status_bar(s, "Track camera path", [&] { track->trigger(); });
}

TEST(TaskCancel, ComputeVisibility) {
  const auto& t = test::test_project("cancel-visibility");
  test::TestStudio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  QAction* visibility = action_named(s.window, "Compute visibility");
  ASSERT_NE(visibility, nullptr);
  ASSERT_TRUE(visibility->isEnabled());
  cancel_from_the_status_bar(s, "Compute visibility", [&] { visibility->trigger(); });
}

TEST(TaskCancel, RefinePathWithAnchors) {
  const auto& t = test::test_project("cancel-refine");
  test::TestStudio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  s.window.document().modify(
      [](Project& p) {
        const PathFrame& first = p.path.frames.front();
        const PathFrame& last = p.path.frames.back();
        p.anchors = {{first.index, first.position(), std::nullopt},
                     {last.index, last.position() + Eigen::Vector2d(0.0, 0.4), std::nullopt}};
      },
      widgets::kAnchorsChanged);
  QAction* refine = action_named(s.window, "Refine path with anchors");
  ASSERT_NE(refine, nullptr);
  ASSERT_TRUE(refine->isEnabled());
  cancel_from_the_status_bar(s, "Refine path with anchors", [&] { refine->trigger(); });
}

TEST(TaskCancel, ExportTourWritesNothing) {
  const auto& t = test::test_project("cancel-export");
  test::TestStudio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  s.window.document().modify(
      [](Project& p) {
        p.keyframes.indices = {p.path.frames.front().index, p.path.frames[15].index,
                               p.path.frames.back().index};
        p.keyframes.rank = {0, 2, 1};
      },
      widgets::kKeyframesChanged);
  const QString target = QDir(t.folder).filePath("cancelled_tour");
  s.window.ask_export = [&](const QString&, const TourSettings& settings) {
    return studio::MainWindow::ExportChoice{target, settings};
  };
  QAction* export_tour = action_named(s.window, "Export tour…");
  ASSERT_NE(export_tour, nullptr);
  ASSERT_TRUE(export_tour->isEnabled());
  cancel_from_the_status_bar(s, "Export tour", [&] { export_tour->trigger(); });
  EXPECT_FALSE(QDir(target).exists());
  EXPECT_FALSE(QDir(target + ".partial").exists());
}

TEST(TaskCancel, PlacePathOnPlan) {
  test::TestStudio s;
  // A walk synthesised in a room with its points on the walls, moved off the plan: placing has work to do.
  Project project;
  project.plan = test::symmetric_room();
  project.capture.camera_height_m = 1.6;
  std::vector<Eigen::Vector2d> walk;
  for (double x = 1.0; x < 9.0; x += 0.1) walk.push_back({x, 3.0 + 0.8 * std::sin(x * 0.9)});
  Similarity2 moved;
  moved.rotation = 0.4;
  moved.translation = {-2.0, 5.0};
  const test::SyntheticPiece piece = test::synthesise(project.plan, walk, moved, 9);
  project.path = piece.path;
  project.path_points = piece.points;
  s.window.document().reset(project, "");
  QAction* place = action_named(s.window, "Place path on plan");
  ASSERT_NE(place, nullptr);
  ASSERT_TRUE(place->isEnabled());
  cancel_from_the_status_bar(s, "Place path on plan", [&] { place->trigger(); });
}

TEST(TaskCancel, ImportTourWritesNoProject) {
  const auto& t = test::test_project("cancel-import-tour");
  test::TestStudio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  Project exported = t.project;
  exported.keyframes.indices = {exported.path.frames.front().index, exported.path.frames.back().index};
  exported.keyframes.rank = {0, 1};
  const QString package = QDir(t.folder).filePath("to_import.zip");
  export_tour(exported, TourExportOptions::from_project(exported, package.toStdString()));
  const QString made = QDir(t.folder).filePath("imported.plenopath");
  s.window.ask_tour_package = [&] { return package; };
  s.window.ask_imported_project = [&](const QString&) { return made; };
  QAction* import = action_named(s.window, "Import tour (to edit it again)…");
  ASSERT_NE(import, nullptr);
  ASSERT_TRUE(import->isEnabled());
  cancel_from_the_status_bar(s, "Import tour", [&] { import->trigger(); });
  EXPECT_FALSE(QFileInfo::exists(made));
  EXPECT_EQ(s.window.document().file_name(), t.project_file);
}

TEST(TaskCancel, RenderCgScene) {
  const auto& t = test::test_project("cancel-render");
  test::TestStudio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  const QString scene = QDir(t.folder).filePath("room.pov");
  QFile file(scene);
  ASSERT_TRUE(file.open(QIODevice::WriteOnly));
  file.write(
      "#version 3.7;\nlight_source { <2, 2.8, 1> color rgb 1 }\n"
      "box { <-5, 0, -3>, <5, 3, 3> inverse pigment { checker rgb 0.8 rgb 0.2 } }\n");
  file.close();
  widgets::CgSceneChoices choices;
  choices.scene = scene.toStdString();
  choices.out_dir = QDir(t.folder).filePath("rendered").toStdString();
  choices.use_project_path = false;
  choices.waypoints = "-4,0 4,0";
  choices.step_m = 2.0;  // five frames: the render is not what is tested
  choices.options.povray.width = 64;
  cancel_from_the_status_bar(s, "Render CG scene", [&] {
    s.window.tasks().start("Render CG scene", studio::render_cg_scene_task(choices));
  });
}

}  // namespace
}  // namespace plenopath
