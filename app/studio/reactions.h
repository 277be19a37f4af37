#pragma once
// One small class per user action (ParaView's pqReaction habit): each owns what its QAction does, so the
// main window only builds menus and docks.
#include <QObject>
#include <QPointer>
#include <QStringList>

#include "widgets/cg_scene_dialog.h"

class QAction;
class QMenu;

namespace plenopath::studio {

class MainWindow;

class Reaction : public QObject {
  Q_OBJECT
 public:
  Reaction(QAction* action, MainWindow& window);
  QAction* action() const { return action_; }

 protected:
  virtual void on_triggered() = 0;
  MainWindow& window_;

 private:
  QAction* action_;
};

class NewProjectReaction : public Reaction {
 public:
  using Reaction::Reaction;
  void on_triggered() override;
};

class OpenProjectReaction : public Reaction {
 public:
  using Reaction::Reaction;
  void on_triggered() override;
};

class SaveProjectReaction : public Reaction {
 public:
  SaveProjectReaction(QAction* action, MainWindow& window, bool save_as);
  void on_triggered() override;

 private:
  bool save_as_;
};

class ImportPlanReaction : public Reaction {
 public:
  using Reaction::Reaction;
  void on_triggered() override;
};

// File > Import capture, or (stills) File > Import still panoramas: the same dialog, its stills box ticked.
class ImportCaptureReaction : public Reaction {
 public:
  ImportCaptureReaction(QAction* action, MainWindow& window, bool stills = false)
      : Reaction(action, window), stills_(stills) {}
  void on_triggered() override;

 private:
  bool stills_;
};

class ImportPathReaction : public Reaction {
 public:
  using Reaction::Reaction;
  void on_triggered() override;
};

// Process > Render CG scene: the CG scene dialog (window-modal; its waypoints can be drawn on the map or
// be the automatic walk), then the render as a task (progress per frame, Cancel kills POV-Ray); the frames
// become the capture and their true poses the path, one undo step.
class RenderCgSceneReaction : public Reaction {
 public:
  RenderCgSceneReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
  QPointer<widgets::CgSceneDialog> dialog_;
};

class ComputeVisibilityReaction : public Reaction {
 public:
  ComputeVisibilityReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
};

// File > Export tour: the packaged walkthrough (folder or .zip) built on a worker with progress and Cancel.
class ExportTourReaction : public Reaction {
 public:
  ExportTourReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
};

// File > Import tour: a published tour (tour.json or .zip) becomes a project again, made and saved on the
// task runner (progress, Cancel), then opened.
class ImportTourReaction : public Reaction {
 public:
  ImportTourReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
};

// View > Walk mode: the tour's experience in a window of its own (widgets/walk_view.h).
class WalkModeReaction : public Reaction {
 public:
  WalkModeReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
};

class TrackPathReaction : public Reaction {
 public:
  TrackPathReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
};

// Process > Place path on plan (placement.h): a task with progress and Cancel, one undo step; the
// candidates go to the window's PlacementService (ghosts on the map).
// Process > Place still on plan (Ctrl+Shift+O): the still on screen placed from where the author clicks on
// the map (processing/stills/still_on_plan.h). Click 1 is the menu, click 2 the spot where it was shot (the
// heading and the position are then found); an optional click 3, toward where the still's centre looks,
// fixes a heading that came out the wrong way round. Each placement is a task and one undo step; Esc ends.
class PlaceStillReaction : public Reaction {
 public:
  PlaceStillReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
  void on_point(double x, double y);
  void finish(const QString& text);

  enum class Stage { kIdle, kSpot, kDirection };
  Stage stage_ = Stage::kIdle;
  int frame_ = -1;                        // capture index of the still being placed
  double click_x_ = 0.0, click_y_ = 0.0;  // the spot clicked
};

class PlacePathOnPlanReaction : public Reaction {
 public:
  PlacePathOnPlanReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
};

// Process > Preview Clean Plate (and the sampling panel's button): the frame on screen as the tour would show
// it with clean plates on (keyframe_cleaner.h, the project's tour settings), a task with progress and Cancel
// that changes nothing; the panorama then shows it before/after, the split dragged, Esc ends it. A stroke
// painted on it (Ctrl+drag away, Ctrl+Shift+drag back) becomes the keyframe's clean-plate edit: a mask
// image beside the project (PROJECT.clean-plates/), one undo step, and the preview is made again.
class PreviewCleanPlateReaction : public Reaction {
 public:
  PreviewCleanPlateReaction(QAction* action, MainWindow& window);
  void on_triggered() override;

 private:
  void update_enabled();
  void on_stroke(int position, const QImage& mask, int value);
};

// The File ▸ Open Recent menu, kept in QSettings ("recent_files").
class RecentFilesMenu : public QObject {
  Q_OBJECT
 public:
  RecentFilesMenu(QMenu* menu, MainWindow& window);
  static void add(const QString& file);
  static QStringList files();

 private:
  void refill();
  QMenu* menu_;
  MainWindow& window_;
};

}  // namespace plenopath::studio
