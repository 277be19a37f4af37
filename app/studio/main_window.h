#pragma once
// The studio's main window: the map and the panorama side by side, docks for the timeline, sampling, layers
// and history, menus and a toolbar built from small reaction classes (app/studio/reactions.h), a status bar
// with the background task's progress and Cancel. It owns the document, the task runner and autosave.
#include <QMainWindow>
#include <QMessageBox>
#include <functional>

#include "model/tour_settings.h"

class QLabel;
class QProgressBar;
class QToolButton;

namespace plenopath::widgets {
class AnchorsPanel;
class FrameProvider;
class HotspotsPanel;
class LayersPanel;
class MapView;
class PanoramaView;
class ProjectDocument;
class SamplingPanel;
class TaskRunner;
class TimelinePanel;
}  // namespace plenopath::widgets

namespace plenopath::studio {

class Autosave;
class EnvelopeService;
class PlacementService;
class ProfileService;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  // Opens a project file (offering to recover a newer autosave); shows a message and returns false on error.
  bool open_project(const QString& file);
  // Save to the current file (Save As when untitled); false when cancelled or failed (message shown).
  bool save_project();
  bool save_project_as();
  bool save_project_to(const QString& file);
  // With unsaved changes: asks Save / Discard / Cancel. True when it is fine to drop the document.
  bool maybe_save();
  // Import dialogs (empty = ask for the file first).
  void import_plan(const QString& dxf_file);
  void import_capture(const QString& folder_or_video, bool stills = false);
  // Offers the autosave of an untitled document left by a crash, if any.
  void offer_untitled_recovery();

  widgets::ProjectDocument& document() const { return *document_; }
  widgets::TaskRunner& tasks() const { return *tasks_; }
  Autosave& autosave() const { return *autosave_; }
  widgets::MapView* map_view() const { return map_; }
  widgets::PanoramaView* panorama_view() const { return panorama_; }
  widgets::FrameProvider& frame_provider() const { return *frames_; }
  widgets::SamplingPanel* sampling_panel() const { return sampling_; }
  widgets::TimelinePanel* timeline_panel() const { return timeline_; }
  widgets::AnchorsPanel* anchors_panel() const { return anchors_; }
  widgets::HotspotsPanel* hotspots_panel() const { return hotspots_; }
  EnvelopeService* envelopes() const { return envelopes_; }
  ProfileService* profiles() const { return profiles_; }
  PlacementService& placement() const { return *placement_; }

  // Questions the window asks; tests replace them with fixed answers.
  std::function<bool(const QString& autosave_file)> ask_recovery;
  std::function<QMessageBox::StandardButton()> ask_save_changes;
  // File > Export tour: where to (a folder, or a file ending in .zip; empty = cancelled) and the tour
  // settings to export with (the Export tour dialog).
  struct ExportChoice {
    QString output;
    TourSettings settings;
  };
  std::function<ExportChoice(const QString& suggested, const TourSettings& current)> ask_export;
  // File > Import tour: the package (a tour.json or a .zip; empty = cancelled), then the project to make.
  std::function<QString()> ask_tour_package;
  std::function<QString(const QString& suggested)> ask_imported_project;
  // Where errors go (default: a message box).
  std::function<void(const QString& title, const QString& message)> show_error;

 protected:
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  void create_docks();
  void create_actions();
  void update_title();
  void restore_window_state();
  bool recover_autosave_if_wanted(const QString& file);

  widgets::ProjectDocument* document_;
  widgets::TaskRunner* tasks_;
  widgets::FrameProvider* frames_;
  Autosave* autosave_;
  widgets::MapView* map_ = nullptr;
  widgets::PanoramaView* panorama_ = nullptr;
  widgets::TimelinePanel* timeline_ = nullptr;
  widgets::SamplingPanel* sampling_ = nullptr;
  widgets::LayersPanel* layers_ = nullptr;
  widgets::AnchorsPanel* anchors_ = nullptr;
  widgets::HotspotsPanel* hotspots_ = nullptr;
  EnvelopeService* envelopes_ = nullptr;
  ProfileService* profiles_ = nullptr;
  PlacementService* placement_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QToolButton* cancel_ = nullptr;
  QLabel* task_label_ = nullptr;
};

}  // namespace plenopath::studio
