// `plenopath-studio [PROJECT.plenopath] [--screenshot FILE.png] [--frame N|middle] [--look DEG] [--size WxH]
//  [--compute-visibility] [--resample] [--preview-clean-plate] [--autosave-seconds S]`: the editor.
// --screenshot opens the project, waits until the panorama shows its frame, saves an image of the whole
// window and exits (app/take-screenshot.sh uses it for the README).
#include <QVTKOpenGLNativeWidget.h>
#include <malloc.h>

#include <QAction>
#include <QApplication>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QPainter>
#include <QSurfaceFormat>
#include <QTimer>
#include <cstdio>

#include "app/studio/autosave.h"
#include "app/studio/envelope_service.h"
#include "app/studio/main_window.h"
#include "app/studio/profile_service.h"
#include "app/studio/studio_tasks.h"
#include "widgets/map_view.h"
#include "widgets/panorama_view.h"
#include "widgets/project_document.h"
#include "widgets/sampling_panel.h"
#include "widgets/task_runner.h"

namespace {

// Runs the event loop until `done` or `timeout_ms`.
template <typename Done>
void wait_until(Done done, int timeout_ms) {
  QElapsedTimer timer;
  timer.start();
  while (!done() && timer.elapsed() < timeout_ms) QApplication::processEvents(QEventLoop::AllEvents, 30);
}

int take_screenshot(plenopath::studio::MainWindow& window, const QString& file) {
  using namespace plenopath;
  const int position = window.document().current_position();
  if (window.document().frame_count() > 0)
    wait_until([&] { return window.panorama_view()->shown_position() == position; }, 20000);
  wait_until([&] { return window.envelopes()->ready() || window.document().project().plan.empty(); }, 20000);
  wait_until([&] { return !window.profiles()->busy(); }, 30000);
  wait_until([] { return false; }, 500);  // let queued renders and repaints happen
  window.map_view()->render_now();
  QPixmap pixmap = window.grab();
  // QWidget::grab redirects the panorama's QPainter overlay (captions, hotspots) away from its framebuffer;
  // the panorama's own framebuffer grab has it, so paste that in.
  {
    QPainter painter(&pixmap);
    QWidget* pano = window.panorama_view();
    painter.drawImage(pano->mapTo(&window, QPoint(0, 0)), window.panorama_view()->grabFramebuffer());
  }
  if (!pixmap.save(file)) {
    std::fprintf(stderr, "plenopath-studio: cannot write the screenshot %s\n", qPrintable(file));
    return 1;
  }
  std::printf("screenshot: %s (%dx%d)\n", qPrintable(file), pixmap.width(), pixmap.height());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Decoded frames are megabytes each: give them back to the system when the frame cache drops them, so
  // scrubbing a long capture stays within the cache's memory bound (bench_frame_cache measures this).
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  // Must precede QApplication so that VTK's OpenGL widgets get a compatible context.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("Plenopath Studio");
  QApplication::setOrganizationName("Plenopath");
  QApplication::setApplicationVersion(PLENOPATH_VERSION);

  QCommandLineParser parser;
  parser.setApplicationDescription("Plenopath Studio: walkthrough tours from 360° video.");
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addPositionalArgument("project", "Project file (*.plenopath) to open.", "[PROJECT]");
  const QCommandLineOption screenshot(QString("screenshot"), "Save an image of the window to FILE and exit.",
                                      "FILE");
  const QCommandLineOption frame(QString("frame"), "Go to path position N after opening.", "N");
  const QCommandLineOption look(QString("look"), "Panorama look azimuth in degrees (with --screenshot).",
                                "DEG");
  const QCommandLineOption size(QString("size"), "Window size WxH (with --screenshot).", "WxH");
  const QCommandLineOption autosave_seconds(QString("autosave-seconds"), "Autosave interval (default 180).",
                                            "S");
  const QCommandLineOption compute_visibility(QString("compute-visibility"),
                                              "After opening, compute visibility if the project has none.");
  const QCommandLineOption resample(QString("resample"),
                                    "After opening, sample keyframes if there are none.");
  const QCommandLineOption preview_clean_plate(
      QString("preview-clean-plate"),
      "After going to the frame, show its clean plate before/after (Process menu).");
  parser.addOptions(
      {screenshot, frame, look, size, autosave_seconds, compute_visibility, resample, preview_clean_plate});
  parser.process(app);

  plenopath::studio::MainWindow window;
  if (parser.isSet(autosave_seconds))
    window.autosave().set_interval(static_cast<int>(parser.value(autosave_seconds).toDouble() * 1000));
  if (parser.isSet(size)) {
    const QStringList wh = parser.value(size).split('x');
    if (wh.size() == 2) window.resize(wh[0].toInt(), wh[1].toInt());
  }
  window.show();
  const QStringList args = parser.positionalArguments();
  bool opened = true;
  if (!args.isEmpty()) {
    if (parser.isSet(screenshot)) {
      // Unattended: no question may block, errors go to stderr.
      window.ask_recovery = [](const QString&) { return false; };
      window.show_error = [](const QString& title, const QString& message) {
        std::fprintf(stderr, "plenopath-studio: %s: %s\n", qPrintable(title), qPrintable(message));
      };
    }
    opened = window.open_project(args.first());
  } else if (!parser.isSet(screenshot)) {
    QTimer::singleShot(0, &window, [&window] { window.offer_untitled_recovery(); });
  }
  plenopath::widgets::ProjectDocument& document = window.document();
  if (opened && parser.isSet(compute_visibility) && document.project().visibility.empty() &&
      document.project().path.size() >= 2) {
    window.tasks().start(QObject::tr("Compute visibility"), plenopath::studio::compute_visibility_task());
    window.tasks().wait();
  }
  if (opened && parser.isSet(resample) && document.project().keyframes.empty()) {
    window.sampling_panel()->resample(0);
    window.sampling_panel()->wait();  // visibility and depth sampling finish on a worker
  }
  if (parser.isSet(frame)) {
    const QString f = parser.value(frame);
    document.set_current_position(f == "middle" ? document.frame_count() / 2 : f.toInt());
  }
  if (parser.isSet(look)) {
    auto* p = window.panorama_view();
    p->set_look(parser.value(look).toDouble() * M_PI / 180.0, p->elevation(), p->fov());
  }
  if (opened && parser.isSet(preview_clean_plate)) {
    if (auto* action = window.findChild<QAction*>("preview_clean_plate")) action->trigger();
    window.tasks().wait();
    wait_until([&] { return window.panorama_view()->comparing(); }, 2000);
  }
  if (parser.isSet(screenshot)) {
    if (!opened) return 1;  // the error went to stderr
    return take_screenshot(window, parser.value(screenshot));
  }
  return QApplication::exec();
}
