#include "app/studio/main_window.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QKeySequence>
#include <QLabel>
#include <QMenuBar>
#include <QMimeData>
#include <QProgressBar>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QSignalBlocker>
#include <QSplitter>
#include <QStatusBar>
#include <QStyle>
#include <QTimer>
#include <QToolBar>
#include <QToolButton>
#include <QUndoStack>
#include <QUndoView>
#include <exception>

#include "app/studio/autosave.h"
#include "app/studio/envelope_service.h"
#include "app/studio/placement_service.h"
#include "app/studio/profile_service.h"
#include "app/studio/reactions.h"
#include "app/studio/refine_anchors_reaction.h"
#include "app/studio/studio_tasks.h"
#include "widgets/anchors_panel.h"
#include "widgets/capture_import_dialog.h"
#include "widgets/clean_plate_box.h"
#include "widgets/document_commands.h"
#include "widgets/dxf_import_dialog.h"
#include "widgets/frame_provider.h"
#include "widgets/hotspot_editor.h"
#include "widgets/hotspots_panel.h"
#include "widgets/layers_panel.h"
#include "widgets/map_view.h"
#include "widgets/panorama_view.h"
#include "widgets/project_document.h"
#include "widgets/sampling_panel.h"
#include "widgets/task_runner.h"
#include "widgets/timeline.h"
#include "widgets/tour_export_dialog.h"

namespace plenopath::studio {

namespace {
constexpr int kDefaultAutosaveMs = 3 * 60 * 1000;

bool is_video(const QString& file) {
  static const QStringList extensions{"mp4", "mov", "mkv", "avi", "m4v", "webm"};
  return extensions.contains(QFileInfo(file).suffix().toLower());
}
}  // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent),
      document_(new widgets::ProjectDocument(this)),
      tasks_(new widgets::TaskRunner(*document_, this)),
      frames_(new widgets::FrameProvider(*document_, this)),
      autosave_(new Autosave(*document_, kDefaultAutosaveMs, this)) {
  setObjectName("main_window");
  ask_recovery = [this](const QString& side) {
    return QMessageBox::question(
               this, tr("Recover unsaved changes?"),
               tr("Plenopath Studio did not close properly. Changes made after the last save "
                  "were autosaved to\n%1\n\nRecover them?")
                   .arg(side),
               QMessageBox::Yes | QMessageBox::No, QMessageBox::Yes) == QMessageBox::Yes;
  };
  ask_save_changes = [this] {
    return QMessageBox::warning(this, tr("Unsaved changes"), tr("Save the changes to this project?"),
                                QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel,
                                QMessageBox::Save);
  };
  show_error = [this](const QString& title, const QString& message) {
    QMessageBox::critical(this, title, message);
  };
  ask_export = [this](const QString& suggested, const TourSettings& current) {
    widgets::TourExportDialog dialog(current, suggested, document_->project().geo.valid, this);
    if (dialog.exec() != QDialog::Accepted) return ExportChoice{};
    return ExportChoice{dialog.output(), dialog.settings()};
  };

  ask_tour_package = [this] {
    return QFileDialog::getOpenFileName(this, tr("Import tour — its tour.json or its .zip"), QString(),
                                        tr("Tours (tour.json *.zip);;All files (*)"));
  };
  ask_imported_project = [this](const QString& suggested) {
    return QFileDialog::getSaveFileName(this, tr("Project to make from the tour"), suggested,
                                        tr("Plenopath project (*.plenopath)"));
  };

  map_ = new widgets::MapView(*document_, this);
  panorama_ = new widgets::PanoramaView(*document_, *frames_, this);
  auto* splitter = new QSplitter(Qt::Horizontal, this);
  splitter->addWidget(map_);
  splitter->addWidget(panorama_);
  splitter->setStretchFactor(0, 11);
  splitter->setStretchFactor(1, 9);
  splitter->setSizes({550, 450});
  setCentralWidget(splitter);
  envelopes_ = new EnvelopeService(*document_, *map_, this);
  connect(map_, &widgets::MapView::message, this,
          [this](const QString& text) { statusBar()->showMessage(text, 6000); });
  placement_ = new PlacementService(*document_, *map_, this);
  connect(placement_, &PlacementService::message, this,
          [this](const QString& text) { statusBar()->showMessage(text, 10000); });

  create_docks();
  create_actions();
  profiles_ = new ProfileService(*document_, *timeline_->strip(), this);

  // Status bar: the running task, its progress and Cancel.
  task_label_ = new QLabel(this);
  progress_ = new QProgressBar(this);
  progress_->setRange(0, 1000);
  progress_->setMaximumWidth(220);
  cancel_ = new QToolButton(this);
  cancel_->setText(tr("Cancel"));
  cancel_->setToolTip(tr("Stop the running task; the document stays as it was"));
  statusBar()->addPermanentWidget(task_label_);
  statusBar()->addPermanentWidget(progress_);
  statusBar()->addPermanentWidget(cancel_);
  for (QWidget* w :
       {static_cast<QWidget*>(task_label_), static_cast<QWidget*>(progress_), static_cast<QWidget*>(cancel_)})
    w->hide();
  connect(cancel_, &QToolButton::clicked, tasks_, &widgets::TaskRunner::cancel);
  connect(tasks_, &widgets::TaskRunner::started, this, [this](const QString& title) {
    task_label_->setText(title + "…");
    progress_->setValue(0);
    task_label_->show();
    progress_->show();
    cancel_->show();
  });
  connect(tasks_, &widgets::TaskRunner::progress, this, [this](double fraction, const QString& message) {
    progress_->setValue(static_cast<int>(fraction * 1000));
    if (!message.isEmpty()) statusBar()->showMessage(message);
  });
  connect(tasks_, &widgets::TaskRunner::finished, this, [this](bool applied) {
    task_label_->hide();
    progress_->hide();
    cancel_->hide();
    if (applied) statusBar()->showMessage(tr("Done"), 4000);
  });
  connect(tasks_, &widgets::TaskRunner::failed, this, [this](const QString& title, const QString& message) {
    show_error(tr("%1 failed").arg(title), message);
  });
  // A cancel is what the author asked for: a note in the status bar, never an error.
  connect(tasks_, &widgets::TaskRunner::cancelled, this, [this](const QString& title) {
    statusBar()->showMessage(tr("%1 cancelled; nothing changed").arg(title), 8000);
  });

  connect(document_, &widgets::ProjectDocument::file_name_changed, this, [this] { update_title(); });
  connect(document_, &widgets::ProjectDocument::modified_changed, this, [this] { update_title(); });
  connect(autosave_, &Autosave::written, this,
          [this](const QString& side) { statusBar()->showMessage(tr("Autosaved to %1").arg(side), 3000); });

  setAcceptDrops(true);
  resize(1500, 920);
  restore_window_state();
  update_title();
  statusBar()->showMessage(tr("Ready"));
}

MainWindow::~MainWindow() = default;

void MainWindow::create_docks() {
  auto dock = [this](const QString& title, const QString& name, QWidget* content, Qt::DockWidgetArea area) {
    auto* d = new QDockWidget(title, this);
    d->setObjectName(name);
    d->setWidget(content);
    addDockWidget(area, d);
    return d;
  };
  timeline_ = new widgets::TimelinePanel(*document_, this);
  sampling_ = new widgets::SamplingPanel(*document_, this);
  layers_ = new widgets::LayersPanel(*document_, this);
  auto* history = new QUndoView(document_->undo_stack(), this);
  history->setEmptyLabel(tr("<opened>"));
  dock(tr("Timeline"), "timeline_dock", timeline_, Qt::BottomDockWidgetArea);
  // In a scroll area: the sampling controls and the clean-plate box need not fit a small window.
  auto* sampling_scroll = new QScrollArea(this);
  sampling_scroll->setWidget(sampling_);
  sampling_scroll->setWidgetResizable(true);
  sampling_scroll->setFrameShape(QFrame::NoFrame);
  sampling_scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  // As wide as the panel needs (the dock then is, as before); only the height scrolls.
  sampling_scroll->setMinimumWidth(sampling_->minimumSizeHint().width() +
                                   sampling_scroll->verticalScrollBar()->sizeHint().width());
  QDockWidget* sampling = dock(tr("Sampling"), "sampling_dock", sampling_scroll, Qt::RightDockWidgetArea);
  QDockWidget* layers = dock(tr("Layers"), "layers_dock", layers_, Qt::RightDockWidgetArea);
  QDockWidget* undo = dock(tr("History"), "history_dock", history, Qt::RightDockWidgetArea);
  anchors_ = new widgets::AnchorsPanel(*document_, this);
  QDockWidget* anchors = dock(tr("Anchors"), "anchors_dock", anchors_, Qt::RightDockWidgetArea);
  hotspots_ = new widgets::HotspotsPanel(*document_, panorama_->hotspot_editor(), this);
  QDockWidget* hotspots = dock(tr("Hotspots"), "hotspots_dock", hotspots_, Qt::RightDockWidgetArea);
  tabifyDockWidget(sampling, hotspots);
  connect(&panorama_->hotspot_editor(), &widgets::HotspotEditor::selection_changed, hotspots,
          [hotspots](const QString& id) {
            if (!id.isEmpty()) hotspots->raise();
          });
  tabifyDockWidget(layers, undo);
  tabifyDockWidget(layers, anchors);
  sampling->raise();
  resizeDocks({sampling}, {300}, Qt::Horizontal);
}

void MainWindow::create_actions() {
  QStyle* s = style();
  QMenu* file = menuBar()->addMenu(tr("&File"));
  QAction* new_action = file->addAction(s->standardIcon(QStyle::SP_FileIcon), tr("&New"));
  new_action->setShortcut(QKeySequence::New);
  new NewProjectReaction(new_action, *this);
  QAction* open = file->addAction(s->standardIcon(QStyle::SP_DialogOpenButton), tr("&Open…"));
  open->setShortcut(QKeySequence::Open);
  new OpenProjectReaction(open, *this);
  new RecentFilesMenu(file->addMenu(tr("Open &Recent")), *this);
  QAction* save = file->addAction(s->standardIcon(QStyle::SP_DialogSaveButton), tr("&Save"));
  save->setShortcut(QKeySequence::Save);
  new SaveProjectReaction(save, *this, false);
  QAction* save_as = file->addAction(tr("Save &As…"));
  save_as->setShortcut(QKeySequence::SaveAs);
  new SaveProjectReaction(save_as, *this, true);
  file->addSeparator();
  QAction* import_plan = file->addAction(tr("Import &floor plan (DXF)…"));
  import_plan->setShortcut(tr("Ctrl+Shift+D"));
  new ImportPlanReaction(import_plan, *this);
  QAction* import_capture = file->addAction(tr("Import &capture (folder or video)…"));
  import_capture->setShortcut(tr("Ctrl+Shift+C"));
  new ImportCaptureReaction(import_capture, *this);
  QAction* import_stills = file->addAction(tr("Import &still panoramas (tripod)…"));
  import_stills->setObjectName("import_stills");
  import_stills->setShortcut(tr("Ctrl+Shift+I"));
  new ImportCaptureReaction(import_stills, *this, true);
  QAction* import_path = file->addAction(tr("Import camera &path…"));
  new ImportPathReaction(import_path, *this);
  QAction* import_tour = file->addAction(tr("Import &tour (to edit it again)…"));
  import_tour->setObjectName("import_tour");
  new ImportTourReaction(import_tour, *this);
  QAction* export_tour = file->addAction(tr("&Export tour…"));
  export_tour->setShortcut(tr("Ctrl+Shift+E"));
  new ExportTourReaction(export_tour, *this);
  // Keyframes exported as clean plates (the people who walked through removed): a tour setting of the
  // project, one undo step per toggle.
  QAction* clean_plates = file->addAction(tr("Export Without &People (Clean Plates)"));
  clean_plates->setObjectName("export_clean_plates");
  clean_plates->setCheckable(true);
  clean_plates->setChecked(document_->project().tour.export_clean_plates);
  connect(clean_plates, &QAction::toggled, this, [this](bool on) {
    if (document_->project().tour.export_clean_plates == on) return;
    Project after = document_->snapshot();
    after.tour.export_clean_plates = on;
    document_->undo_stack()->push(new widgets::ReplacePartsCommand(
        *document_, on ? tr("Export clean plates") : tr("Export keyframes as captured"), after,
        widgets::kSettingsChanged));
  });
  connect(document_, &widgets::ProjectDocument::changed, clean_plates, [this, clean_plates] {
    const QSignalBlocker block(clean_plates);
    clean_plates->setChecked(document_->project().tour.export_clean_plates);
  });
  file->addSeparator();
  QAction* quit = file->addAction(tr("&Quit"), this, &QWidget::close);
  quit->setShortcut(QKeySequence::Quit);

  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  QAction* undo = document_->undo_stack()->createUndoAction(this, tr("&Undo"));
  undo->setShortcut(QKeySequence::Undo);
  undo->setIcon(s->standardIcon(QStyle::SP_ArrowBack));
  QAction* redo = document_->undo_stack()->createRedoAction(this, tr("&Redo"));
  redo->setShortcut(QKeySequence::Redo);
  redo->setIcon(s->standardIcon(QStyle::SP_ArrowForward));
  edit->addAction(undo);
  edit->addAction(redo);

  QMenu* view = menuBar()->addMenu(tr("&View"));
  QAction* fit = view->addAction(tr("&Fit map"), this, [this] { map_->reset_camera(); });
  fit->setShortcut(tr("Ctrl+0"));
  QAction* whole = view->addAction(tr("&Whole equirectangular image"));
  whole->setCheckable(true);
  whole->setShortcut(tr("Ctrl+E"));
  connect(whole, &QAction::toggled, panorama_, &widgets::PanoramaView::set_equirect_mode);
  connect(panorama_, &widgets::PanoramaView::equirect_mode_changed, whole, &QAction::setChecked);
  QAction* next = view->addAction(tr("&Next frame"), this, [this] { document_->step(1); });
  next->setShortcut(tr("Ctrl+Right"));
  QAction* previous = view->addAction(tr("&Previous frame"), this, [this] { document_->step(-1); });
  previous->setShortcut(tr("Ctrl+Left"));
  QAction* walk = view->addAction(tr("&Walk mode"));
  walk->setShortcut(tr("F5"));
  new WalkModeReaction(walk, *this);
  view->addSeparator();
  for (QDockWidget* d : findChildren<QDockWidget*>()) view->addAction(d->toggleViewAction());

  // Hotspots: marking modes in the panorama view (checkable: unchecking cancels a half-made one).
  QMenu* hotspot_menu = menuBar()->addMenu(tr("Hot&spots"));
  widgets::HotspotEditor* hotspot_editor = &panorama_->hotspot_editor();
  QAction* new_movie = hotspot_menu->addAction(tr("New &movie texture"));
  new_movie->setShortcut(tr("Ctrl+Shift+M"));
  new_movie->setStatusTip(
      tr("Click four corners of a TV, poster or window in the panorama; it is placed on its wall"));
  QAction* new_event = hotspot_menu->addAction(tr("New &event hotspot"));
  new_event->setShortcut(tr("Ctrl+Shift+H"));
  new_event->setStatusTip(tr("Click four corners (or Shift+click a polygon, Enter) of a region that reacts"));
  for (QAction* a : {new_movie, new_event}) a->setCheckable(true);
  using HotspotMode = widgets::HotspotEditor::Mode;
  connect(new_movie, &QAction::triggered, this, [this, hotspot_editor](bool on) {
    hotspot_editor->set_mode(on ? HotspotMode::kNewMovieTexture : HotspotMode::kIdle);
    panorama_->setFocus();
  });
  connect(new_event, &QAction::triggered, this, [this, hotspot_editor](bool on) {
    hotspot_editor->set_mode(on ? HotspotMode::kNewEvent : HotspotMode::kIdle);
    panorama_->setFocus();
  });
  connect(hotspot_editor, &widgets::HotspotEditor::mode_changed, this,
          [new_movie, new_event](HotspotMode mode) {
            new_movie->setChecked(mode == HotspotMode::kNewMovieTexture);
            new_event->setChecked(mode == HotspotMode::kNewEvent);
          });
  connect(hotspot_editor, &widgets::HotspotEditor::status_message, this, [this](const QString& message) {
    if (message.isEmpty())
      statusBar()->clearMessage();
    else
      statusBar()->showMessage(message, 15000);
  });
  QAction* delete_hotspot = hotspot_menu->addAction(tr("&Delete selected hotspot"), this,
                                                    [hotspot_editor] { hotspot_editor->delete_selected(); });
  delete_hotspot->setStatusTip(tr("Delete in the panorama view does the same"));

  QMenu* process = menuBar()->addMenu(tr("&Process"));
  QAction* render_cg = process->addAction(tr("Render &CG scene…"));
  render_cg->setObjectName("render_cg_scene");
  render_cg->setShortcut(tr("Ctrl+Shift+G"));
  render_cg->setStatusTip(
      tr("Render your POV-Ray scene along the path with the spherical camera, colour and depth, every frame "
         "or online (keyframes only at full size); the frames become the capture"));
  new RenderCgSceneReaction(render_cg, *this);
  process->addSeparator();
  QAction* track = process->addAction(tr("&Track camera path"));
  track->setShortcut(tr("Ctrl+Shift+T"));
  new TrackPathReaction(track, *this);
  QAction* visibility = process->addAction(tr("Compute &visibility"));
  visibility->setShortcut(tr("Ctrl+Shift+V"));
  new ComputeVisibilityReaction(visibility, *this);
  QAction* place = process->addAction(tr("&Place path on plan"));
  place->setShortcut(tr("Ctrl+Shift+P"));
  place->setStatusTip(
      tr("Put the tracked path on the plan by its points on the walls; the runners-up are "
         "drawn as ghosts, click one to take it instead. One undo step"));
  new PlacePathOnPlanReaction(place, *this);
  QAction* place_still = process->addAction(tr("Place still &on plan"));
  place_still->setObjectName("place_still");
  place_still->setShortcut(tr("Ctrl+Shift+O"));
  place_still->setStatusTip(
      tr("Click on the map where the still on screen was shot: its heading and position are found from "
         "the walls; a second click toward where it looks fixes a heading the wrong way round"));
  new PlaceStillReaction(place_still, *this);
  QAction* resample = process->addAction(tr("&Resample keyframes"), this, [this] { sampling_->resample(0); });
  resample->setShortcut(tr("Ctrl+Shift+K"));
  QAction* refine = process->addAction(tr("Refine path with &anchors"));
  refine->setShortcut(tr("Ctrl+Shift+A"));
  refine->setStatusTip(
      tr("Bend the path onto the anchors with the global refinement (Ceres); one undo step"));
  new RefineWithAnchorsReaction(refine, *this);
  anchors_->set_refine_action(refine);
  QAction* preview_clean = process->addAction(tr("Preview &clean plate"));
  preview_clean->setObjectName("preview_clean_plate");
  preview_clean->setShortcut(tr("Ctrl+Shift+L"));
  preview_clean->setStatusTip(
      tr("The frame on screen without the people and the rig, before/after in the panorama: drag the line, "
         "Esc ends it"));
  new PreviewCleanPlateReaction(preview_clean, *this);
  connect(sampling_->clean_plate_box(), &widgets::CleanPlateBox::preview_requested, preview_clean,
          &QAction::trigger);

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("&About"), this, [this] {
    QMessageBox::about(this, tr("About Plenopath Studio"),
                       tr("<b>Plenopath Studio %1</b><br>Walkthrough tours from 360° video along a path "
                          "through a building.<br>GPL-3.0-or-later.")
                           .arg(QApplication::applicationVersion()));
  });

  QToolBar* bar = addToolBar(tr("Main"));
  bar->setObjectName("main_toolbar");
  bar->addAction(open);
  bar->addAction(save);
  bar->addSeparator();
  bar->addAction(undo);
  bar->addAction(redo);
  bar->addSeparator();
  bar->addAction(import_plan);
  bar->addAction(import_capture);
  bar->addAction(visibility);
  bar->addAction(whole);
  bar->addAction(new_movie);
  bar->addAction(new_event);
  bar->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
}

void MainWindow::update_title() {
  const QString name =
      document_->file_name().isEmpty() ? tr("Untitled") : QFileInfo(document_->file_name()).fileName();
  setWindowTitle(tr("%1%2 — Plenopath Studio").arg(name).arg(document_->is_modified() ? "*" : ""));
}

void MainWindow::restore_window_state() {
  QSettings settings;
  restoreGeometry(settings.value("window/geometry").toByteArray());
  restoreState(settings.value("window/state").toByteArray());
}

bool MainWindow::open_project(const QString& file) {
  try {
    document_->load(file);
  } catch (const std::exception& e) {
    show_error(tr("Cannot open project"), QString::fromStdString(e.what()));
    return false;
  }
  RecentFilesMenu::add(document_->file_name());
  recover_autosave_if_wanted(document_->file_name());
  if (!document_->load_warning().isEmpty())
    statusBar()->showMessage(document_->load_warning(), 15000);
  else
    statusBar()->showMessage(tr("Opened %1").arg(document_->file_name()), 5000);
  return true;
}

bool MainWindow::recover_autosave_if_wanted(const QString& file) {
  if (!Autosave::recovery_available(file)) return false;
  if (!ask_recovery(Autosave::side_file(file))) {
    autosave_->discard();
    return false;
  }
  try {
    const Project recovered = Autosave::read(file);
    document_->undo_stack()->push(new widgets::ReplacePartsCommand(
        *document_, tr("Recover autosaved changes"), recovered, widgets::kEverythingChanged));
  } catch (const std::exception& e) {
    show_error(tr("Cannot recover the autosave"), QString::fromStdString(e.what()));
    return false;
  }
  return true;
}

void MainWindow::offer_untitled_recovery() {
  if (document_->file_name().isEmpty()) recover_autosave_if_wanted(QString());
}

bool MainWindow::save_project() {
  if (document_->file_name().isEmpty()) return save_project_as();
  return save_project_to(document_->file_name());
}

bool MainWindow::save_project_as() {
  QString file = QFileDialog::getSaveFileName(this, tr("Save project"), document_->file_name(),
                                              tr("Plenopath projects (*.plenopath)"));
  if (file.isEmpty()) return false;
  if (!file.endsWith(".plenopath")) file += ".plenopath";
  return save_project_to(file);
}

bool MainWindow::save_project_to(const QString& file) {
  const QString old_side = Autosave::side_file(document_->file_name());
  try {
    document_->save(file);
  } catch (const std::exception& e) {
    show_error(tr("Cannot save project"), QString::fromStdString(e.what()));
    return false;
  }
  QFile::remove(old_side);
  autosave_->discard();
  RecentFilesMenu::add(document_->file_name());
  statusBar()->showMessage(tr("Saved %1").arg(document_->file_name()), 4000);
  return true;
}

bool MainWindow::maybe_save() {
  if (!document_->is_modified()) return true;
  switch (ask_save_changes()) {
    case QMessageBox::Save:
      return save_project();
    case QMessageBox::Discard:
      autosave_->discard();
      return true;
    default:
      return false;
  }
}

void MainWindow::import_plan(const QString& dxf_file) {
  widgets::DxfImportDialog dialog(this, dxf_file);
  if (dialog.exec() != QDialog::Accepted) return;
  Project after = document_->snapshot();
  after.plan = dialog.plan();
  document_->undo_stack()->push(
      new widgets::ReplacePartsCommand(*document_, tr("Import floor plan"), after, widgets::kPlanChanged));
  map_->reset_camera();
}

void MainWindow::import_capture(const QString& folder_or_video, bool stills) {
  widgets::CaptureImportDialog dialog(this, folder_or_video, stills);
  if (dialog.exec() != QDialog::Accepted) return;
  const widgets::CaptureImportChoices choices = dialog.choices();
  if (!tasks_->start(choices.stills ? tr("Import still panoramas") : tr("Import capture"),
                     import_capture_task(choices)))
    show_error(tr("Busy"), tr("Another task is running; wait for it or cancel it first."));
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (!maybe_save()) {
    event->ignore();
    return;
  }
  if (tasks_->is_running()) {
    tasks_->cancel();
    tasks_->wait();
  }
  // Closing cleanly: the autosave is not needed any more.
  autosave_->discard();
  QSettings settings;
  settings.setValue("window/geometry", saveGeometry());
  settings.setValue("window/state", saveState());
  event->accept();
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  if (event->mimeData()->hasUrls()) event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  const QList<QUrl> urls = event->mimeData()->urls();
  if (urls.isEmpty()) return;
  const QString file = urls.first().toLocalFile();
  const QFileInfo info(file);
  const QString suffix = info.suffix().toLower();
  event->acceptProposedAction();
  // Dialogs must not run inside the drop handler (the drag source waits): defer them.
  QTimer::singleShot(0, this, [this, file, info, suffix] {
    if (suffix == "plenopath") {
      if (maybe_save()) open_project(file);
    } else if (suffix == "dxf") {
      import_plan(file);
    } else if (info.isDir() || is_video(file)) {
      import_capture(file);
    } else {
      show_error(tr("Cannot open %1").arg(info.fileName()),
                 tr("Drop a .plenopath project, a .dxf plan, a folder of frames or a video."));
    }
  });
}

}  // namespace plenopath::studio
