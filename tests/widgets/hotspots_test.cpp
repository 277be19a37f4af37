// Hotspot authoring in the studio, as an author does it: four clicks on a wall of the test room in the
// panorama view make a movie texture whose 3-D quad lies on that wall (the room's east wall is the plane
// x = 8 m; the camera is 1.6 m up), drawn re-projected in a later frame, previewed with its media, shown on
// the map; undo and redo; dragging a corner handle; Delete; Esc; an event polygon with its properties edited
// in the Hotspots panel, and its warnings shown as plain text.
#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMouseEvent>
#include <QPushButton>
#include <QTest>
#include <QUndoStack>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "app/studio/main_window.h"
#include "processing/hotspots/hotspot_geometry.h"
#include "processing/hotspots/hotspot_validation.h"
#include "tests/widgets/test_project.h"
#include "tests/widgets/test_studio.h"
#include "tests/widgets/wait_until.h"
#include "widgets/hotspot_editor.h"
#include "widgets/hotspots_panel.h"
#include "widgets/map_view.h"
#include "widgets/panorama_view.h"
#include "widgets/project_document.h"

namespace plenopath {
namespace {

using studio::MainWindow;
using test::test_project;
using test::wait_until;
using widgets::HotspotEditor;

constexpr double kCameraHeight = 1.6;  // the synthetic renderer's, and the studio's default

struct Studio : test::TestStudio {
  widgets::ProjectDocument& document() { return window.document(); }
  widgets::PanoramaView* pano() { return window.panorama_view(); }
  HotspotEditor& editor() { return window.panorama_view()->hotspot_editor(); }
  QAction* action(const QString& text) {
    for (QAction* a : window.findChildren<QAction*>())
      if (a->text() == text) return a;
    ADD_FAILURE() << "no action " << text.toStdString();
    return nullptr;
  }
  const Hotspot* hotspot(const std::string& id) {
    for (const Hotspot& h : document().project().hotspots)
      if (h.id == id) return &h;
    return nullptr;
  }
};

// A rectangle on the east wall x = 8 (y 2.8..4.2, z 1.1..2.1), corners in order around it as seen from the
// west: top-left (larger y), top-right, bottom-right, bottom-left.
const std::vector<Eigen::Vector3d> kWallRectangle{{8, 4.2, 2.1}, {8, 2.8, 2.1}, {8, 2.8, 1.1}, {8, 4.2, 1.1}};

QPointF point_of(Studio& s, const Eigen::Vector3d& world, int position) {
  const PathFrame& pose = s.document().project().path.frames[static_cast<std::size_t>(position)];
  const auto p = s.pano()->widget_point_of(direction_in_frame(world, pose, kCameraHeight));
  EXPECT_TRUE(p.has_value());
  return p.value_or(QPointF());
}

void send_mouse(QWidget* widget, QEvent::Type type, const QPointF& at, Qt::MouseButtons buttons,
                Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  QMouseEvent event(type, at, widget->mapToGlobal(at.toPoint()), Qt::LeftButton, buttons, modifiers);
  QApplication::sendEvent(widget, &event);
}

void click(QWidget* widget, const QPointF& at, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  send_mouse(widget, QEvent::MouseButtonPress, at, Qt::LeftButton, modifiers);
  send_mouse(widget, QEvent::MouseButtonRelease, at, Qt::NoButton, modifiers);
}

double distance(const QPointF& a, const QPointF& b) { return std::hypot(a.x() - b.x(), a.y() - b.y()); }

// Opens the test project at frame 0 looking along +x (at the east wall) with a 90 degree field of view.
void open_and_look_east(Studio& s) {
  ASSERT_TRUE(s.window.open_project(test_project().project_file)) << s.errors.join("\n").toStdString();
  ASSERT_TRUE(wait_until([&] { return s.pano()->shown_position() == 0; })) << "first frame never shown";
  s.pano()->set_look(0.0, 0.0, M_PI / 2);
}

// Places the wall rectangle as a movie texture by four clicks; returns its id.
std::string place_movie_texture(Studio& s) {
  s.action("New &movie texture")->trigger();
  EXPECT_EQ(s.editor().mode(), HotspotEditor::Mode::kNewMovieTexture);
  const std::size_t before = s.document().project().hotspots.size();
  for (const auto& corner : kWallRectangle) click(s.pano(), point_of(s, corner, 0));
  EXPECT_EQ(s.document().project().hotspots.size(), before + 1);
  EXPECT_EQ(s.editor().mode(), HotspotEditor::Mode::kIdle);
  return s.document().project().hotspots.back().id;
}

TEST(Hotspots, FourClicksPlaceAMovieTextureOnTheWallUndoRedo) {
  Studio s;
  open_and_look_east(s);
  QUndoStack* undo = s.document().undo_stack();
  const int steps_before = undo->count();
  const std::string id = place_movie_texture(s);
  const Hotspot* h = s.hotspot(id);
  ASSERT_NE(h, nullptr);
  EXPECT_EQ(h->kind, HotspotKind::kMovieTexture);
  EXPECT_EQ(h->frame, 0);
  EXPECT_EQ(s.editor().selected(), id);
  EXPECT_TRUE(s.editor().last_message().contains("wall")) << s.editor().last_message().toStdString();
  ASSERT_EQ(h->world_corners.size(), 4u);
  // On the wall's plane exactly (snapped), and where the rectangle is to within the click rounding
  // (half a pixel at about 0.2 degrees per pixel, 7 m away: under 2 cm).
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(h->world_corners[i].x(), 8.0, 1e-9) << "corner " << i << " on the east wall";
    EXPECT_NEAR(h->world_corners[i].y(), kWallRectangle[i].y(), 0.03) << i;
    EXPECT_NEAR(h->world_corners[i].z(), kWallRectangle[i].z(), 0.03) << i;
  }
  EXPECT_EQ(undo->count(), steps_before + 1) << "one undo step";
  const std::vector<Eigen::Vector3d> placed = h->world_corners;

  undo->undo();
  EXPECT_EQ(s.hotspot(id), nullptr) << "undo removes it";
  EXPECT_TRUE(s.editor().selected().empty());
  undo->redo();
  ASSERT_NE(s.hotspot(id), nullptr) << "redo restores it";
  EXPECT_EQ(s.hotspot(id)->world_corners, placed);

  // Twelve frames on (x = 3.48 m), the quad is drawn where that frame sees the wall rectangle.
  s.editor().select(id);
  s.document().set_current_position(12);
  ASSERT_TRUE(wait_until([&] { return s.pano()->shown_position() == 12; }));
  const auto corners = s.editor().corner_points(id);
  ASSERT_TRUE(corners.has_value()) << "visible from frame 12";
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_LT(distance((*corners)[i], point_of(s, kWallRectangle[i], 12)), 3.0) << "corner " << i;

  // A corner dragged in frame 12 stays on the wall, and its mark in the authoring frame follows: validation
  // finds the marks consistent with the 3-D quad.
  const QPointF from = (*corners)[2];
  send_mouse(s.pano(), QEvent::MouseButtonPress, from, Qt::LeftButton);
  send_mouse(s.pano(), QEvent::MouseMove, from + QPointF(15, 10), Qt::LeftButton);
  send_mouse(s.pano(), QEvent::MouseButtonRelease, from + QPointF(15, 10), Qt::NoButton);
  const Hotspot& dragged = *s.hotspot(id);
  EXPECT_NEAR(dragged.world_corners[2].x(), 8.0, 1e-9);
  EXPECT_GT((dragged.world_corners[2] - placed[2]).norm(), 0.05) << "the corner moved";
  for (const HotspotWarning& w : validate_hotspot(dragged, s.document().project()))
    EXPECT_NE(w.field, "world_corners") << w.message;

  // The map shows it at its 3-D position: gold on the east wall around y = 3.5.
  widgets::MapView* map = s.window.map_view();
  map->render_now();
  const QImage image = map->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  const QPoint at = map->widget_pixel_of({8.0, 3.5});
  int amber = 0;
  for (int y = at.y() - 4; y <= at.y() + 4; ++y)
    for (int x = at.x() - 4; x <= at.x() + 4; ++x)
      if (image.valid(x, y)) {
        const QRgb c = image.pixel(x, y);
        amber += qRed(c) > 200 && qGreen(c) > 160 && qBlue(c) < 80;  // gold, not the paler critical lines
      }
  EXPECT_GT(amber, 4) << "hotspot marker on the map";
}

TEST(Hotspots, MediaPreviewDragHandleDeleteAndEscape) {
  Studio s;
  open_and_look_east(s);
  const std::string id = place_movie_texture(s);
  QUndoStack* undo = s.document().undo_stack();
  widgets::HotspotsPanel* panel = s.window.hotspots_panel();
  ASSERT_NE(panel, nullptr);

  // Media picked in the panel is warped onto the quad in the panorama, the right way round: the media's left
  // half (red) covers the quad's half nearer corner 0, its right half (blue) the half nearer corner 1.
  const QString media = QFileInfo(test_project().project_file).absolutePath() + "/red_blue.png";
  cv::Mat red_blue(60, 80, CV_8UC3, cv::Scalar(0, 0, 255));
  red_blue(cv::Rect(40, 0, 40, 60)).setTo(cv::Scalar(255, 0, 0));
  cv::imwrite(media.toStdString(), red_blue);
  panel->ask_file = [&](const QString&, const QString&) { return media; };
  QPushButton* choose = nullptr;
  for (QPushButton* b : panel->findChildren<QPushButton*>())
    if (b->text() == "Choose…" && b->isEnabled() && !choose) choose = b;
  ASSERT_NE(choose, nullptr);
  const int before_media = undo->count();
  choose->click();
  EXPECT_EQ(undo->count(), before_media + 1);
  EXPECT_EQ(QString::fromStdString(s.hotspot(id)->media), media);
  const std::vector<Eigen::Vector3d>& q = s.hotspot(id)->world_corners;
  const Eigen::Vector3d centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
  const QImage view = s.pano()->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  if (qgetenv("PLENOPATH_TEST_SAVE").size()) view.save("/tmp/h9/pano_media.png");
  const QRgb left = view.pixel(point_of(s, centre - 0.25 * (q[1] - q[0]), 0).toPoint());
  const QRgb right = view.pixel(point_of(s, centre + 0.25 * (q[1] - q[0]), 0).toPoint());
  EXPECT_TRUE(qRed(left) > 220 && qGreen(left) < 40 && qBlue(left) < 40)
      << "media left half: " << qRed(left) << "," << qGreen(left) << "," << qBlue(left);
  EXPECT_TRUE(qBlue(right) > 220 && qGreen(right) < 40 && qRed(right) < 40)
      << "media right half: " << qRed(right) << "," << qGreen(right) << "," << qBlue(right);

  // Dragging corner 1 (top-right, (8, 2.8, 2.1)) 40 px right and 20 px down: one undo step, and the corner
  // stays on the wall under the mouse.
  const Eigen::Vector3d corner_before = s.hotspot(id)->world_corners[1];
  const QPointF from = point_of(s, corner_before, 0);
  const QPointF to = from + QPointF(40, 20);
  const int before_drag = undo->count();
  send_mouse(s.pano(), QEvent::MouseButtonPress, from, Qt::LeftButton);
  for (int k = 1; k <= 8; ++k)
    send_mouse(s.pano(), QEvent::MouseMove, from + (to - from) * (k / 8.0), Qt::LeftButton);
  send_mouse(s.pano(), QEvent::MouseButtonRelease, to, Qt::NoButton);
  EXPECT_EQ(undo->count(), before_drag + 1) << "a drag is one undo step";
  const Eigen::Vector3d moved = s.hotspot(id)->world_corners[1];
  EXPECT_NEAR(moved.x(), 8.0, 1e-9);
  EXPECT_LT(moved.y(), 2.8 - 0.2) << "moved right (towards -y)";
  EXPECT_LT(moved.z(), 2.1 - 0.1) << "moved down";
  EXPECT_LT(distance(point_of(s, moved, 0), to), 1.5);
  EXPECT_NEAR(s.pano()->azimuth(), 0.0, 1e-12) << "the drag did not turn the view";
  undo->undo();
  EXPECT_LT((s.hotspot(id)->world_corners[1] - corner_before).norm(), 1e-12) << "undo puts the corner back";

  // Delete removes the selected hotspot; undo brings it back.
  s.pano()->setFocus();
  ASSERT_EQ(s.editor().selected(), id);
  QTest::keyClick(s.pano(), Qt::Key_Delete);
  EXPECT_EQ(s.hotspot(id), nullptr);
  undo->undo();
  EXPECT_NE(s.hotspot(id), nullptr);

  // Esc drops a half-made quad: nothing is added.
  const std::size_t count = s.document().project().hotspots.size();
  s.action("New &movie texture")->trigger();
  click(s.pano(), point_of(s, kWallRectangle[0], 0));
  click(s.pano(), point_of(s, kWallRectangle[1], 0));
  EXPECT_EQ(s.editor().pending_corners().size(), 2u);
  QTest::keyClick(s.pano(), Qt::Key_Escape);
  EXPECT_TRUE(s.editor().pending_corners().empty());
  EXPECT_EQ(s.editor().mode(), HotspotEditor::Mode::kIdle);
  EXPECT_FALSE(s.action("New &movie texture")->isChecked());
  EXPECT_EQ(s.document().project().hotspots.size(), count);
}

TEST(Hotspots, EventPolygonEditedInThePanelWithPlainTextWarnings) {
  Studio s;
  open_and_look_east(s);
  // Five Shift+clicks on the north wall (y = 5; look left, azimuth -90 degrees) and Enter: a polygon.
  s.pano()->set_look(-M_PI / 2, 0.0, M_PI / 2);
  s.action("New &event hotspot")->trigger();
  const std::vector<Eigen::Vector3d> pentagon{
      {1.5, 5, 2.0}, {2.3, 5, 1.6}, {2.0, 5, 1.0}, {1.0, 5, 1.0}, {0.7, 5, 1.6}};
  for (const auto& corner : pentagon) click(s.pano(), point_of(s, corner, 0), Qt::ShiftModifier);
  EXPECT_EQ(s.editor().pending_corners().size(), 5u);
  s.pano()->setFocus();
  QTest::keyClick(s.pano(), Qt::Key_Return);
  const Hotspot made = s.document().project().hotspots.back();
  const std::string id = made.id;
  EXPECT_EQ(made.kind, HotspotKind::kEvent);
  ASSERT_EQ(made.world_corners.size(), 5u);
  for (const auto& c : made.world_corners) EXPECT_NEAR(c.y(), 5.0, 1e-9) << "on the north wall";
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(made.world_corners[i].x(), pentagon[i].x(), 0.03) << i;
    EXPECT_NEAR(made.world_corners[i].z(), pentagon[i].z(), 0.03) << i;
  }

  // Properties in the panel: each edit is undoable; typing a name is one step.
  widgets::HotspotsPanel* panel = s.window.hotspots_panel();
  QUndoStack* undo = s.document().undo_stack();
  const int before = undo->count();
  panel->title_edit()->setFocus();
  panel->title_edit()->selectAll();
  QTest::keyClicks(panel->title_edit(), "<b>Lift</b>");
  EXPECT_EQ(s.hotspot(id)->title, "<b>Lift</b>");
  EXPECT_EQ(undo->count(), before + 1) << "typing merges into one step";
  const int open_url = panel->action_box()->findData("open_url");
  ASSERT_GE(open_url, 0);
  panel->action_box()->setCurrentIndex(open_url);
  emit panel->action_box()->activated(open_url);
  EXPECT_EQ(s.hotspot(id)->action, HotspotAction::kOpenUrl);
  panel->target_edit()->setFocus();
  QTest::keyClicks(panel->target_edit(), "javascript:alert(1)");
  EXPECT_EQ(s.hotspot(id)->action_target, "javascript:alert(1)");
  EXPECT_EQ(undo->count(), before + 3);

  // Warnings: markup in the title and a non-http link, shown as plain text.
  panel->validate_now();
  const QString shown = panel->warnings_label()->text();
  EXPECT_TRUE(shown.contains("markup")) << shown.toStdString();
  EXPECT_TRUE(shown.contains("only http and https")) << shown.toStdString();
  EXPECT_TRUE(shown.contains("<b>Lift</b>")) << "the title as typed";
  EXPECT_EQ(panel->warnings_label()->textFormat(), Qt::PlainText);
  undo->undo();
  undo->undo();
  undo->undo();
  EXPECT_EQ(s.hotspot(id)->title, made.title) << "undo restores the name";
  EXPECT_EQ(s.hotspot(id)->action, HotspotAction::kShowText) << "undo restores the action";

  // Selecting the test project's own hotspot (frame 0) from another frame jumps back to frame 0.
  s.document().set_current_position(20);
  panel->list()->setCurrentRow(0);
  EXPECT_EQ(s.editor().selected(), "poster");
  EXPECT_EQ(s.document().current_position(), 0);
}

TEST(Hotspots, VideoMediaPlaysInThePreviewAndWarpsInWholeImageMode) {
  Studio s;
  open_and_look_east(s);
  const std::string id = place_movie_texture(s);
  // A 10 fps clip: five red frames, then five blue ones.
  const QString clip = QFileInfo(test_project().project_file).absolutePath() + "/clip.avi";
  {
    cv::VideoWriter writer(clip.toStdString(), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                           10.0, cv::Size(64, 48));
    ASSERT_TRUE(writer.isOpened());
    for (int k = 0; k < 10; ++k)
      writer.write(cv::Mat(48, 64, CV_8UC3, k < 5 ? cv::Scalar(0, 0, 255) : cv::Scalar(255, 0, 0)));
  }
  widgets::HotspotsPanel* panel = s.window.hotspots_panel();
  panel->media_edit()->setFocus();
  panel->media_edit()->selectAll();
  QTest::keyClicks(panel->media_edit(), clip);
  ASSERT_EQ(QString::fromStdString(s.hotspot(id)->media), clip);
  const std::vector<Eigen::Vector3d>& q = s.hotspot(id)->world_corners;
  const Eigen::Vector3d centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
  auto centre_colour = [&] {
    return s.pano()
        ->grabFramebuffer()
        .convertToFormat(QImage::Format_RGB32)
        .pixel(point_of(s, centre, 0).toPoint());
  };
  auto is_red = [](QRgb c) { return qRed(c) > 200 && qGreen(c) < 60 && qBlue(c) < 60; };
  auto is_blue = [](QRgb c) { return qBlue(c) > 200 && qGreen(c) < 60 && qRed(c) < 60; };
  EXPECT_TRUE(is_red(centre_colour())) << "the first frame";
  s.editor().set_playing(true);
  EXPECT_TRUE(wait_until([&] { return is_blue(centre_colour()); }, 5000))
      << "playing reaches the blue frames";
  s.editor().set_playing(false);

  // Whole-image mode: the quad's centre in the equirectangular frame shows the media too.
  s.pano()->set_equirect_mode(true);
  const QRgb c = centre_colour();
  EXPECT_TRUE(is_red(c) || is_blue(c)) << qRed(c) << "," << qGreen(c) << "," << qBlue(c);

  // Validation decodes the clip: no media warning.
  panel->validate_now();
  for (const HotspotWarning& w : panel->warnings()) EXPECT_NE(w.field, "media") << w.message;
}

}  // namespace
}  // namespace plenopath
