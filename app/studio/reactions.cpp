#include "app/studio/reactions.h"

#include <QAction>
#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QImage>
#include <QMenu>
#include <QMessageBox>
#include <QSettings>
#include <QStatusBar>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "app/studio/main_window.h"
#include "app/studio/placement_service.h"
#include "app/studio/studio_tasks.h"
#include "model/error.h"
#include "model/path_io.h"
#include "model/project_io.h"
#include "processing/export/tour_export.h"
#include "processing/export/tour_import.h"
#include "widgets/capture_import_dialog.h"
#include "widgets/cg_scene_dialog.h"
#include "widgets/document_commands.h"
#include "widgets/dxf_import_dialog.h"
#include "widgets/map_view.h"
#include "widgets/panorama_view.h"
#include "widgets/project_document.h"
#include "widgets/task_runner.h"
#include "widgets/walk_view.h"

namespace plenopath::studio {

namespace {

// Once the running task's result is the document's, hands what registration found to the placement
// service and says in the status bar how the placement went (one-shot: the next task connects anew).
void offer_when_applied(MainWindow& window, std::shared_ptr<PlacementOutcome> outcome) {
  auto connection = std::make_shared<QMetaObject::Connection>();
  *connection = QObject::connect(
      &window.tasks(), &widgets::TaskRunner::finished, &window, [&window, outcome, connection](bool applied) {
        QObject::disconnect(*connection);
        if (!applied) return;
        window.placement().offer(std::move(outcome->choices));
        QString text = QString::fromStdString(outcome->summary);
        if (!window.map_view()->placement_ghosts().empty())
          text += QObject::tr(" — other placements in violet on the map: click one to take it");
        if (!text.isEmpty()) window.statusBar()->showMessage(text, 20000);
      });
}

}  // namespace

Reaction::Reaction(QAction* action, MainWindow& window) : QObject(action), window_(window), action_(action) {
  connect(action, &QAction::triggered, this, [this] { on_triggered(); });
}

void NewProjectReaction::on_triggered() {
  if (!window_.maybe_save()) return;
  window_.document().reset(Project{}, QString());
}

void OpenProjectReaction::on_triggered() {
  const QString file = QFileDialog::getOpenFileName(&window_, QObject::tr("Open project"), QString(),
                                                    QObject::tr("Plenopath projects (*.plenopath)"));
  if (!file.isEmpty() && window_.maybe_save()) window_.open_project(file);
}

SaveProjectReaction::SaveProjectReaction(QAction* action, MainWindow& window, bool save_as)
    : Reaction(action, window), save_as_(save_as) {}

void SaveProjectReaction::on_triggered() {
  if (save_as_) {
    window_.save_project_as();
  } else {
    window_.save_project();
  }
}

void ImportPlanReaction::on_triggered() { window_.import_plan(QString()); }

void ImportCaptureReaction::on_triggered() { window_.import_capture(QString(), stills_); }

void ImportPathReaction::on_triggered() {
  const QString file = QFileDialog::getOpenFileName(&window_, QObject::tr("Camera path"), QString(),
                                                    QObject::tr("Path files (*.json)"));
  if (file.isEmpty()) return;
  Project after = window_.document().snapshot();
  try {
    after.path = read_path_file(file.toStdString());
  } catch (const std::exception& e) {
    QMessageBox::critical(&window_, QObject::tr("Cannot read the path"), QString::fromStdString(e.what()));
    return;
  }
  window_.document().undo_stack()->push(new widgets::ReplacePartsCommand(
      window_.document(), QObject::tr("Import path"), after, widgets::kPathChanged));
}

RenderCgSceneReaction::RenderCgSceneReaction(QAction* action, MainWindow& window) : Reaction(action, window) {
  connect(&window.tasks(), &widgets::TaskRunner::finished, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::started, this, [this] { update_enabled(); });
  update_enabled();
}

void RenderCgSceneReaction::update_enabled() { action()->setEnabled(!window_.tasks().is_running()); }

void RenderCgSceneReaction::on_triggered() {
  if (dialog_) {  // already open (or hidden while its waypoints are drawn on the map)
    if (dialog_->isVisible()) {
      dialog_->raise();
      dialog_->activateWindow();
    }
    return;
  }
  const Project& p = window_.document().project();
  // Window-modal and opened, not exec()'d: Draw on plan hides it while the map takes the clicks.
  dialog_ = new widgets::CgSceneDialog(&window_, p.path.size() >= 2);
  dialog_->setAttribute(Qt::WA_DeleteOnClose);
  dialog_->set_map(window_.map_view());
  dialog_->set_plan(p.plan);
  connect(dialog_, &QDialog::accepted, this, [this, dialog = dialog_.data()] {
    const widgets::CgSceneChoices choices = dialog->choices();
    if (!window_.document().project().capture.empty() &&
        QMessageBox::question(&window_, QObject::tr("Render CG scene"),
                              QObject::tr("Replace the project's capture and path with the rendered frames "
                                          "and their poses? (Undo brings the old ones back.)")) !=
            QMessageBox::Yes)
      return;
    window_.tasks().start(QObject::tr("Render CG scene"), render_cg_scene_task(choices));
  });
  dialog_->open();
}

ComputeVisibilityReaction::ComputeVisibilityReaction(QAction* action, MainWindow& window)
    : Reaction(action, window) {
  connect(&window.document(), &widgets::ProjectDocument::changed, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::finished, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::started, this, [this] { update_enabled(); });
  update_enabled();
}

void ComputeVisibilityReaction::update_enabled() {
  const Project& p = window_.document().project();
  action()->setEnabled(!window_.tasks().is_running() && p.path.size() >= 2 && !p.plan.segments.empty());
}

void ComputeVisibilityReaction::on_triggered() {
  window_.tasks().start(QObject::tr("Compute visibility"),
                        compute_visibility_task(window_.document().visibility_index()));
}

ExportTourReaction::ExportTourReaction(QAction* action, MainWindow& window) : Reaction(action, window) {
  connect(&window.document(), &widgets::ProjectDocument::changed, this, [this] { update_enabled(); });
  update_enabled();
}

void ExportTourReaction::update_enabled() {
  const Project& p = window_.document().project();
  action()->setEnabled(!p.path.empty() && !p.keyframes.empty());
}

void ExportTourReaction::on_triggered() {
  const QString suggested = window_.document().file_name().isEmpty()
                                ? QStringLiteral("tour")
                                : QFileInfo(window_.document().file_name()).completeBaseName() + "_tour";
  const MainWindow::ExportChoice choice =
      window_.ask_export(QFileInfo(window_.document().file_name()).absoluteDir().filePath(suggested),
                         window_.document().project().tour);
  if (choice.output.isEmpty()) return;
  // The choices are the project's tour settings (one undo step), so the next export starts from them.
  if (!(choice.settings == window_.document().project().tour)) {
    Project after = window_.document().snapshot();
    after.tour = choice.settings;
    window_.document().undo_stack()->push(new widgets::ReplacePartsCommand(
        window_.document(), QObject::tr("Tour export settings"), after, widgets::kSettingsChanged));
  }
  const std::string out = choice.output.toStdString();
  window_.tasks().start(QObject::tr("Export tour"), export_tour_task(out));
}

ImportTourReaction::ImportTourReaction(QAction* action, MainWindow& window) : Reaction(action, window) {
  connect(&window.tasks(), &widgets::TaskRunner::finished, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::started, this, [this] { update_enabled(); });
  update_enabled();
}

void ImportTourReaction::update_enabled() { action()->setEnabled(!window_.tasks().is_running()); }

void ImportTourReaction::on_triggered() {
  if (!window_.maybe_save()) return;
  const QString package = window_.ask_tour_package();
  if (package.isEmpty()) return;
  QFileInfo info(package);
  // A tour.json names its folder; a zip is named for itself.
  const QString stem =
      info.fileName() == "tour.json" ? info.absoluteDir().dirName() : info.completeBaseName();
  const QString file = window_.ask_imported_project(info.absoluteDir().filePath(stem + ".plenopath"));
  if (file.isEmpty()) return;
  if (QFileInfo::exists(file)) {
    window_.show_error(QObject::tr("Import tour"),
                       QObject::tr("%1 already exists: choose a new project name.").arg(file));
    return;
  }
  // The import writes files and a new project; the open document is left as it is until it is done.
  auto summary = std::make_shared<std::string>();
  const TourImportOptions options{package.toStdString(), file.toStdString()};
  const bool started = window_.tasks().start(
      QObject::tr("Import tour"), [options, summary](Project snapshot, Progress& progress) {
        TourImportResult result = import_tour(options, progress);
        progress.throw_if_cancelled();
        save_project(result.project, options.project_file);
        *summary = std::to_string(result.keyframes) + " keyframes, " +
                   std::to_string(result.project.hotspots.size()) + " hotspots";
        for (const std::string& w : result.warnings) *summary += "; " + w;
        return widgets::TaskResult{std::move(snapshot), 0};
      });
  if (!started) return;
  auto connection = std::make_shared<QMetaObject::Connection>();
  *connection = connect(
      &window_.tasks(), &widgets::TaskRunner::finished, &window_, [this, file, summary, connection](bool) {
        QObject::disconnect(*connection);
        if (summary->empty()) return;  // failed or cancelled: said by the task runner
        if (window_.open_project(file))
          window_.statusBar()->showMessage(
              QObject::tr("Imported the tour: %1").arg(QString::fromStdString(*summary)), 20000);
      });
}

WalkModeReaction::WalkModeReaction(QAction* action, MainWindow& window) : Reaction(action, window) {
  connect(&window.document(), &widgets::ProjectDocument::changed, this, [this] { update_enabled(); });
  update_enabled();
}

void WalkModeReaction::update_enabled() {
  const Project& p = window_.document().project();
  action()->setEnabled(!p.path.empty() && !p.keyframes.empty());
}

void WalkModeReaction::on_triggered() {
  try {
    auto* walk = new widgets::WalkView(window_.document(), window_.frame_provider());
    walk->setAttribute(Qt::WA_DeleteOnClose);
    walk->setWindowFlag(Qt::Window);
    walk->resize(std::max(800, window_.width() * 3 / 4), std::max(500, window_.height() * 3 / 4));
    walk->show();
    walk->setFocus();
  } catch (const Error& e) {
    window_.show_error(QObject::tr("Walk mode"), QString::fromStdString(e.what()));
  }
}

TrackPathReaction::TrackPathReaction(QAction* action, MainWindow& window) : Reaction(action, window) {
  connect(&window.document(), &widgets::ProjectDocument::changed, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::finished, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::started, this, [this] { update_enabled(); });
  update_enabled();
}

void TrackPathReaction::update_enabled() {
  action()->setEnabled(!window_.tasks().is_running() && !window_.document().project().capture.empty());
}

void TrackPathReaction::on_triggered() {
  if (!window_.document().project().path.empty() &&
      QMessageBox::question(&window_, QObject::tr("Track camera path"),
                            QObject::tr("Replace the current path with one tracked from the frames? "
                                        "(Undo brings the old one back.)")) != QMessageBox::Yes)
    return;
  auto outcome = std::make_shared<PlacementOutcome>();
  if (window_.tasks().start(QObject::tr("Track camera path"), track_path_task(outcome)))
    offer_when_applied(window_, outcome);
}

PlaceStillReaction::PlaceStillReaction(QAction* action, MainWindow& window) : Reaction(action, window) {
  connect(&window.document(), &widgets::ProjectDocument::changed, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::finished, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::started, this, [this] { update_enabled(); });
  connect(window.map_view(), &widgets::MapView::point_picked, this, &PlaceStillReaction::on_point);
  connect(window.map_view(), &widgets::MapView::point_pick_cancelled, this, [this] {
    if (stage_ != Stage::kIdle) finish(QObject::tr("Still placement ended"));
  });
  update_enabled();
}

void PlaceStillReaction::update_enabled() {
  const Project& p = window_.document().project();
  const bool ok = !window_.tasks().is_running() && !p.path.empty() && !p.plan.empty() &&
                  p.capture.kind == CaptureKind::kImageFolder;
  action()->setEnabled(ok);
  action()->setToolTip(p.plan.empty() ? QObject::tr("Import the floor plan first")
                       : p.path.empty()
                           ? QObject::tr("Track the stills first (Process > Track camera path)")
                           : QObject::tr("Place the still on screen by clicking where it was shot"));
}

void PlaceStillReaction::on_triggered() {
  const Project& p = window_.document().project();
  const int position = window_.document().current_position();
  if (position < 0 || position >= static_cast<int>(p.path.size())) return;
  frame_ = p.path.frames[static_cast<std::size_t>(position)].index;
  stage_ = Stage::kSpot;
  const QString name = frame_ < static_cast<int>(p.capture.frame_names.size())
                           ? QString::fromStdString(p.capture.frame_names[static_cast<std::size_t>(frame_)])
                           : QObject::tr("frame %1").arg(frame_);
  window_.map_view()->start_point_pick(
      QObject::tr("Click on the map where %1 was shot (Esc cancels)").arg(name));
}

void PlaceStillReaction::finish(const QString& text) {
  stage_ = Stage::kIdle;
  window_.map_view()->cancel_point_pick();
  if (!text.isEmpty()) window_.statusBar()->showMessage(text, 20000);
}

void PlaceStillReaction::on_point(double x, double y) {
  if (stage_ == Stage::kIdle) return;
  std::optional<double> hint;
  if (stage_ == Stage::kSpot) {
    click_x_ = x;
    click_y_ = y;
  } else {
    if (std::hypot(x - click_x_, y - click_y_) < 1e-3) return finish({});
    hint = std::atan2(y - click_y_, x - click_x_) * 180.0 / M_PI;
  }
  const bool then_direction = stage_ == Stage::kSpot;
  stage_ = Stage::kIdle;
  auto summary = std::make_shared<std::string>();
  if (!window_.tasks().start(QObject::tr("Place still on plan"),
                             place_still_task(frame_, {click_x_, click_y_}, hint, summary)))
    return finish(QObject::tr("Another task is running; wait for it or cancel it first."));
  auto connection = std::make_shared<QMetaObject::Connection>();
  *connection = connect(&window_.tasks(), &widgets::TaskRunner::finished, this,
                        [this, connection, summary, then_direction](bool applied) {
                          QObject::disconnect(*connection);
                          if (!applied) return finish({});
                          const QString text = QString::fromStdString(*summary);
                          if (!then_direction) return finish(text);
                          stage_ = Stage::kDirection;
                          window_.map_view()->start_point_pick(
                              text + QObject::tr(" — if the heading is wrong, click toward where the still's "
                                                 "centre looks; Esc keeps it"));
                        });
}

PlacePathOnPlanReaction::PlacePathOnPlanReaction(QAction* action, MainWindow& window)
    : Reaction(action, window) {
  connect(&window.document(), &widgets::ProjectDocument::changed, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::finished, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::started, this, [this] { update_enabled(); });
  update_enabled();
}

void PlacePathOnPlanReaction::update_enabled() {
  const Project& p = window_.document().project();
  const std::string why = placement_precondition(p);
  action()->setEnabled(!window_.tasks().is_running() && !p.path.empty() && !p.plan.empty());
  // The reason is worth more than a greyed-out item: the status tip says what is missing.
  action()->setToolTip(why.empty() ? QObject::tr("Place the path on the plan by its points on the walls")
                                   : QString::fromStdString(why));
}

void PlacePathOnPlanReaction::on_triggered() {
  auto outcome = std::make_shared<PlacementOutcome>();
  if (window_.tasks().start(QObject::tr("Place path on plan"),
                            place_path_on_plan_task(outcome, window_.document().visibility_index())))
    offer_when_applied(window_, outcome);
}

PreviewCleanPlateReaction::PreviewCleanPlateReaction(QAction* action, MainWindow& window)
    : Reaction(action, window) {
  connect(&window.document(), &widgets::ProjectDocument::changed, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::finished, this, [this] { update_enabled(); });
  connect(&window.tasks(), &widgets::TaskRunner::started, this, [this] { update_enabled(); });
  connect(window.panorama_view(), &widgets::PanoramaView::stroke_painted, this,
          [this](int position, const QImage& mask, int value) { on_stroke(position, mask, value); });
  update_enabled();
}

void PreviewCleanPlateReaction::on_stroke(int position, const QImage& stroke, int value) {
  widgets::ProjectDocument& document = window_.document();
  const int frame = document.frame_index_at(position);
  // The keyframe's edit so far (or none), with the stroke painted in.
  QImage edit(stroke.size(), QImage::Format_Grayscale8);
  edit.fill(0);
  if (const CleanPlateEdit* old = document.project().tour.clean_plate_edit(frame)) {
    const QImage previous(QString::fromStdString(old->mask));
    if (!previous.isNull())
      edit = previous.convertToFormat(QImage::Format_Grayscale8)
                 .scaled(stroke.size(), Qt::IgnoreAspectRatio, Qt::FastTransformation);
  }
  for (int y = 0; y < stroke.height(); ++y) {
    const uchar* painted = stroke.constScanLine(y);
    uchar* out = edit.scanLine(y);
    for (int x = 0; x < stroke.width(); ++x)
      if (painted[x]) out[x] = static_cast<uchar>(value);
  }
  // A new file per stroke, so that undo can go back to the one before.
  const QFileInfo project_file(document.file_name());
  const QDir folder(document.file_name().isEmpty() ? QDir::temp().filePath("plenopath-clean-plates")
                                                   : project_file.absoluteDir().filePath(
                                                         project_file.completeBaseName() + ".clean-plates"));
  QDir().mkpath(folder.path());
  const QString file = folder.filePath(
      QString("k%1_%2.png").arg(frame, 6, 10, QChar('0')).arg(QDateTime::currentMSecsSinceEpoch()));
  if (!edit.save(file)) {
    window_.show_error(QObject::tr("Clean plate"), QObject::tr("Cannot write %1").arg(file));
    return;
  }
  Project after = document.snapshot();
  auto& edits = after.tour.clean_plate_edits;
  edits.erase(
      std::remove_if(edits.begin(), edits.end(), [&](const CleanPlateEdit& e) { return e.frame == frame; }),
      edits.end());
  edits.push_back({frame, file.toStdString()});
  document.undo_stack()->push(new widgets::ReplacePartsCommand(document,
                                                               value == kCleanPlateKeep
                                                                   ? QObject::tr("Paint clean plate back")
                                                                   : QObject::tr("Paint clean plate away"),
                                                               after, widgets::kSettingsChanged));
  on_triggered();  // the preview again, with the edit
}

void PreviewCleanPlateReaction::update_enabled() {
  const Project& p = window_.document().project();
  action()->setEnabled(!p.path.empty() && !p.capture.empty() && !window_.tasks().is_running());
}

void PreviewCleanPlateReaction::on_triggered() {
  const int position = window_.document().current_position();
  if (position < 0) return;
  const int frame = window_.document().frame_index_at(position);
  struct Preview {
    QImage image;
    QString label;
  };
  auto preview = std::make_shared<Preview>();
  const bool started = window_.tasks().start(
      QObject::tr("Preview clean plate"), [frame, preview](Project snapshot, Progress& progress) {
        KeyframeCleaning cleaning = KeyframeCleaning::from_project(snapshot);
        cleaning.clean_plates = true;  // the preview shows what the option would do
        SubProgress opening(progress, 0.0, 0.15, "finding the rig");
        KeyframeCleaner cleaner(snapshot, cleaning, opening);
        SubProgress cleaning_progress(progress, 0.15, 1.0, "clean plate of frame " + std::to_string(frame));
        const CleanedKeyframe cleaned = cleaner.clean(frame, cleaning_progress);
        cv::Mat rgb;
        cv::cvtColor(cleaned.image, rgb, cv::COLOR_BGR2RGB);
        preview->image =
            QImage(rgb.data, rgb.cols, rgb.rows, static_cast<int>(rgb.step), QImage::Format_RGB888).copy();
        QString label =
            QObject::tr("Clean plate · %1 % replaced").arg(100 * cleaned.plate.moving_share, 0, 'f', 1);
        if (!cleaner.rig_mask().empty() || !cleaned.plate.rig_filled.empty())
          label +=
              QObject::tr(" · rig %1 % filled").arg(100 * (1 - cleaned.plate.rig_unfilled_share), 0, 'f', 0);
        if (cleaning.blur_faces) label += QObject::tr(" · %n face(s) blurred", nullptr, cleaned.faces);
        preview->label = label;
        progress.report(1.0, label.toStdString());
        return widgets::TaskResult{std::move(snapshot), 0};  // a preview changes nothing in the document
      });
  if (!started) return;
  auto connection = std::make_shared<QMetaObject::Connection>();
  *connection =
      connect(&window_.tasks(), &widgets::TaskRunner::finished, this, [this, preview, position, connection] {
        QObject::disconnect(*connection);
        if (preview->image.isNull()) return;  // failed or cancelled: the runner said so
        window_.panorama_view()->set_comparison(position, preview->image, preview->label);
      });
}

RecentFilesMenu::RecentFilesMenu(QMenu* menu, MainWindow& window)
    : QObject(menu), menu_(menu), window_(window) {
  connect(menu_, &QMenu::aboutToShow, this, &RecentFilesMenu::refill);
  refill();
}

QStringList RecentFilesMenu::files() { return QSettings().value("recent_files").toStringList(); }

void RecentFilesMenu::add(const QString& file) {
  QStringList list = files();
  const QString absolute = QFileInfo(file).absoluteFilePath();
  list.removeAll(absolute);
  list.prepend(absolute);
  while (list.size() > 10) list.removeLast();
  QSettings().setValue("recent_files", list);
}

void RecentFilesMenu::refill() {
  menu_->clear();
  const QStringList list = files();
  for (const QString& file : list) {
    QAction* a = menu_->addAction(QFileInfo(file).fileName(), this, [this, file] {
      if (window_.maybe_save()) window_.open_project(file);
    });
    a->setToolTip(file);
    a->setEnabled(QFileInfo::exists(file));
  }
  if (list.isEmpty()) menu_->addAction(tr("(none)"))->setEnabled(false);
}

}  // namespace plenopath::studio
