// The studio's done-when tests: open a project, the map shows plan and path, stepping frames changes the
// panorama (and the panorama follows the equirect convention), sampling sliders and undo, cancelled tasks,
// autosave recovery after kill -9, and the command line.
#include <gtest/gtest.h>

#include <QAbstractSlider>
#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QMimeData>
#include <QProcess>
#include <QSignalSpy>
#include <QSlider>
#include <QTest>
#include <QThread>
#include <QTimer>
#include <QUndoStack>
#include <QUrl>
#include <atomic>
#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "app/studio/autosave.h"
#include "app/studio/envelope_service.h"
#include "app/studio/main_window.h"
#include "app/studio/profile_service.h"
#include "app/studio/studio_tasks.h"
#include "model/error.h"
#include "model/project_io.h"
#include "processing/export/tour_export.h"
#include "rig/equirect_sampling.h"
#include "rig/spherical.h"
#include "tests/widgets/test_project.h"
#include "tests/widgets/test_studio.h"
#include "tests/widgets/wait_until.h"
#include "widgets/clean_plate_box.h"
#include "widgets/document_commands.h"
#include "widgets/map_view.h"
#include "widgets/panorama_view.h"
#include "widgets/project_document.h"
#include "widgets/sampling_panel.h"
#include "widgets/task_runner.h"
#include "widgets/timeline.h"

namespace plenopath {
namespace {

using studio::MainWindow;
using test::test_project;

using test::wait_until;

using Studio = test::TestStudio;
using test::count_near;

bool near_colour(QRgb c, int r, int g, int b, int tolerance) {
  return std::abs(qRed(c) - r) <= tolerance && std::abs(qGreen(c) - g) <= tolerance &&
         std::abs(qBlue(c) - b) <= tolerance;
}

TEST(Studio, MapShowsPlanAndPath) {
  const auto& t = test_project();
  Studio s;
  widgets::MapView* map = s.window.map_view();
  map->render_now();
  const QImage empty = map->grabFramebuffer();

  ASSERT_TRUE(s.window.open_project(t.project_file)) << s.errors.join("\n").toStdString();
  QTest::qWait(50);
  map->render_now();
  const QImage image = map->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  ASSERT_FALSE(image.isNull());

  auto is_background = [](QRgb c) { return near_colour(c, 246, 245, 240, 6); };
  auto is_wall = [](QRgb c) { return qRed(c) < 90 && qGreen(c) < 90 && qBlue(c) < 100; };
  auto is_path = [](QRgb c) { return near_colour(c, 31, 119, 180, 40); };
  int background = 0, wall = 0, path = 0, empty_background = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QRgb c = image.pixel(x, y);
      background += is_background(c);
      wall += is_wall(c);
      path += is_path(c);
      empty_background += is_background(empty.pixel(x, y));
    }
  const int total = image.width() * image.height();
  // Without a project the map is (nearly) all background; with one, walls and path cover real area.
  EXPECT_GT(empty_background, 0.97 * total);
  EXPECT_GT(wall, 400) << "walls drawn";
  EXPECT_GT(path, 200) << "path drawn";
  EXPECT_GT(background, 0.3 * total);

  // Where things are: the half wall (x = 4, y 0..2.5) is dark at its middle, the path (y = 3.5) is blue at
  // x = 5.5 (no keyframe or marker there), and the room's middle is empty background.
  EXPECT_GT(count_near(image, map->widget_pixel_of({4.0, 1.25}), 3, is_wall), 0);
  EXPECT_GT(count_near(image, map->widget_pixel_of({5.5, 3.5}), 3, is_path), 0);
  EXPECT_EQ(count_near(image, map->widget_pixel_of({6.0, 1.5}), 3, is_wall), 0);
  EXPECT_GT(count_near(image, map->widget_pixel_of({6.0, 1.5}), 3, is_background), 40);
}

// File > Export Without People: a tour setting of the project, saved with it, one undo step per toggle.
TEST(Studio, CleanPlatesAreATourSettingWithUndo) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file)) << s.errors.join("\n").toStdString();
  QAction* action = s.window.findChild<QAction*>("export_clean_plates");
  ASSERT_NE(action, nullptr);
  EXPECT_FALSE(action->isChecked());
  action->trigger();
  EXPECT_TRUE(s.window.document().project().tour.export_clean_plates);
  EXPECT_TRUE(TourExportOptions::from_project(s.window.document().project(), "out").cleaning.clean_plates);
  s.window.document().undo_stack()->undo();
  EXPECT_FALSE(s.window.document().project().tour.export_clean_plates);
  EXPECT_FALSE(action->isChecked());  // the menu follows the document
}

// The sampling panel's clean-plate box: each control one undo step of the tour settings, the box follows
// the document, and an image nadir patch names its picture.
TEST(Studio, CleanPlateOptionsInTheSamplingPanel) {
  const auto& t = test_project("clean_plate_box");
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file)) << s.errors.join("\n").toStdString();
  widgets::CleanPlateBox* box = s.window.sampling_panel()->clean_plate_box();
  ASSERT_NE(box, nullptr);
  QUndoStack* undo = s.window.document().undo_stack();
  const int steps = undo->count();
  box->clean_plates_box()->click();
  EXPECT_TRUE(s.window.document().project().tour.export_clean_plates);
  EXPECT_TRUE(s.window.findChild<QAction*>("export_clean_plates")->isChecked());  // the menu agrees
  box->nadir_box()->setCurrentIndex(box->nadir_box()->findData("none"));
  EXPECT_EQ(s.window.document().project().tour.nadir_patch, NadirPatch::kNone);
  box->faces_box()->click();
  EXPECT_TRUE(s.window.document().project().tour.blur_faces);
  const QString logo = QFileInfo(t.project_file).absolutePath() + "/logo.png";
  box->set_nadir_image(logo);
  EXPECT_EQ(s.window.document().project().tour.nadir_patch, NadirPatch::kImage);
  EXPECT_EQ(QString::fromStdString(s.window.document().project().tour.nadir_image),
            QFileInfo(logo).absoluteFilePath());
  EXPECT_EQ(box->nadir_box()->currentData().toString(), "image");
  EXPECT_EQ(undo->count(), steps + 4);
  box->set_rig_mask(QFileInfo(t.project_file).absolutePath() + "/rig.png");
  EXPECT_EQ(QFileInfo(QString::fromStdString(s.window.document().project().capture.rig_mask)).fileName(),
            "rig.png");
  undo->undo();
  EXPECT_TRUE(s.window.document().project().capture.rig_mask.empty());
  undo->undo();
  undo->undo();
  EXPECT_FALSE(s.window.document().project().tour.blur_faces);
  EXPECT_FALSE(box->faces_box()->isChecked());
  EXPECT_EQ(box->nadir_box()->currentData().toString(), "none");
}

// Before/after in the panorama: right of the split the other image, left the frame; the split follows a
// drag; Esc and another frame end it. Then Process > Preview clean plate computes one for the frame shown.
TEST(Studio, PanoramaComparesBeforeAndAfter) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  s.window.document().set_current_position(5);
  widgets::PanoramaView* pano = s.window.panorama_view();
  ASSERT_TRUE(wait_until([&] { return pano->shown_position() == 5; }));
  pano->set_look(0.0, 0.0, radians(90.0));
  QImage magenta(t.project.capture.width, t.project.capture.height, QImage::Format_RGB32);
  magenta.fill(QColor(255, 0, 255));
  pano->set_comparison(5, magenta, "test");
  ASSERT_TRUE(pano->comparing());
  auto magenta_share = [&](double from, double to) {
    const QImage view = pano->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
    int n = 0, all = 0;
    for (int y = view.height() / 4; y < view.height() * 3 / 4; y += 2)
      for (int x = static_cast<int>(from * view.width()); x < static_cast<int>(to * view.width()); x += 2) {
        ++all;
        n += near_colour(view.pixel(x, y), 255, 0, 255, 10);
      }
    return double(n) / std::max(1, all);
  };
  EXPECT_LT(magenta_share(0.05, 0.45), 0.02) << "left of the split: the frame";
  EXPECT_GT(magenta_share(0.55, 0.95), 0.95) << "right of the split: the other image";
  // Drag the split from the middle to a quarter of the width.
  const QPoint middle(pano->width() / 2, pano->height() / 2), quarter(pano->width() / 4, pano->height() / 2);
  QTest::mousePress(pano, Qt::LeftButton, Qt::NoModifier, middle);
  QMouseEvent move(QEvent::MouseMove, quarter, Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(pano, &move);
  QTest::mouseRelease(pano, Qt::LeftButton, Qt::NoModifier, quarter);
  EXPECT_NEAR(pano->comparison_split(), 0.25, 0.02);
  EXPECT_GT(magenta_share(0.30, 0.45), 0.95);
  QTest::keyClick(pano, Qt::Key_Escape);
  EXPECT_FALSE(pano->comparing());
  EXPECT_LT(magenta_share(0.30, 0.95), 0.02);

  QAction* preview = s.window.findChild<QAction*>("preview_clean_plate");
  ASSERT_NE(preview, nullptr);
  ASSERT_TRUE(preview->isEnabled());
  preview->trigger();
  ASSERT_TRUE(wait_until([&] { return pano->comparing(); }, 60000)) << s.errors.join("\n").toStdString();
  EXPECT_FALSE(s.window.tasks().is_running());
  EXPECT_EQ(s.window.document().current_position(), 5);
  // Ctrl+drag across the view's middle paints the clean plate away there: an edit of this frame, its mask
  // beside the project, one undo step, and the preview made again.
  const int steps = s.window.document().undo_stack()->count();
  const QPoint from(pano->width() / 2 - 20, pano->height() / 2),
      to(pano->width() / 2 + 20, pano->height() / 2);
  QTest::mousePress(pano, Qt::LeftButton, Qt::ControlModifier, from);
  QMouseEvent stroke(QEvent::MouseMove, to, Qt::LeftButton, Qt::LeftButton, Qt::ControlModifier);
  QApplication::sendEvent(pano, &stroke);
  QTest::mouseRelease(pano, Qt::LeftButton, Qt::ControlModifier, to);
  const int frame = s.window.document().frame_index_at(5);
  const CleanPlateEdit* edit = s.window.document().project().tour.clean_plate_edit(frame);
  ASSERT_NE(edit, nullptr);
  EXPECT_EQ(s.window.document().undo_stack()->count(), steps + 1);
  const cv::Mat mask = cv::imread(edit->mask, cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(mask.empty()) << edit->mask;
  // The view looks at azimuth 0, elevation 0: the image's centre, painted away.
  std::printf("painted %d of %d pixels; mask %dx%d\n", cv::countNonZero(mask), int(mask.total()), mask.cols,
              mask.rows);
  EXPECT_EQ(mask.at<std::uint8_t>(mask.rows / 2, mask.cols / 2), kCleanPlateRemove);
  EXPECT_EQ(mask.at<std::uint8_t>(2, 2), 0);
  ASSERT_TRUE(wait_until([&] { return !s.window.tasks().is_running(); }, 60000));
  EXPECT_TRUE(pano->comparing());
  s.window.document().undo_stack()->undo();
  EXPECT_EQ(s.window.document().project().tour.clean_plate_edit(frame), nullptr);
  s.window.document().set_current_position(6);
  EXPECT_FALSE(pano->comparing()) << "another frame ends the comparison";
}

TEST(Studio, MapShowsTheEnvelopeOfTheCurrentFrame) {
  // From frame 0 at (1, 3.5) the half wall x = 4, y 0..2.5 hides (6, 1): the sight line crosses x = 4 at
  // y = 3.5 - 2.5 * 3 / 5 = 2.0. (6, 4.5) is in plain view. The envelope is drawn as a translucent blue fill.
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  ASSERT_TRUE(wait_until([&] { return s.window.envelopes()->ready(); })) << "visibility index never built";
  widgets::MapView* map = s.window.map_view();
  QTest::qWait(20);
  map->render_now();
  const QImage image = map->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  auto is_envelope = [](QRgb c) { return qBlue(c) > qRed(c) + 25 && qBlue(c) > 200; };
  auto is_background = [](QRgb c) { return near_colour(c, 246, 245, 240, 6); };
  EXPECT_GT(count_near(image, map->widget_pixel_of({6.0, 4.5}), 3, is_envelope), 40);
  EXPECT_GT(count_near(image, map->widget_pixel_of({6.0, 1.0}), 3, is_background), 40);
  EXPECT_EQ(count_near(image, map->widget_pixel_of({6.0, 1.0}), 3, is_envelope), 0);
}

TEST(Studio, TimelineProfileHoldsTheEnvelopeAreaAlongThePath) {
  // By hand: from frame 0 at (1, 3.5) the half wall hides the region right of x = 4 below the line through
  // (4, 2.5) of slope -1/3: the trapezoid (4,0) (4,2.5) (8,1.1667) (8,0) of area 4 * (2.5 + 1.1667) / 2 =
  // 7.333 m^2, so the envelope is 40 - 7.333 = 32.667 m^2; the last frame at (7, 3.5) is its mirror image.
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  ASSERT_TRUE(wait_until([&] {
    return s.window.envelopes()->ready() && !s.window.profiles()->busy() &&
           s.window.profiles()->profiles().envelope_area.size() == 30;
  }));
  const QVector<double>& area = s.window.profiles()->profiles().envelope_area;
  // Tolerance: visibility thickens the dangling half wall to 1 cm (processing/visibility/visibility.h), which
  // takes 2.5 m x 1 cm = 0.025 m^2 off the free space.
  EXPECT_NEAR(area.front(), 40.0 - 22.0 / 3.0, 0.04);
  EXPECT_NEAR(area.back(), 40.0 - 22.0 / 3.0, 0.04);
  for (double a : area) {
    EXPECT_GT(a, 32.0);
    EXPECT_LE(a, 40.0 + 1e-6);
  }
  EXPECT_TRUE(s.window.profiles()->profiles().depth_volume.isEmpty()) << "the test capture has no depth";
}

TEST(Studio, TimelineMarksFlaggedFramesAndSaysWhy) {
  // Frames 10..14 flagged as the tracker would flag them: amber marks over them at the top of the strip,
  // none elsewhere; the line above counts them and gives the current frame's reason.
  const auto& t = test_project("flags");
  Project project = t.project;
  for (int i = 10; i <= 14; ++i) {
    project.path.frames[i].flags = kFrameBridged;
    project.path.frames[i].reason = "bridged: too few tracked points to place the frame";
  }
  const QString file = t.folder + "/flagged.plenopath";
  save_project(project, file.toStdString());
  Studio s;
  ASSERT_TRUE(s.window.open_project(file));
  widgets::TimelinePanel* timeline = s.window.timeline_panel();
  s.window.document().set_current_position(12);
  QApplication::processEvents();
  EXPECT_TRUE(timeline->info_text().contains("5 flagged")) << timeline->info_text().toStdString();
  EXPECT_TRUE(timeline->info_text().contains("too few tracked points"))
      << timeline->info_text().toStdString();
  s.window.document().set_current_position(25);
  QApplication::processEvents();
  EXPECT_TRUE(timeline->info_text().contains("5 flagged"));
  EXPECT_FALSE(timeline->info_text().contains("this frame")) << timeline->info_text().toStdString();
  widgets::TimelineStrip* strip = timeline->strip();
  const QImage image = strip->grab().toImage().convertToFormat(QImage::Format_RGB32);
  auto is_amber = [](QRgb c) { return near_colour(c, 240, 150, 0, 12); };
  EXPECT_GT(count_near(image, QPoint(static_cast<int>(strip->x_of(12)), 8), 2, is_amber), 5);
  EXPECT_EQ(count_near(image, QPoint(static_cast<int>(strip->x_of(3)), 8), 2, is_amber), 0);
  EXPECT_EQ(count_near(image, QPoint(static_cast<int>(strip->x_of(22)), 8), 2, is_amber), 0);
}

TEST(Studio, ClickOnThePathGoesThere) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::MapView* map = s.window.map_view();
  map->render_now();
  const PathFrame& target = t.project.path.frames[20];
  const QPoint pixel = map->widget_pixel_of(target.position()) + QPoint(2, 1);  // a little off the line
  QTest::mouseClick(map, Qt::LeftButton, Qt::NoModifier, pixel);
  EXPECT_EQ(s.window.document().current_position(), 20);
  // A click far from the path goes nowhere.
  QTest::mouseClick(map, Qt::LeftButton, Qt::NoModifier, map->widget_pixel_of({6.0, 0.5}));
  EXPECT_EQ(s.window.document().current_position(), 20);
}

double mean_abs_difference(const QImage& a, const QImage& b) {
  const QImage x = a.convertToFormat(QImage::Format_RGB32), y = b.convertToFormat(QImage::Format_RGB32);
  if (x.size() != y.size()) return 1e9;
  double sum = 0;
  for (int r = 0; r < x.height(); ++r)
    for (int c = 0; c < x.width(); ++c) {
      const QRgb p = x.pixel(c, r), q = y.pixel(c, r);
      sum += std::abs(qRed(p) - qRed(q)) + std::abs(qGreen(p) - qGreen(q)) + std::abs(qBlue(p) - qBlue(q));
    }
  return sum / (3.0 * x.width() * x.height());
}

TEST(Studio, SteppingFramesChangesThePanorama) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::PanoramaView* pano = s.window.panorama_view();
  ASSERT_TRUE(wait_until([&] { return pano->shown_position() == 0; })) << "first frame never shown";
  const QImage first = pano->grabFramebuffer();
  QTest::qWait(20);
  EXPECT_LT(mean_abs_difference(first, pano->grabFramebuffer()), 0.01) << "same frame, same picture";

  pano->setFocus();
  for (int k = 0; k < 12; ++k) QTest::keyClick(pano, Qt::Key_Right);  // keys step frames
  EXPECT_EQ(s.window.document().current_position(), 12);
  ASSERT_TRUE(wait_until([&] { return pano->shown_position() == 12; }));
  const QImage later = pano->grabFramebuffer();
  EXPECT_GT(mean_abs_difference(first, later), 3.0);

  // The whole-image toggle shows a different picture of the same frame.
  QTest::keyClick(pano, Qt::Key_E);
  EXPECT_TRUE(pano->equirect_mode());
  EXPECT_GT(mean_abs_difference(later, pano->grabFramebuffer()), 3.0);
}

TEST(Studio, PlayAdvancesAtTheCaptureFrameRate) {
  // The test capture runs at 10 frames per second: the play timer asks for one frame every 100 ms, playing
  // steps through the frames one by one (never skipping), the panorama keeps up with the play head, and a
  // pause stops it. No wall-clock bounds: a loaded machine fires timers late.
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::TimelinePanel* timeline = s.window.timeline_panel();
  std::vector<int> positions;
  QObject::connect(&s.window.document(), &widgets::ProjectDocument::current_position_changed,
                   [&] { positions.push_back(s.window.document().current_position()); });
  timeline->set_playing(true);
  EXPECT_EQ(timeline->play_interval_ms(), 100);
  ASSERT_TRUE(wait_until([&] { return s.window.document().current_position() >= 4; }, 20000));
  timeline->set_playing(false);
  const int position = s.window.document().current_position();
  ASSERT_GE(positions.size(), 4u);
  for (std::size_t i = 0; i < positions.size(); ++i) EXPECT_EQ(positions[i], static_cast<int>(i) + 1) << i;
  EXPECT_TRUE(wait_until([&] { return s.window.panorama_view()->shown_position() == position; }, 5000));
  QTest::qWait(300);
  EXPECT_EQ(s.window.document().current_position(), position) << "paused";
}

TEST(Studio, PanoramaFollowsTheEquirectConvention) {
  // The view's centre pixel must show the frame's equirect pixel at the look direction, sampled here on the
  // CPU with rig/ (independent of the shader); mirroring the azimuth must not match.
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  s.window.document().set_current_position(7);
  widgets::PanoramaView* pano = s.window.panorama_view();
  ASSERT_TRUE(wait_until([&] { return pano->shown_position() == 7; }));
  const cv::Mat frame = cv::imread(QFileInfo(t.project_file).absolutePath().toStdString() + "/" +
                                   t.project.path.frames[7].file);
  ASSERT_FALSE(frame.empty());

  int matched = 0, mirrored_matched = 0, checks = 0;
  for (double az_deg : {0.0, 50.0, 100.0, 150.0, -40.0, -120.0})
    for (double el_deg : {0.0, 25.0, -20.0}) {
      pano->set_look(radians(az_deg), radians(el_deg), radians(20.0));
      const QImage view = pano->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
      const QRgb c = view.pixel(view.width() / 2, view.height() / 2);
      auto sample = [&](double az) {
        const Eigen::Vector2d px = angles_to_equirect({radians(az), radians(el_deg)}, frame.cols, frame.rows);
        return sample_equirect_bilinear_bgr(frame, px.x(), px.y());
      };
      const cv::Vec3f expected = sample(az_deg), mirrored = sample(-az_deg);
      auto close = [&](const cv::Vec3f& bgr) {
        return std::abs(qRed(c) - bgr[2]) < 14 && std::abs(qGreen(c) - bgr[1]) < 14 &&
               std::abs(qBlue(c) - bgr[0]) < 14;
      };
      ++checks;
      matched += close(expected);
      mirrored_matched += az_deg != 0.0 && close(mirrored) && !close(expected);
    }
  EXPECT_GE(matched, checks - 1) << "view centre matches the equirect sample";
  EXPECT_LE(mirrored_matched, 1);
}

TEST(Studio, WholeImageModeOutlinesTheHotspots) {
  // The test project's hotspot in frame 0 spans azimuth -20..20 deg, elevation -10..20 deg. In whole-image
  // mode the 2:1 image is letterboxed, so its left edge at elevation 5 deg sits at
  // x = x0 + (180 - 20) / 360 * w, y = y0 + (90 - 5) / 180 * h.
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::PanoramaView* pano = s.window.panorama_view();
  ASSERT_TRUE(wait_until([&] { return pano->shown_position() == 0; }));
  pano->set_equirect_mode(true);
  const QImage image = pano->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
  const double aspect = image.width() / static_cast<double>(image.height());
  const double w = aspect > 2.0 ? 2.0 * image.height() : image.width();
  const double h = w / 2.0;
  const double x0 = (image.width() - w) / 2.0, y0 = (image.height() - h) / 2.0;
  auto at = [&](double az, double el) {
    return QPoint(static_cast<int>(x0 + (az + 180.0) / 360.0 * w),
                  static_cast<int>(y0 + (90.0 - el) / 180.0 * h));
  };
  auto is_outline = [](QRgb c) { return near_colour(c, 255, 200, 40, 30); };
  EXPECT_GT(count_near(image, at(-20, 5), 2, is_outline), 2) << "left edge";
  EXPECT_GT(count_near(image, at(20, 5), 2, is_outline), 2) << "right edge";
  EXPECT_GT(count_near(image, at(0, 20), 2, is_outline), 2) << "top edge";
  EXPECT_EQ(count_near(image, at(0, 5), 2, is_outline), 0) << "inside";
  EXPECT_EQ(count_near(image, at(90, 5), 2, is_outline), 0) << "elsewhere";
}

TEST(Studio, DroppingAProjectFileOpensIt) {
  const auto& t = test_project();
  Studio s;
  QMimeData mime;
  mime.setUrls({QUrl::fromLocalFile(t.project_file)});
  QDragEnterEvent enter(QPoint(100, 100), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&s.window, &enter);
  EXPECT_TRUE(enter.isAccepted());
  QDropEvent drop(QPointF(100, 100), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&s.window, &drop);
  ASSERT_TRUE(wait_until([&] { return !s.window.document().file_name().isEmpty(); }, 5000));
  EXPECT_EQ(s.window.document().file_name(), QFileInfo(t.project_file).absoluteFilePath());
  EXPECT_EQ(s.window.document().project().path.size(), 30u);
}

TEST(Studio, SamplingSliderChangesKeyframesAndUndoRestores) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  widgets::ProjectDocument& doc = s.window.document();
  widgets::SamplingPanel* panel = s.window.sampling_panel();
  QUndoStack* stack = doc.undo_stack();
  // Uniform sampling (at once; visibility sampling is tested in sampling_panel_test.cpp).
  panel->method_box()->setCurrentIndex(panel->method_box()->findData("uniform"));
  const Keyframes before = doc.project().keyframes;
  const int steps_before = stack->count();

  // 30 frames at one keyframe per ~5 frames: round(30 / ratio) keyframes, first and last included.
  const int value = widgets::SamplingPanel::slider_of_ratio(5.0);
  const double ratio = widgets::SamplingPanel::ratio_of_slider(value);
  const int expected = std::max(2, static_cast<int>(std::lround(30.0 / ratio)));
  panel->budget_slider()->setValue(value);
  const std::vector<int> k1 = doc.project().keyframes.indices;
  ASSERT_EQ(static_cast<int>(k1.size()), expected);
  EXPECT_EQ(k1.front(), 0);
  EXPECT_EQ(k1.back(), 29);
  EXPECT_EQ(stack->count(), steps_before + 1);

  stack->undo();
  EXPECT_EQ(doc.project().keyframes, before);
  stack->redo();
  EXPECT_EQ(doc.project().keyframes.indices, k1);

  // A drag through several values is one undo step.
  QSlider* slider = panel->budget_slider();
  slider->setSliderDown(true);
  for (double r : {8.0, 12.0, 15.0}) slider->setValue(widgets::SamplingPanel::slider_of_ratio(r));
  slider->setSliderDown(false);
  EXPECT_EQ(stack->count(), steps_before + 2);
  EXPECT_EQ(static_cast<int>(doc.project().keyframes.indices.size()),
            std::max(2, static_cast<int>(
                            std::lround(30.0 / widgets::SamplingPanel::ratio_of_slider(slider->value())))));
  stack->undo();
  EXPECT_EQ(doc.project().keyframes.indices, k1);
}

// A task that edits its snapshot slowly and checks for cancellation every 10 ms.
widgets::TaskResult slow_task(Project project, Progress& progress) {
  project.keyframes.indices = {1, 2, 3};
  project.tour.title = "changed by the task";
  for (int i = 0; i < 6000; ++i) {
    progress.throw_if_cancelled();
    progress.report(i / 6000.0);
    QThread::msleep(10);
  }
  return {std::move(project), widgets::kKeyframesChanged | widgets::kSettingsChanged};
}

TEST(Studio, CancelledTaskLeavesTheDocumentUnchanged) {
  const auto& t = test_project();
  widgets::ProjectDocument doc;
  doc.load(t.project_file);
  widgets::TaskRunner runner(doc);
  const Project before = doc.project();
  QSignalSpy finished(&runner, &widgets::TaskRunner::finished);
  QSignalSpy cancelled(&runner, &widgets::TaskRunner::cancelled);
  QSignalSpy failed(&runner, &widgets::TaskRunner::failed);
  // Whether the cancel reached the worker: the task saw it and ended by Cancelled (the task alone runs for
  // a minute; no wall-clock assertion, the sequence is checked).
  std::atomic<bool> saw_cancel{false};
  auto task = [&saw_cancel](Project project, Progress& progress) {
    try {
      return slow_task(std::move(project), progress);
    } catch (const Cancelled&) {
      saw_cancel = true;
      throw;
    }
  };
  ASSERT_TRUE(runner.start("Slow", task));
  EXPECT_FALSE(runner.start("Another", slow_task)) << "one task at a time";

  // The GUI thread turns meanwhile: a timer keeps firing while the task runs.
  int ticks = 0;
  QTimer timer;
  QObject::connect(&timer, &QTimer::timeout, [&] { ++ticks; });
  timer.start(20);
  ASSERT_TRUE(wait_until([&] { return ticks >= 3; }, 30000));
  EXPECT_TRUE(runner.is_running());

  runner.cancel();
  ASSERT_TRUE(wait_until([&] { return !runner.is_running(); }, 50000)) << "the cancel never reached the task";
  EXPECT_TRUE(saw_cancel) << "the task ran to its end instead of stopping at the cancel";
  ASSERT_EQ(finished.count(), 1);
  EXPECT_FALSE(finished.at(0).at(0).toBool());
  ASSERT_EQ(cancelled.count(), 1);
  EXPECT_EQ(cancelled.at(0).at(0).toString(), "Slow");
  EXPECT_EQ(failed.count(), 0) << "cancelled, not failed";
  EXPECT_EQ(doc.project(), before);
  EXPECT_EQ(doc.undo_stack()->count(), 0);
  EXPECT_FALSE(doc.is_modified());
}

TEST(Studio, TaskResultIsOneUndoStepAndErrorsArriveAsMessages) {
  const auto& t = test_project();
  widgets::ProjectDocument doc;
  doc.load(t.project_file);
  widgets::TaskRunner runner(doc);
  const Project before = doc.project();

  QSignalSpy failed(&runner, &widgets::TaskRunner::failed);
  runner.start("Broken",
               [](Project, Progress&) -> widgets::TaskResult { throw Error("broken.dxf: no geometry"); });
  runner.wait();
  ASSERT_EQ(failed.count(), 1);
  EXPECT_EQ(failed.at(0).at(1).toString(), "broken.dxf: no geometry");
  EXPECT_EQ(doc.project(), before);

  runner.start("Quick", [](Project p, Progress&) {
    p.tour.title = "quick";
    return widgets::TaskResult{std::move(p), widgets::kSettingsChanged};
  });
  runner.wait();
  EXPECT_EQ(doc.project().tour.title, "quick");
  EXPECT_EQ(doc.undo_stack()->count(), 1);
  doc.undo_stack()->undo();
  EXPECT_EQ(doc.project(), before);
}

TEST(Studio, ComputeVisibilityRunsAsATaskAndIsOneUndoStep) {
  // Walking along y = 3.5 past the half wall's end (4, 2.5), the room corners behind it appear and vanish:
  // the path must split into several cells, and the cells must cover the path in order.
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  QAction* action = nullptr;
  for (QAction* a : s.window.findChildren<QAction*>())
    if (a->text().contains("visibility", Qt::CaseInsensitive)) action = a;
  ASSERT_NE(action, nullptr);
  ASSERT_TRUE(action->isEnabled());
  action->trigger();
  EXPECT_TRUE(s.window.tasks().is_running());
  s.window.tasks().wait();
  ASSERT_TRUE(s.errors.isEmpty()) << s.errors.join("\n").toStdString();
  const VisibilityCells& v = s.window.document().project().visibility;
  ASSERT_GE(v.cells.size(), 2u);
  EXPECT_EQ(v.cells.front().first_frame, 0);
  EXPECT_EQ(v.cells.back().last_frame, 29);
  for (std::size_t k = 1; k < v.cells.size(); ++k)
    EXPECT_LE(v.cells[k - 1].last_frame, v.cells[k].first_frame);
  EXPECT_EQ(s.window.document().undo_stack()->count(), 1);
  s.window.document().undo_stack()->undo();
  EXPECT_TRUE(s.window.document().project().visibility.empty());
}

TEST(Studio, TrackingRunsOffTheGuiThreadAndCancels) {
  const auto& t = test_project();
  widgets::ProjectDocument doc;
  doc.load(t.project_file);
  widgets::TaskRunner runner(doc);
  const Project before = doc.project();
  // The tracker's first report holds the worker until the cancel is sent, so the cancel always lands in the
  // middle of the run (whatever the machine's load); then the run must end as cancelled.
  std::atomic<bool> reported{false}, cancel_sent{false};
  runner.set_report_hook([&](double, const std::string&) {
    reported = true;
    for (int i = 0; i < 60000 && !cancel_sent; ++i) QThread::msleep(1);
  });
  QSignalSpy failed(&runner, &widgets::TaskRunner::failed);
  QSignalSpy cancelled(&runner, &widgets::TaskRunner::cancelled);
  ASSERT_TRUE(runner.start("Track camera path", studio::track_path_task()));
  const bool in_the_middle = wait_until([&] { return reported.load(); }, 60000);
  runner.cancel();
  cancel_sent = true;
  ASSERT_TRUE(in_the_middle) << "the tracker never reported";
  ASSERT_TRUE(wait_until([&] { return !runner.is_running(); }, 60000));
  EXPECT_EQ(cancelled.count(), 1) << "the cancel reached the tracker";
  EXPECT_EQ(failed.count(), 0) << (failed.isEmpty() ? "" : failed.at(0).at(1).toString().toStdString());
  EXPECT_EQ(doc.project(), before);
  EXPECT_EQ(doc.undo_stack()->count(), 0);
}

TEST(Studio, ChangesArriveAsOneNotificationPerBatch) {
  widgets::ProjectDocument doc;
  QSignalSpy changed(&doc, &widgets::ProjectDocument::changed);
  {
    widgets::ChangeBatch batch(doc);
    doc.modify([](Project& p) { p.tour.title = "a"; }, widgets::kSettingsChanged);
    doc.modify([](Project& p) { p.keyframes.indices = {0}; }, widgets::kKeyframesChanged);
    EXPECT_EQ(changed.count(), 0);
  }
  ASSERT_EQ(changed.count(), 1);
  EXPECT_EQ(changed.at(0).at(0).toUInt(), widgets::kSettingsChanged | widgets::kKeyframesChanged);
}

TEST(Studio, ClosingWithUnsavedChangesAsks) {
  const auto& t = test_project();
  Studio s;
  ASSERT_TRUE(s.window.open_project(t.project_file));
  s.window.document().undo_stack()->push(new widgets::SetTourTitleCommand(s.window.document(), "edited"));
  int asked = 0;
  s.window.ask_save_changes = [&] {
    ++asked;
    return QMessageBox::Cancel;
  };
  EXPECT_FALSE(s.window.close());
  EXPECT_EQ(asked, 1);
  EXPECT_TRUE(s.window.isVisible());
  s.window.ask_save_changes = [&] {
    ++asked;
    return QMessageBox::Discard;
  };
  EXPECT_TRUE(s.window.close());
  EXPECT_EQ(asked, 2);
  // Discarded: the file on disk is as it was.
  EXPECT_EQ(load_project(t.project_file.toStdString()).tour.title, t.project.tour.title);
}

// ---- autosave recovery after kill -9: the child half runs in a separate process (see below).
constexpr const char* kChildProjectVariable = "PLENOPATH_AUTOSAVE_CHILD_PROJECT";
constexpr const char* kRecoveredTitle = "Edited before the crash";

TEST(AutosaveChild, DISABLED_EditThenWaitToBeKilled) {
  const QString file = qEnvironmentVariable(kChildProjectVariable);
  ASSERT_FALSE(file.isEmpty());
  Studio s;
  ASSERT_TRUE(s.window.open_project(file));
  s.window.autosave().set_interval(200);
  s.window.document().undo_stack()->push(
      new widgets::SetTourTitleCommand(s.window.document(), kRecoveredTitle));
  widgets::SamplingPanel* panel = s.window.sampling_panel();
  panel->method_box()->setCurrentIndex(panel->method_box()->findData("uniform"));  // at once, no cells needed
  panel->budget_slider()->setValue(widgets::SamplingPanel::slider_of_ratio(10.0));
  ASSERT_TRUE(wait_until([&] { return QFile::exists(studio::Autosave::side_file(file)); }, 20000));
  std::printf("AUTOSAVED\n");
  std::fflush(stdout);
  wait_until([] { return false; }, 60000);  // until killed
}

TEST(Studio, AutosaveRecoversAnEditAfterTheProcessIsKilled) {
  const auto& t = test_project("autosave");
  const QString side = studio::Autosave::side_file(t.project_file);
  QFile::remove(side);

  QProcess child;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert(kChildProjectVariable, t.project_file);
  child.setProcessEnvironment(env);
  child.start(
      QCoreApplication::applicationFilePath(),
      {"--gtest_also_run_disabled_tests", "--gtest_filter=AutosaveChild.DISABLED_EditThenWaitToBeKilled"});
  ASSERT_TRUE(child.waitForStarted(10000));
  QByteArray output;
  QElapsedTimer clock;
  clock.start();
  while (!output.contains("AUTOSAVED") && clock.elapsed() < 90000 && child.state() == QProcess::Running) {
    child.waitForReadyRead(200);
    output += child.readAllStandardOutput();
  }
  ASSERT_TRUE(output.contains("AUTOSAVED"))
      << output.toStdString() << child.readAllStandardError().toStdString();
  child.kill();  // SIGKILL: no chance to clean up
  ASSERT_TRUE(child.waitForFinished(10000));
  EXPECT_EQ(child.exitStatus(), QProcess::CrashExit);

  ASSERT_TRUE(QFile::exists(side));
  EXPECT_EQ(load_project(t.project_file.toStdString()).tour.title, t.project.tour.title)
      << "edit was not saved";

  Studio s;
  QString offered;
  s.window.ask_recovery = [&](const QString& file) {
    offered = file;
    return true;
  };
  ASSERT_TRUE(s.window.open_project(t.project_file));
  EXPECT_EQ(offered, side);
  const Project& recovered = s.window.document().project();
  EXPECT_EQ(recovered.tour.title, kRecoveredTitle);
  EXPECT_EQ(recovered.keyframes.indices.size(), 3u);  // round(30 / 10)
  EXPECT_TRUE(s.window.document().is_modified()) << "recovered changes still need saving";
  s.window.document().undo_stack()->undo();  // the recovery itself is one undo step
  EXPECT_EQ(s.window.document().project().tour.title, t.project.tour.title);
  s.window.document().undo_stack()->redo();
  // Saving makes the side file go away.
  ASSERT_TRUE(s.window.save_project());
  EXPECT_FALSE(QFile::exists(side));
  EXPECT_EQ(load_project(t.project_file.toStdString()).tour.title, kRecoveredTitle);
}

TEST(Studio, CommandLineOpensTheProjectAndTakesAScreenshot) {
  const auto& t = test_project();
  const QString png = QFileInfo(t.project_file).absolutePath() + "/shot.png";
  QProcess studio_process;
  studio_process.start(QString(PLENOPATH_BINARY_DIR) + "/app/plenopath-studio",
                       {t.project_file, "--screenshot", png, "--frame", "10", "--size", "1200x760"});
  ASSERT_TRUE(studio_process.waitForFinished(120000));
  ASSERT_EQ(studio_process.exitCode(), 0) << studio_process.readAllStandardError().toStdString();
  QImage shot(png);
  ASSERT_FALSE(shot.isNull());
  EXPECT_EQ(shot.size(), QSize(1200, 760));
  // Not one flat colour: count distinct grey levels over a coarse grid.
  QSet<int> levels;
  for (int y = 0; y < shot.height(); y += 7)
    for (int x = 0; x < shot.width(); x += 7) levels.insert(qGray(shot.pixel(x, y)));
  EXPECT_GT(levels.size(), 40);
}

}  // namespace
}  // namespace plenopath
