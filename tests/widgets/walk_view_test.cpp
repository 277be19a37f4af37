// Walk mode in the studio: it shows the keyframe images (not blank), a walk key moves to the next keyframe
// and the picture changes, and a click on the map window walks there.
#include "widgets/walk_view.h"

#include <gtest/gtest.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QFile>
#include <QMessageBox>
#include <QTest>
#include <QThread>
#include <QUndoStack>

#include "model/error.h"
#include "tests/widgets/test_project.h"
#include "tests/widgets/wait_until.h"
#include "widgets/frame_provider.h"
#include "widgets/project_document.h"

namespace plenopath {
namespace {

// Mean and spread of a grabbed view's grey levels, outside the map window and status line.
std::pair<double, double> grey_statistics(const QImage& image) {
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = 40; y < image.height() / 2; y += 3)
    for (int x = 0; x < image.width() / 2; x += 3) {
      const double g = qGray(image.pixel(x, y));
      sum += g;
      sum2 += g * g;
      ++n;
    }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean))};
}

TEST(WalkView, ShowsKeyframesAndWalks) {
  Project project = test::test_project("walk").project;
  project.keyframes.indices = {0, 10, 20, 29};
  widgets::ProjectDocument document;
  document.reset(project, test::test_project("walk").project_file);
  widgets::FrameProvider frames(document);
  widgets::WalkView view(document, frames);
  view.resize(800, 500);
  view.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&view));

  QImage first;
  ASSERT_TRUE(test::wait_until([&] {
    first = view.grabFramebuffer();
    return grey_statistics(first).second > 10.0;
  })) << "the walk view stayed blank";
  EXPECT_EQ(view.navigator().current_keyframe(), 0);

  QTest::keyClick(&view, Qt::Key_W);
  ASSERT_TRUE(test::wait_until(
      [&] { return view.navigator().current_keyframe() == 1 && !view.navigator().moving(); }));
  QImage walked;
  ASSERT_TRUE(test::wait_until([&] {
    walked = view.grabFramebuffer();
    return view.navigator().fade() >= 1.0 && grey_statistics(walked).second > 10.0 && walked != first;
  })) << "the picture did not change after walking";
  walked.save(QString(PLENOPATH_BINARY_DIR) + "/walk_view.png");  // to look at

  // The frame rate while redrawing continuously (printed for the record; speed is not asserted in tests).
  int swaps = 0;
  QObject::connect(&view, &QOpenGLWidget::frameSwapped, [&] { ++swaps; });
  QElapsedTimer clock;
  clock.start();
  while (clock.elapsed() < 1500) {
    view.update();
    QCoreApplication::processEvents(QEventLoop::AllEvents, 5);
  }
  std::printf("walk view: %.0f frames/s at %dx%d\n", swaps * 1000.0 / clock.elapsed(), view.width(),
              view.height());

  // A click on the map window where the last keyframe is drawn walks there.
  const QPointF last = view.map_point(project.path.frames.back().position());
  QTest::mouseClick(&view, Qt::LeftButton, Qt::NoModifier, last.toPoint());
  ASSERT_TRUE(test::wait_until([&] { return !view.navigator().moving(); }));
  EXPECT_EQ(view.navigator().current_keyframe(), 3);
  EXPECT_NEAR(view.navigator().s(), view.navigator().path_length(), 0.2);
}

TEST(WalkView, RefusesAProjectWithoutKeyframes) {
  widgets::ProjectDocument document;
  Project project = test::test_project("walk").project;
  project.keyframes = {};
  document.reset(project, QString());
  widgets::FrameProvider frames(document);
  EXPECT_THROW(widgets::WalkView(document, frames), Error);
}

}  // namespace
}  // namespace plenopath

#include <QAction>
#include <QDir>

#include "app/studio/main_window.h"
#include "processing/export/tour_export.h"
#include "widgets/task_runner.h"

namespace plenopath {
namespace {

QAction* action_named(QWidget& window, const QString& text) {
  for (QAction* a : window.findChildren<QAction*>())
    if (a->text().remove('&').startsWith(text)) return a;
  return nullptr;
}

// From the studio's menus: File > Export tour writes a package (on the task runner, no undo step), and
// View > Walk mode opens the walk window.
TEST(StudioTour, ExportAndWalkFromTheMenus) {
  studio::MainWindow window;
  window.ask_recovery = [](const QString&) { return false; };
  window.ask_save_changes = [] { return QMessageBox::Discard; };
  QStringList errors;
  window.show_error = [&](const QString& title, const QString& message) { errors << title + ": " + message; };
  const QString out = QDir::temp().filePath("plenopath_studio_export_tour");
  QDir(out).removeRecursively();
  window.ask_export = [&](const QString&, const TourSettings& settings) {
    return studio::MainWindow::ExportChoice{out, settings};
  };
  Project project = test::test_project("walk").project;
  project.keyframes.indices = {0, 15, 29};
  window.document().reset(project, test::test_project("walk").project_file);
  window.show();

  QAction* export_tour = action_named(window, "Export tour");
  ASSERT_NE(export_tour, nullptr);
  ASSERT_TRUE(export_tour->isEnabled());
  const int undo_steps = window.document().undo_stack()->count();
  export_tour->trigger();
  ASSERT_TRUE(test::wait_until([&] {
    return !window.tasks().is_running() && QFile::exists(out + "/tour.json");
  })) << errors.join("\n").toStdString();
  EXPECT_TRUE(QFile::exists(out + "/index.html"));
  EXPECT_TRUE(QFile::exists(out + "/images/k000015_full.jpg"));
  EXPECT_EQ(window.document().undo_stack()->count(),
            undo_steps);  // nothing to undo: the document is unchanged
  EXPECT_TRUE(errors.isEmpty()) << errors.join("\n").toStdString();

  QAction* walk = action_named(window, "Walk mode");
  ASSERT_NE(walk, nullptr);
  walk->trigger();
  widgets::WalkView* view = nullptr;
  ASSERT_TRUE(test::wait_until([&] {
    for (QWidget* w : QApplication::topLevelWidgets())
      if (auto* v = qobject_cast<widgets::WalkView*>(w); v && v->isVisible()) view = v;
    return view != nullptr;
  }));
  EXPECT_EQ(view->navigator().keyframes().size(), 3u);
  view->close();
  QDir(out).removeRecursively();
}

// File > Export tour with the dialog's choices: they become the project's tour settings (one undo step),
// and the export writes the files they ask for.
TEST(StudioTour, ExportsWithTheChosenSettings) {
  studio::MainWindow window;
  window.ask_recovery = [](const QString&) { return false; };
  window.ask_save_changes = [] { return QMessageBox::Discard; };
  QStringList errors;
  window.show_error = [&](const QString& title, const QString& message) { errors << title + ": " + message; };
  const QString out = QDir::temp().filePath("plenopath_studio_export_settings");
  QDir(out).removeRecursively();
  Project project = test::test_project("walk").project;
  project.keyframes.indices = {0, 15, 29};
  window.document().reset(project, test::test_project("walk").project_file);
  window.ask_export = [&](const QString&, const TourSettings& current) {
    TourSettings chosen = current;
    chosen.export_tum = true;
    chosen.export_pannellum = true;
    return studio::MainWindow::ExportChoice{out, chosen};
  };
  window.show();
  const int undo_steps = window.document().undo_stack()->count();
  action_named(window, "Export tour")->trigger();
  ASSERT_TRUE(test::wait_until([&] {
    return !window.tasks().is_running() && QFile::exists(out + "/tour.json");
  })) << errors.join("\n").toStdString();
  EXPECT_TRUE(QFile::exists(out + "/trajectory.tum"));
  EXPECT_TRUE(QFile::exists(out + "/pannellum.json"));
  EXPECT_FALSE(QFile::exists(out + "/transforms.json"));
  EXPECT_TRUE(window.document().project().tour.export_tum);
  EXPECT_EQ(window.document().undo_stack()->count(), undo_steps + 1);
  window.document().undo_stack()->undo();
  EXPECT_FALSE(window.document().project().tour.export_tum);
  EXPECT_TRUE(errors.isEmpty()) << errors.join("\n").toStdString();
  QDir(out).removeRecursively();
}

// File > Import tour: an exported tour becomes a project again (made on the task runner, then opened) with
// the tour's keyframes and path, and the open document asked about first.
TEST(StudioTour, ImportsAnExportedTour) {
  studio::MainWindow window;
  window.ask_recovery = [](const QString&) { return false; };
  window.ask_save_changes = [] { return QMessageBox::Discard; };
  QStringList errors;
  window.show_error = [&](const QString& title, const QString& message) { errors << title + ": " + message; };
  const QString root = QDir::temp().filePath("plenopath_studio_import_tour");
  QDir(root).removeRecursively();
  QDir().mkpath(root);
  Project project = test::test_project("walk").project;
  project.keyframes.indices = {0, 15, 29};
  project.keyframes.rank = {0, 2, 1};
  export_tour(project, TourExportOptions::from_project(project, (root + "/tour.zip").toStdString()));
  const QString made = root + "/again.plenopath";
  window.ask_tour_package = [&] { return root + "/tour.zip"; };
  window.ask_imported_project = [&](const QString& suggested) {
    EXPECT_EQ(suggested, root + "/tour.plenopath");
    return made;
  };
  window.show();
  QAction* import = action_named(window, "Import tour");
  ASSERT_NE(import, nullptr);
  import->trigger();
  ASSERT_TRUE(test::wait_until([&] { return window.document().file_name() == made; }))
      << errors.join("\n").toStdString();
  const Project& opened = window.document().project();
  EXPECT_EQ(opened.keyframes.indices, project.keyframes.indices);
  EXPECT_EQ(opened.keyframes.progressive_order(), project.keyframes.progressive_order());
  ASSERT_EQ(opened.path.frames.size(), project.path.frames.size());
  for (std::size_t i = 0; i < project.path.frames.size(); ++i) {
    EXPECT_NEAR(opened.path.frames[i].x, project.path.frames[i].x, 1e-9);
    EXPECT_NEAR(opened.path.frames[i].heading, project.path.frames[i].heading, 1e-9);
  }
  EXPECT_EQ(opened.capture.frame_count, project.path.frames.back().index + 1);
  EXPECT_TRUE(QFile::exists(root + "/again_tour/images/k000015_full.jpg"));
  EXPECT_TRUE(errors.isEmpty()) << errors.join("\n").toStdString();
  // A second import to the same name is refused before any work.
  window.ask_imported_project = [&](const QString&) { return made; };
  import->trigger();
  EXPECT_EQ(errors.size(), 1);
  QDir(root).removeRecursively();
}

}  // namespace
}  // namespace plenopath
