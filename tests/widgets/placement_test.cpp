// The path placed on the plan in the studio (issue 19): Process > Place path on plan runs registration as a
// task (one undo step); the runners-up are drawn on the map as ghosts and a click on one takes it; an anchor
// decides; the tracker's points live in the sidecar beside the project. The truth is the known similarity
// that moved the synthetic path and points off the plan (tests/processing/registration/synthetic_walls.h),
// and, for a symmetric room, that similarity turned by half a turn about the room's centre.
#include <gtest/gtest.h>

#include <QAction>
#include <QFile>
#include <QImage>
#include <QMenuBar>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/studio/main_window.h"
#include "app/studio/placement_service.h"
#include "app/studio/studio_tasks.h"
#include "model/path_points.h"
#include "model/project_io.h"
#include "tests/processing/registration/synthetic_walls.h"
#include "tests/widgets/test_project.h"
#include "tests/widgets/test_studio.h"
#include "tests/widgets/wait_until.h"
#include "widgets/map_view.h"
#include "widgets/project_document.h"
#include "widgets/task_runner.h"

namespace plenopath {
namespace {

constexpr double kDeg = M_PI / 180.0;
using Studio = test::TestStudio;

QAction* action_named(studio::MainWindow& window, const QString& text) {
  for (QAction* menu : window.menuBar()->actions())
    if (menu->menu())
      for (QAction* a : menu->menu()->actions())
        if (a->text() == text) return a;
  ADD_FAILURE() << "no action " << text.toStdString();
  return nullptr;
}

// The symmetric room with a wavy walk, moved off the plan by `truth`.
struct SymmetricCase {
  FloorPlan plan = test::symmetric_room();
  Similarity2 truth, turned;  // the two placements that fit
  Project project;
};

SymmetricCase symmetric_case() {
  SymmetricCase c;
  std::vector<Eigen::Vector2d> walk;
  for (double x = 1.0; x < 9.0; x += 0.1) walk.push_back({x, 3.0 + 0.8 * std::sin(x * 0.9)});
  c.truth.rotation = -33 * kDeg;
  c.truth.translation = {-2.0, 5.0};
  c.turned = c.truth;
  c.turned.rotation = c.truth.rotation + M_PI;
  c.turned.translation = Eigen::Vector2d(10, 6) - c.truth.translation;
  const test::SyntheticPiece piece = test::synthesise(c.plan, walk, c.truth, 9);
  c.project.plan = c.plan;
  c.project.capture.camera_height_m = 1.6;
  c.project.path = piece.path;
  c.project.path_points = piece.points;
  return c;
}

// Largest distance of the document's path from `expected` applied to the unplaced path.
double placement_error(const CameraPath& placed, const CameraPath& unplaced, const Similarity2& expected) {
  double worst = 0.0;
  for (std::size_t i = 0; i < placed.size(); ++i)
    worst =
        std::max(worst, (placed.frames[i].position() - expected.apply(unplaced.frames[i].position())).norm());
  return worst;
}

bool run_place_action(Studio& s) {
  QAction* place = action_named(s.window, "&Place path on plan");
  if (!place || !place->isEnabled()) return false;
  place->trigger();
  return test::wait_until([&] { return !s.window.tasks().is_running(); }, 60000);
}

TEST(Placement, PlaceOnPlanFindsBothFitsOfASymmetricRoomAndAGhostClickTakesTheOther) {
  Studio s;
  const SymmetricCase c = symmetric_case();
  s.window.document().reset(c.project, "");
  ASSERT_TRUE(run_place_action(s));
  ASSERT_TRUE(s.errors.isEmpty()) << s.errors.join("\n").toStdString();
  const CameraPath first = s.window.document().project().path;
  const double to_truth = placement_error(first, c.project.path, c.truth);
  const double to_turned = placement_error(first, c.project.path, c.turned);
  EXPECT_LT(std::min(to_truth, to_turned), 0.05)
      << "truth " << to_truth << " m, turned " << to_turned << " m";
  EXPECT_EQ(s.window.document().undo_stack()->count(), 1);
  // The points moved with the path: the wall points now lie on the plan's walls (z unchanged).
  const Similarity2& applied = to_truth < to_turned ? c.truth : c.turned;
  const PathPoint& p0 = s.window.document().project().path_points.front();
  const Eigen::Vector2d expected_p0 = applied.apply(c.project.path_points.front().position.head<2>());
  EXPECT_LT((p0.position.head<2>() - expected_p0).norm(), 0.05);

  // The other fit is a ghost on the map; clicking it (where it is away from the path) takes it.
  widgets::MapView* map = s.window.map_view();
  map->render_now();
  const Similarity2& other = to_truth < to_turned ? c.turned : c.truth;
  const widgets::MapPlacementGhost* ghost = nullptr;
  for (const widgets::MapPlacementGhost& g : map->placement_ghosts()) {
    double worst = 0.0;
    for (std::size_t i = 0; i < g.polyline.size(); ++i)
      worst = std::max(worst, (g.polyline[i] - other.apply(c.project.path.frames[i].position())).norm());
    if (worst < 0.05) ghost = &g;
  }
  ASSERT_NE(ghost, nullptr) << map->placement_ghosts().size() << " ghosts, none at the other fit";
  EXPECT_NE(ghost->label.find("#"), std::string::npos);
  std::size_t far = 0;
  double far_distance = -1.0;
  for (std::size_t i = 0; i < ghost->polyline.size(); ++i) {
    double nearest = 1e9;
    for (const PathFrame& f : first.frames)
      nearest = std::min(nearest, (f.position() - ghost->polyline[i]).norm());
    if (nearest > far_distance) far_distance = nearest, far = i;
  }
  ASSERT_GT(far_distance, 0.5);
  // The ghost is on screen in its violet (not only in the list).
  map->render_now();
  const QImage image = map->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  if (qEnvironmentVariableIsSet("PLENOPATH_TEST_SAVE")) s.window.grab().save("/tmp/placement_ghosts.png");
  const auto is_violet = [](QRgb c) {
    return qRed(c) > 110 && qBlue(c) > qGreen(c) + 30 && qBlue(c) > qRed(c) + 20;  // not the path's blue
  };
  EXPECT_GT(test::count_near(image, map->widget_pixel_of(ghost->polyline[far]), 4, is_violet), 4);
  QTest::mouseClick(map, Qt::LeftButton, Qt::NoModifier, map->widget_pixel_of(ghost->polyline[far]));
  const CameraPath second = s.window.document().project().path;
  EXPECT_LT(placement_error(second, c.project.path, other), 0.05);
  EXPECT_EQ(s.window.document().undo_stack()->count(), 2);
  // Undo returns to the first placement, and its ghosts come back with it.
  s.window.document().undo_stack()->undo();
  EXPECT_EQ(s.window.document().project().path, first);
  EXPECT_FALSE(map->placement_ghosts().empty());
  // Any other change of the path drops the ghosts.
  Project moved = s.window.document().snapshot();
  moved.path.frames[0].x += 0.5;
  s.window.document().reset(moved, "");
  EXPECT_TRUE(map->placement_ghosts().empty());
}

TEST(Placement, AnAnchorOnThePathDecidesBetweenEqualFits) {
  for (const bool anchor_on_turned : {false, true}) {
    Studio s;
    SymmetricCase c = symmetric_case();
    const Similarity2& wanted = anchor_on_turned ? c.turned : c.truth;
    c.project.anchors = {{10, wanted.apply(c.project.path.frames[10].position()), std::nullopt}};
    s.window.document().reset(c.project, "");
    ASSERT_TRUE(run_place_action(s));
    EXPECT_LT(placement_error(s.window.document().project().path, c.project.path, wanted), 0.05)
        << (anchor_on_turned ? "anchor on the half turn" : "anchor on the truth");
  }
}

TEST(Placement, WhatIsMissingIsSaidNotGuessed) {
  Studio s;
  SymmetricCase c = symmetric_case();
  c.project.capture.camera_height_m = 0.0;
  s.window.document().reset(c.project, "");
  ASSERT_TRUE(run_place_action(s));
  ASSERT_EQ(s.errors.size(), 1);
  EXPECT_TRUE(s.errors[0].contains("camera height")) << s.errors[0].toStdString();
  EXPECT_EQ(s.window.document().project().path, c.project.path);

  // Points from another building fit nowhere: the task fails with registration's reason, nothing moves.
  s.errors.clear();
  c = symmetric_case();
  for (PathPoint& p : c.project.path_points) p.position.head<2>() *= 3.7;  // a building 3.7 times larger
  s.window.document().reset(c.project, "");
  ASSERT_TRUE(run_place_action(s));
  ASSERT_EQ(s.errors.size(), 1);
  EXPECT_TRUE(s.errors[0].contains("no piece of the path fits")) << s.errors[0].toStdString();
  EXPECT_EQ(s.window.document().project().path, c.project.path);
  EXPECT_EQ(s.window.document().undo_stack()->count(), 0);
}

TEST(Placement, TheTrackersPointsLiveInTheSidecarBesideTheProject) {
  QTemporaryDir dir;
  const QString file = dir.filePath("walk.plenopath");
  const SymmetricCase c = symmetric_case();
  {
    widgets::ProjectDocument doc;
    doc.reset(c.project, "");
    doc.save(file);
  }
  // The sidecar read as plain JSON: one [x, y, z, piece, observations] per point.
  std::ifstream in(dir.filePath("walk.points.json").toStdString());
  ASSERT_TRUE(in.good());
  const nlohmann::json sidecar = nlohmann::json::parse(in);
  ASSERT_EQ(sidecar["points"].size(), c.project.path_points.size());
  EXPECT_NEAR(sidecar["points"][3][0].get<double>(), c.project.path_points[3].position.x(),
              1e-5);  // written to 10 µm
  EXPECT_NEAR(sidecar["points"][3][2].get<double>(), c.project.path_points[3].position.z(), 1e-5);
  widgets::ProjectDocument back;
  back.load(file);
  EXPECT_TRUE(back.load_warning().isEmpty());
  EXPECT_EQ(back.project().path_points.size(), c.project.path_points.size());

  // A damaged sidecar does not stop the project from opening; the warning names it.
  QFile damaged(dir.filePath("walk.points.json"));
  ASSERT_TRUE(damaged.open(QIODevice::WriteOnly | QIODevice::Truncate));
  damaged.write("{\"format\": \"plenopath-path-points\", \"points\": [[1, 2");
  damaged.close();
  widgets::ProjectDocument partial;
  partial.load(file);
  EXPECT_TRUE(partial.project().path_points.empty());
  EXPECT_EQ(partial.project().path, back.project().path);
  EXPECT_TRUE(partial.load_warning().contains("walk.points.json")) << partial.load_warning().toStdString();
}

TEST(Placement, TrackingKeepsThePointsAndPlacesThePathByItself) {
  const test::TestProject& t = test::test_project("placement");
  widgets::ProjectDocument doc;
  doc.load(t.project_file);
  Project start = doc.snapshot();
  start.capture.camera_height_m = 1.6;  // the synthetic camera's height in the test project
  doc.reset(start, t.project_file);
  widgets::TaskRunner runner(doc);
  auto outcome = std::make_shared<studio::PlacementOutcome>();
  QSignalSpy failed(&runner, &widgets::TaskRunner::failed);
  ASSERT_TRUE(runner.start("Track camera path", studio::track_path_task(outcome)));
  ASSERT_TRUE(test::wait_until([&] { return !runner.is_running(); }, 120000));
  ASSERT_EQ(failed.count(), 0) << failed.at(0).at(1).toString().toStdString();
  const Project& p = doc.project();
  EXPECT_GT(p.path_points.size(), 100u);
  std::printf("%s\n", outcome->summary.c_str());
  ASSERT_FALSE(outcome->choices.empty()) << outcome->summary;
  ASSERT_TRUE(outcome->choices.result.pieces[0].ok) << outcome->summary;
  // Placed with no alignment at all: against the path the test project was rendered along.
  double worst = 0.0;
  for (std::size_t i = 0; i < p.path.size(); ++i)
    worst = std::max(worst, (p.path.frames[i].position() - t.project.path.frames[i].position()).norm());
  EXPECT_LT(worst, 0.15) << outcome->summary;
  // The points know their frames (capture indices of the path), and the placement was refined on the walls.
  int with_frame = 0;
  for (const PathPoint& q : p.path_points) with_frame += p.path.find_frame(q.frame) ? 1 : 0;
  EXPECT_EQ(with_frame, static_cast<int>(p.path_points.size()));
  ASSERT_EQ(outcome->choices.refinement.pieces.size(), 1u);
  EXPECT_TRUE(outcome->choices.refinement.pieces[0].refined) << outcome->choices.refinement.pieces[0].message;
}

}  // namespace
}  // namespace plenopath
