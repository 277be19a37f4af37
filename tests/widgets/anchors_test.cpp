// Drift anchors in the studio: a Ctrl+drag on the map anchors a frame and bends the path (live preview,
// one undo step), Shift snaps to a plan corner, the Anchors panel lists, edits and deletes anchors with
// residuals, and Refine with anchors runs as an undoable task. The test project's path is straight
// (x = 1..7 at y = 3.5, 30 frames), so the expected bends are computed by hand below.
#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QElapsedTimer>
#include <QMouseEvent>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>
#include <cmath>

#include "app/studio/main_window.h"
#include "app/studio/studio_tasks.h"
#include "model/project_io.h"
#include "processing/anchors/anchor_refinement.h"
#include "processing/egomotion/path_evaluation.h"
#include "processing/visibility/visibility.h"
#include "rig/synthetic_camera.h"
#include "tests/widgets/send_mouse.h"
#include "tests/widgets/test_project.h"
#include "tests/widgets/test_studio.h"
#include "tests/widgets/wait_until.h"
#include "widgets/anchor_commands.h"
#include "widgets/anchor_editor.h"
#include "widgets/anchors_panel.h"
#include "widgets/document_commands.h"
#include "widgets/map_view.h"
#include "widgets/project_document.h"
#include "widgets/task_runner.h"

namespace plenopath {
namespace {

using studio::MainWindow;
using test::test_project;

using Studio = test::TestStudio;
using test::count_near;
using test::send_mouse;

// Press at `from`, move there in `steps` steps, release at `to`, holding `modifiers` all along.
void drag(QWidget* widget, QPoint from, QPoint to, Qt::KeyboardModifiers modifiers, int steps = 8,
          const std::function<void()>& before_release = {}) {
  send_mouse(widget, QEvent::MouseButtonPress, from, Qt::LeftButton, modifiers);
  for (int k = 1; k <= steps; ++k)
    send_mouse(widget, QEvent::MouseMove, from + (to - from) * k / steps, Qt::LeftButton, modifiers);
  if (before_release) before_release();
  send_mouse(widget, QEvent::MouseButtonRelease, to, Qt::NoButton, modifiers);
}

// Lets the anchor edit computed on a worker land (widgets/anchor_editor.h).
void settle(widgets::ProjectDocument& doc) { widgets::AnchorEditor::of(doc).wait(); }

double metres_per_pixel(widgets::MapView* map) {
  return (map->plan_point_at(QPoint(100, 100)) - map->plan_point_at(QPoint(101, 100))).norm();
}

bool is_anchor_colour(QRgb c) {  // the markers' and residual lines' magenta (209, 0, 140)
  return qRed(c) > 150 && qGreen(c) < 80 && qBlue(c) > 90 && qBlue(c) < 190;
}

QAction* action_named(MainWindow& window, const QString& text) {
  for (QAction* a : window.findChildren<QAction*>())
    if (a->text() == text) return a;
  return nullptr;
}

TEST(Anchors, DragCreatesAnAnchorBendsThePathAndUndoRestoresIt) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::MapView* map = s.window.map_view();
  widgets::ProjectDocument& doc = s.window.document();
  map->render_now();
  const CameraPath original = doc.project().path;
  const double tolerance = 1.5 * metres_per_pixel(map);  // where a drag can put a point
  ASSERT_LT(tolerance, 0.05);

  // A plain drag from a frame pans the map: no anchor.
  drag(map, map->widget_pixel_of({4.0, 3.5}), map->widget_pixel_of({4.0, 3.0}), Qt::NoModifier);
  EXPECT_TRUE(doc.project().anchors.empty());
  EXPECT_EQ(doc.undo_stack()->count(), 0);
  map->reset_camera();
  map->render_now();

  // First anchor: frame 0 half a metre south. One anchor is a translation of the whole path.
  bool previewed = false;
  drag(map, map->widget_pixel_of({1.0, 3.5}), map->widget_pixel_of({1.0, 3.0}), Qt::ControlModifier, 8, [&] {
    // While dragging: the preview moves, the document does not.
    previewed = map->is_dragging_anchor() && std::abs(map->anchor_preview().frames[29].y - 3.0) < tolerance &&
                doc.project().path == original;
  });
  settle(doc);
  EXPECT_TRUE(previewed);
  EXPECT_FALSE(map->is_dragging_anchor());
  ASSERT_EQ(doc.project().anchors.size(), 1u);
  EXPECT_EQ(doc.project().anchors[0].frame, 0);
  EXPECT_LT((doc.project().anchors[0].position - Eigen::Vector2d(1.0, 3.0)).norm(), tolerance);
  const CameraPath after_first = doc.project().path;
  for (std::size_t i = 0; i < after_first.size(); ++i) {
    EXPECT_NEAR(after_first.frames[i].x - original.frames[i].x,
                after_first.frames[0].x - original.frames[0].x, 1e-9);
    EXPECT_NEAR(after_first.frames[i].y, 3.0, tolerance) << "frame " << i;
  }
  EXPECT_EQ(doc.undo_stack()->count(), 1);

  // Second anchor: frame 29 (now at about (7, 3)) one metre further south. Between the anchors the path turns
  // and stretches about frame 0: frame i moves by i/29 m (hand-computed for the straight path), so frames
  // near the dragged one move most and those near the other anchor hardly at all.
  map->render_now();
  drag(map, map->widget_pixel_of(after_first.frames[29].position()),
       map->widget_pixel_of(after_first.frames[29].position() - Eigen::Vector2d(0, 1.0)),
       Qt::ControlModifier);
  settle(doc);
  ASSERT_EQ(doc.project().anchors.size(), 2u);
  const CameraPath bent = doc.project().path;
  EXPECT_LT((bent.frames[29].position() - doc.project().anchors[1].position).norm(), 1e-4) << "on its anchor";
  EXPECT_LT((bent.frames[0].position() - doc.project().anchors[0].position).norm(), 1e-4)
      << "first anchor kept";
  std::vector<double> moved;
  for (std::size_t i = 0; i < bent.size(); ++i) {
    moved.push_back((bent.frames[i].position() - after_first.frames[i].position()).norm());
    EXPECT_NEAR(moved[i], i / 29.0, 2 * tolerance) << "frame " << i;
  }
  EXPECT_GT(moved[28], 0.9);
  EXPECT_LT(moved[2], 0.1);

  // The anchors are drawn: magenta markers at both.
  map->render_now();
  const QImage image = map->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  for (const Anchor& a : doc.project().anchors)
    EXPECT_GT(count_near(image, map->widget_pixel_of(a.position), 4, is_anchor_colour), 10)
        << "frame " << a.frame;

  // Undo restores the path and the anchors, step by step; redo brings them back.
  EXPECT_EQ(doc.undo_stack()->count(), 2);
  doc.undo_stack()->undo();
  EXPECT_EQ(doc.project().path, after_first);
  EXPECT_EQ(doc.project().anchors.size(), 1u);
  doc.undo_stack()->undo();
  EXPECT_EQ(doc.project().path, original);
  EXPECT_TRUE(doc.project().anchors.empty());
  doc.undo_stack()->redo();
  doc.undo_stack()->redo();
  EXPECT_EQ(doc.project().path, bent);
}

// Visibility cells belong to a path: when an anchor moves the path, the cells are those of the moved path
// (the map's colours and the visibility sampler use them), and undo brings back the old ones with the old
// path.
TEST(Anchors, CellsFollowTheCorrectedPathAndUndoRestoresThem) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::MapView* map = s.window.map_view();
  widgets::ProjectDocument& doc = s.window.document();
  doc.modify([](Project& p) { p.visibility = VisibilityIndex(p.plan).cells_along_path(p.path); },
             widgets::kVisibilityChanged);
  const VisibilityCells cells_before = doc.project().visibility;
  ASSERT_GT(cells_before.cells.size(), 1u) << "the half wall cuts the straight path into cells";
  map->render_now();
  // Frame 29 (7, 3.5) one metre south: the path turns about frame 0 and its far end crosses other
  // visibility lines of the half wall's end.
  drag(map, map->widget_pixel_of(doc.project().path.frames[29].position()), map->widget_pixel_of({7.0, 2.5}),
       Qt::ControlModifier);
  settle(doc);
  ASSERT_EQ(doc.project().anchors.size(), 1u);
  ASSERT_FALSE(doc.project().path == t.project.path);
  const VisibilityCells expected = VisibilityIndex(doc.project().plan).cells_along_path(doc.project().path);
  EXPECT_EQ(doc.project().visibility, expected);
  EXPECT_FALSE(doc.project().visibility == cells_before);
  doc.undo_stack()->undo();
  EXPECT_EQ(doc.project().visibility, cells_before);
  EXPECT_TRUE(doc.project().anchors.empty());
}

TEST(Anchors, DraggingAnAnchorMarkerMovesItAndShiftSnapsToAPlanCorner) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::MapView* map = s.window.map_view();
  widgets::ProjectDocument& doc = s.window.document();
  map->render_now();
  // Ctrl+Shift drag frame 15 (4.1, 3.5) to 3 pixels off the half wall's end (4, 2.5): it snaps there exactly.
  const int frame = 15;
  const QPoint corner = map->widget_pixel_of({4.0, 2.5});
  drag(map, map->widget_pixel_of(doc.project().path.frames[frame].position()), corner + QPoint(3, -2),
       Qt::ControlModifier | Qt::ShiftModifier);
  settle(doc);
  ASSERT_EQ(doc.project().anchors.size(), 1u);
  EXPECT_EQ(doc.project().anchors[0].frame, frame);
  EXPECT_EQ(doc.project().anchors[0].position, Eigen::Vector2d(4.0, 2.5));
  EXPECT_LT((doc.project().path.frames[frame].position() - Eigen::Vector2d(4.0, 2.5)).norm(), 1e-6);
  // A plain drag on the marker moves the same anchor (no new one); Esc in the middle of a drag cancels.
  map->render_now();
  drag(map, corner, map->widget_pixel_of({5.0, 2.0}), Qt::NoModifier);
  settle(doc);
  ASSERT_EQ(doc.project().anchors.size(), 1u);
  EXPECT_LT((doc.project().anchors[0].position - Eigen::Vector2d(5.0, 2.0)).norm(),
            1.5 * metres_per_pixel(map));
  EXPECT_EQ(doc.undo_stack()->count(), 2);
  const Project before = doc.project();
  map->render_now();
  drag(map, map->widget_pixel_of({5.0, 2.0}), map->widget_pixel_of({6.0, 1.0}), Qt::NoModifier, 4,
       [&] { QTest::keyClick(map, Qt::Key_Escape); });
  EXPECT_EQ(doc.project(), before);
  EXPECT_EQ(doc.undo_stack()->count(), 2);
  EXPECT_FALSE(map->toolTip().isEmpty());
}

TEST(Anchors, PanelListsEditsAndDeletesAnchorsWithResiduals) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::ProjectDocument& doc = s.window.document();
  widgets::AnchorsPanel* panel = s.window.anchors_panel();
  ASSERT_NE(panel, nullptr);
  QTableWidget* table = panel->table();
  const CameraPath original = doc.project().path;

  // Anchors as read from a file: frame 0 on the path, frame 29 half a metre south of it.
  Project with_anchors = doc.snapshot();
  with_anchors.anchors = {{0, {1.0, 3.5}, std::nullopt}, {29, {7.0, 3.0}, std::nullopt}};
  doc.undo_stack()->push(
      new widgets::ReplacePartsCommand(doc, "anchors", with_anchors, widgets::kAnchorsChanged));
  ASSERT_EQ(table->rowCount(), 2);
  EXPECT_EQ(table->item(0, widgets::AnchorsPanel::kFrameColumn)->text(), "0");
  EXPECT_EQ(table->item(1, widgets::AnchorsPanel::kFrameColumn)->text(), "29");
  EXPECT_EQ(table->item(0, widgets::AnchorsPanel::kResidualColumn)->text(), "0.000");
  EXPECT_EQ(table->item(1, widgets::AnchorsPanel::kResidualColumn)->text(), "0.500");
  EXPECT_TRUE(panel->summary().contains("0.500")) << panel->summary().toStdString();

  // The residual is drawn on the map: a magenta line from the anchor (7, 3) to its frame (7, 3.5).
  widgets::MapView* map = s.window.map_view();
  map->render_now();
  const QImage image = map->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  EXPECT_GT(count_near(image, map->widget_pixel_of({7.0, 3.25}), 2, is_anchor_colour), 2);

  // Selecting a row goes to that frame.
  table->selectRow(1);
  EXPECT_EQ(doc.current_position(), 29);

  // Editing y moves the anchor and corrects the path onto it: one undo step.
  const int steps = doc.undo_stack()->count();
  table->item(1, widgets::AnchorsPanel::kYColumn)->setText("2.5");
  settle(doc);
  ASSERT_EQ(doc.project().anchors.size(), 2u);
  EXPECT_EQ(doc.project().anchors[1].position, Eigen::Vector2d(7.0, 2.5));
  EXPECT_LT((doc.project().path.frames[29].position() - Eigen::Vector2d(7.0, 2.5)).norm(), 1e-3);
  EXPECT_EQ(table->item(1, widgets::AnchorsPanel::kResidualColumn)->text(), "0.000");
  EXPECT_EQ(doc.undo_stack()->count(), steps + 1);
  doc.undo_stack()->undo();
  EXPECT_EQ(doc.project().anchors[1].position, Eigen::Vector2d(7.0, 3.0));
  EXPECT_EQ(doc.project().path, original);
  EXPECT_EQ(table->item(1, widgets::AnchorsPanel::kYColumn)->text(), "3.000");

  // A heading: stored in radians; the refinement turns frame 0 toward it (the path ran east, heading 0).
  table->item(0, widgets::AnchorsPanel::kHeadingColumn)->setText("10");
  settle(doc);
  ASSERT_TRUE(doc.project().anchors[0].heading.has_value());
  EXPECT_NEAR(*doc.project().anchors[0].heading, radians(10.0), 1e-12);
  EXPECT_NEAR(doc.project().path.frames[0].heading, radians(10.0), radians(2.0));
  EXPECT_LT((doc.project().path.frames[0].position() - Eigen::Vector2d(1.0, 3.5)).norm(), 0.05);
  doc.undo_stack()->undo();
  EXPECT_EQ(doc.project().path, original);
  EXPECT_FALSE(doc.project().anchors[0].heading.has_value());

  // Bad input is refused with a message and the cell shows the document's value again; no undo step.
  const int before_bad = doc.undo_stack()->count();
  table->item(1, widgets::AnchorsPanel::kXColumn)->setText("east");
  QTest::qWait(20);
  EXPECT_EQ(table->item(1, widgets::AnchorsPanel::kXColumn)->text(), "7.000");
  EXPECT_TRUE(panel->summary().contains("east")) << panel->summary().toStdString();
  table->item(1, widgets::AnchorsPanel::kFrameColumn)->setText("99");
  QTest::qWait(20);
  EXPECT_TRUE(panel->summary().contains("99")) << panel->summary().toStdString();
  table->item(1, widgets::AnchorsPanel::kFrameColumn)->setText("0");
  QTest::qWait(20);
  EXPECT_TRUE(panel->summary().contains("already")) << panel->summary().toStdString();
  EXPECT_EQ(doc.undo_stack()->count(), before_bad);

  // Moving the anchor to another frame.
  table->item(1, widgets::AnchorsPanel::kFrameColumn)->setText("20");
  settle(doc);
  ASSERT_EQ(doc.project().anchors.size(), 2u);
  EXPECT_EQ(doc.project().anchors[1].frame, 20);
  EXPECT_LT((doc.project().path.frames[20].position() - Eigen::Vector2d(7.0, 3.0)).norm(), 1e-3);
  doc.undo_stack()->undo();

  // Del removes the selected anchor (the path stays); the button does the same; undo brings it back.
  table->setFocus();
  table->selectRow(1);
  QTest::keyClick(table, Qt::Key_Delete);
  ASSERT_EQ(doc.project().anchors.size(), 1u);
  EXPECT_EQ(doc.project().anchors[0].frame, 0);
  EXPECT_EQ(table->rowCount(), 1);
  table->selectRow(0);
  panel->delete_button()->click();
  EXPECT_TRUE(doc.project().anchors.empty());
  doc.undo_stack()->undo();
  doc.undo_stack()->undo();
  EXPECT_EQ(doc.project().anchors.size(), 2u);
  EXPECT_EQ(doc.project().path, original);
}

TEST(Anchors, RefineWithAnchorsIsATaskAndOneUndoStep) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::ProjectDocument& doc = s.window.document();
  QAction* refine = action_named(s.window, "Refine path with &anchors");
  ASSERT_NE(refine, nullptr);
  EXPECT_FALSE(refine->isEnabled()) << "no anchors yet";
  const CameraPath original = doc.project().path;
  // Anchors on its ends say the path really ran north along x = 4 from y = 1 to y = 4: the refinement turns
  // and shrinks the straight 6 m path onto that line, frame i at y = 1 + 3 i / 29.
  Project with_anchors = doc.snapshot();
  with_anchors.anchors = {{0, {4.0, 1.0}, std::nullopt}, {29, {4.0, 4.0}, std::nullopt}};
  doc.undo_stack()->push(
      new widgets::ReplacePartsCommand(doc, "anchors", with_anchors, widgets::kAnchorsChanged));
  ASSERT_TRUE(refine->isEnabled());
  const int steps = doc.undo_stack()->count();
  refine->trigger();
  EXPECT_TRUE(s.window.tasks().is_running());
  s.window.tasks().wait();
  ASSERT_TRUE(s.errors.isEmpty()) << s.errors.join("\n").toStdString();
  const CameraPath& refined = doc.project().path;
  EXPECT_LT((refined.frames[0].position() - Eigen::Vector2d(4.0, 1.0)).norm(), 0.05);
  EXPECT_LT((refined.frames[29].position() - Eigen::Vector2d(4.0, 4.0)).norm(), 0.05);
  // A straight path stays straight: frame i at y = 1 + 3 i / 29 on x = 4, heading north.
  for (int i : {7, 15, 22}) {
    EXPECT_NEAR(refined.frames[i].x, 4.0, 0.05) << i;
    EXPECT_NEAR(refined.frames[i].y, 1.0 + 3.0 * i / 29, 0.05) << i;
    EXPECT_NEAR(refined.frames[i].heading, M_PI / 2, 0.02) << i;
  }
  EXPECT_EQ(doc.undo_stack()->count(), steps + 1);
  EXPECT_LT(
      s.window.anchors_panel()->table()->item(1, widgets::AnchorsPanel::kResidualColumn)->text().toDouble(),
      0.05);
  doc.undo_stack()->undo();
  EXPECT_EQ(doc.project().path, original);
}

// Anchors placed one after another, as an author does (each placement refines the path already corrected
// by the previous ones), undo the drift as well as the three at once: a 900-frame office walk integrated
// with a slow heading bias and a 5 % scale error, anchors on ground-truth positions.
TEST(Anchors, AnchorsPlacedOneByOneUndoDrift) {
  CameraPath truth = auto_walk(make_office_sample_plan());
  truth.frames.resize(std::min<std::size_t>(truth.frames.size(), 900));
  CameraPath drifted = truth;
  Eigen::Vector2d p = truth.frames[0].position() + Eigen::Vector2d(0.7, -0.4);
  double bias = 0.1;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i > 0) {
      bias += radians(0.02);
      const Eigen::Vector2d step = truth.frames[i].position() - truth.frames[i - 1].position();
      p += 1.05 * Eigen::Vector2d(std::cos(bias) * step.x() - std::sin(bias) * step.y(),
                                  std::sin(bias) * step.x() + std::cos(bias) * step.y());
    }
    drifted.frames[i].x = p.x();
    drifted.frames[i].y = p.y();
    drifted.frames[i].heading = wrap_angle(truth.frames[i].heading + bias);
  }
  Project project;
  project.path = drifted;
  widgets::ProjectDocument doc;
  doc.reset(project, QString());
  const std::size_t n = truth.size();
  for (std::size_t i : {std::size_t{0}, n - 1, n / 2}) {
    const Anchors after =
        widgets::anchors_with(doc.project().anchors, truth.frames[i].index, truth.frames[i].position());
    auto* command = new widgets::SetAnchorsCommand(
        doc, "anchor", edit_anchors(doc.project(), after, widgets::PathCorrection::kRefine));
    EXPECT_EQ(command->applied(), widgets::PathCorrection::kRefine);
    doc.undo_stack()->push(command);
  }
  const double before = evaluate_path(drifted, truth).ate_rms_m;
  const double after = evaluate_path(doc.project().path, truth).ate_rms_m;
  std::printf("anchors placed one by one: ATE %.3f m -> %.3f m (%.1fx)\n", before, after, before / after);
  EXPECT_GT(before / after, 5.0);
  for (const Anchor& a : doc.project().anchors)
    EXPECT_LT((doc.project().path.find_frame(a.frame)->position() - a.position).norm(), 0.05) << a.frame;
  // The warp alone (what the drag previews) does much less.
  const double warped =
      evaluate_path(preview_path_with_anchors(drifted, doc.project().anchors), truth).ate_rms_m;
  std::printf("  the warp alone: ATE %.3f m\n", warped);
  while (doc.undo_stack()->canUndo()) doc.undo_stack()->undo();
  EXPECT_EQ(doc.project().path, drifted);
}

// How interactive a drag is on a long path (printed for the report; speed targets live in bench_anchors):
// the office sample's whole walk, ~2 900 frames, each move recomputing the preview and redrawing the map.
TEST(Anchors, DragOnALongPathPrintsItsFrameTime) {
  Project project;
  project.plan = make_office_sample_plan();
  project.path = auto_walk(project.plan);
  widgets::ProjectDocument doc;
  doc.reset(project, QString());
  widgets::MapView map(doc);
  map.resize(900, 600);
  map.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&map));
  map.reset_camera();
  map.render_now();
  const PathFrame& f = doc.project().path.frames[doc.project().path.size() / 3];
  const QPoint from = map.widget_pixel_of(f.position());
  const int moves = 8;
  QElapsedTimer clock;
  clock.start();
  for (int k = 0; k < moves; ++k) map.render_now();
  const double ms_per_render = clock.nsecsElapsed() / 1e6 / moves;
  send_mouse(&map, QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::ControlModifier);
  clock.restart();
  for (int k = 1; k <= moves; ++k) {
    send_mouse(&map, QEvent::MouseMove, from + QPoint(2 * k, k), Qt::LeftButton, Qt::ControlModifier);
    map.render_now();
  }
  const double ms_per_move = clock.nsecsElapsed() / 1e6 / moves;
  clock.restart();
  send_mouse(&map, QEvent::MouseButtonRelease, from + QPoint(2 * moves, moves), Qt::NoButton,
             Qt::ControlModifier);
  const double release_ms = clock.nsecsElapsed() / 1e6;
  settle(doc);
  const double landed_ms = clock.nsecsElapsed() / 1e6;
  std::printf(
      "drag on a %zu-frame path: %.1f ms per move (preview + redraw; a redraw alone %.1f ms), release "
      "%.0f ms, refinement landed after %.0f ms\n",
      doc.project().path.size(), ms_per_move, ms_per_render, release_ms, landed_ms);
  EXPECT_EQ(doc.project().anchors.size(), 1u);
}

// Cancel reaches the solver: the refinement of the office walk (2 888 frames) cancelled right after it
// starts leaves the document as it was, with no undo step.
TEST(Anchors, CancelledRefinementChangesNothing) {
  Project project;
  project.plan = make_office_sample_plan();
  project.path = auto_walk(project.plan);
  const std::size_t n = project.path.size();
  for (std::size_t i : {std::size_t{0}, n / 2, n - 1})
    project.anchors.push_back({project.path.frames[i].index,
                               project.path.frames[i].position() + Eigen::Vector2d(0.3, 0.2), std::nullopt});
  widgets::ProjectDocument doc;
  doc.reset(project, QString());
  widgets::TaskRunner runner(doc);
  QSignalSpy finished(&runner, &widgets::TaskRunner::finished);
  QSignalSpy failed(&runner, &widgets::TaskRunner::failed);
  ASSERT_TRUE(runner.start("Refine path with anchors", studio::refine_with_anchors_task()));
  runner.cancel();
  runner.wait();
  ASSERT_EQ(finished.count(), 1);
  EXPECT_FALSE(finished.at(0).at(0).toBool());
  EXPECT_EQ(failed.count(), 0) << "cancelled, not failed";
  EXPECT_EQ(doc.project().path, project.path);
  EXPECT_EQ(doc.undo_stack()->count(), 0);
}

}  // namespace
}  // namespace plenopath

namespace plenopath {
namespace {

// A path in two pieces (the tracker's result where the images do not connect): the second piece is
// unplaced, in its own gauge (first frame at the origin, heading 0, here turned 90 deg against the plan). The
// map draws it beside the plan, not at the origin; one Ctrl+drag of one of its frames places it there (an
// anchor moves that piece alone), a second anchor turns it onto its true line.
TEST(Anchors, AnUnplacedPieceIsDrawnBesideThePlanAndPlacedByItsAnchors) {
  const auto& t = test_project("pieces");
  Project project = t.project;
  const CameraPath truth = project.path;  // x = 1..7 at y = 3.5
  ASSERT_EQ(truth.size(), 30u);
  CameraPath path = truth;
  const PathFrame start = truth.frames[15];
  for (std::size_t i = 15; i < path.size(); ++i) {
    PathFrame& f = path.frames[i];
    const Eigen::Vector2d d = truth.frames[i].position() - start.position();
    f.x = -d.y();  // rotated by +90 deg about the piece's first frame, which sits at the origin
    f.y = d.x();
    f.heading = wrap_angle(truth.frames[i].heading + M_PI / 2);
    f.piece = 1;
  }
  path.pieces = {
      {truth.frames[0].index, truth.frames[14].index, true, "camera_height", 1.0, ""},
      {truth.frames[15].index, truth.frames[29].index, false, "camera_height", 1.0, "no image connects"}};
  project.path = path;
  const std::string file = (t.folder + "/pieces.plenopath").toStdString();
  save_project(project, file);

  Studio s;
  ASSERT_TRUE(s.window.open_project(QString::fromStdString(file)));
  widgets::MapView* map = s.window.map_view();
  widgets::ProjectDocument& doc = s.window.document();
  ASSERT_EQ(doc.project().path.piece_count(), 2);
  map->render_now();
  const double tolerance = 1.5 * metres_per_pixel(map);

  // Drawn beside the plan (right of its 8 m), never at the plan's origin; piece 0 where it is.
  const CameraPath& drawn = map->drawn_path();
  ASSERT_EQ(drawn.size(), 30u);
  const PlanExtents extents = doc.project().plan.extents();
  for (std::size_t i = 15; i < 30; ++i) EXPECT_GT(drawn.frames[i].x, extents.max.x() + 0.5) << i;
  for (std::size_t i = 0; i < 15; ++i) EXPECT_EQ(drawn.frames[i].position(), path.frames[i].position());
  // The tray piece is drawn in its colour (palette entry 1: red).
  const QImage image = map->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  auto is_piece_1 = [](QRgb c) { return qRed(c) > 180 && qGreen(c) < 90 && qBlue(c) < 90; };
  EXPECT_GT(count_near(image, map->widget_pixel_of(drawn.frames[22].position()), 4, is_piece_1), 3);

  // One anchor on frame 15 at its true place: piece 1 placed, moved as a whole; piece 0 untouched.
  drag(map, map->widget_pixel_of(drawn.frames[15].position()), map->widget_pixel_of(start.position()),
       Qt::ControlModifier);
  settle(doc);
  ASSERT_EQ(doc.project().anchors.size(), 1u);
  EXPECT_EQ(doc.project().anchors[0].frame, start.index);
  const CameraPath& placed = doc.project().path;
  EXPECT_TRUE(placed.piece_placed(1));
  EXPECT_LT((placed.frames[15].position() - start.position()).norm(), tolerance);
  for (std::size_t i = 0; i < 15; ++i) EXPECT_EQ(placed.frames[i].position(), path.frames[i].position()) << i;
  // Still turned (one anchor without a heading cannot know better), but rigidly: frame 29 is 14 steps
  // from frame 15, along +y.
  const double step = (truth.frames[1].position() - truth.frames[0].position()).norm();
  EXPECT_NEAR((placed.frames[29].position() - placed.frames[15].position()).norm(), 14 * step, 1e-6);

  // A second anchor, frame 29 at its true place: the piece lies on its true line.
  map->render_now();
  drag(map, map->widget_pixel_of(placed.frames[29].position()),
       map->widget_pixel_of(truth.frames[29].position()), Qt::ControlModifier);
  settle(doc);
  ASSERT_EQ(doc.project().anchors.size(), 2u);
  for (std::size_t i = 15; i < 30; ++i)
    EXPECT_LT((doc.project().path.frames[i].position() - truth.frames[i].position()).norm(), 3 * tolerance)
        << i;
  // Undo twice: unplaced again.
  doc.undo_stack()->undo();
  doc.undo_stack()->undo();
  EXPECT_FALSE(doc.project().path.piece_placed(1));
  EXPECT_EQ(doc.project().path, path);
}

}  // namespace
}  // namespace plenopath
