#pragma once
// The open document: one Project, its file name, its undo stack and the view state every panel shares
// (current frame, look direction). Edits go through QUndoCommands (widgets/document_commands.h) that call
// modify(); views listen to `changed(flags)`, which is emitted once per batch of model changes.
#include <QObject>
#include <QString>
#include <atomic>
#include <functional>
#include <memory>

#include "model/project.h"
#include "processing/pipeline/project_parts.h"

class QUndoStack;

namespace plenopath {
class SharedVisibilityIndex;
}

namespace plenopath::widgets {

// What part of the project changed, so views redraw only what they must: the pipeline's ProjectPart
// (processing/pipeline/project_parts.h), the one definition.
using ChangeFlag = ProjectPart;
using plenopath::kAnchorsChanged;
using plenopath::kCaptureChanged;
using plenopath::kEverythingChanged;
using plenopath::kHotspotsChanged;
using plenopath::kKeyframesChanged;
using plenopath::kPathChanged;
using plenopath::kPlanChanged;
using plenopath::kSettingsChanged;
using plenopath::kVisibilityChanged;

class ProjectDocument : public QObject {
  Q_OBJECT
 public:
  explicit ProjectDocument(QObject* parent = nullptr);
  ~ProjectDocument() override;

  const Project& project() const { return project_; }
  // A copy for a worker thread: the worker never sees the live document.
  Project snapshot() const { return project_; }
  QUndoStack* undo_stack() const { return undo_stack_; }

  // Absolute path of the project file, empty while untitled.
  const QString& file_name() const { return file_name_; }
  bool is_modified() const;

  // Replaces the document (new, opened or recovered project): clears the undo stack, resets the view state.
  void reset(Project project, const QString& file_name);
  // Loads / saves a project file; throws plenopath::Error naming the file. save() marks the stack clean.
  // The tracker's points (Project::path_points) go to and come from the sidecar PROJECT.points.json: a
  // sidecar that cannot be read does not stop the load; load_warning() then says why the points are missing.
  void load(const QString& file);
  void save(const QString& file);
  const QString& load_warning() const { return load_warning_; }

  // The one way undo commands change the project. Emits changed(flags) now, or at the end of the
  // outermost batch.
  void modify(const std::function<void(Project&)>& edit, unsigned flags);
  // Batches: changes made between begin_batch() and end_batch() produce one notification.
  void begin_batch();
  void end_batch();

  // ---- the plan's visibility index, one per plan revision, shared by everything that needs it (the map's
  // envelopes, the timeline's profile, the cells that follow an anchor edit).
  // Counts the plan's changes (kPlanChanged, a new document).
  unsigned plan_revision() const { return plan_revision_; }
  // The index of the present plan: the same object until the plan changes, built by the first get()
  // (processing/visibility/shared_visibility_index.h). Call this on the GUI thread and hand the pointer
  // to the worker, which calls get(): it never touches the document.
  std::shared_ptr<const SharedVisibilityIndex> visibility_index();
  // How many visibility indexes of the document's plans were built (tests).
  int visibility_index_builds() const { return index_builds_->load(); }

  // ---- frames: a "position" is an index into path.frames (or into the capture when there is no path).
  int frame_count() const;
  // Capture index of the frame at `position` (path.frames[position].index), or position itself.
  int frame_index_at(int position) const;
  // Position of the frame with capture index `frame_index`, or -1.
  int position_of_frame_index(int frame_index) const;

  int current_position() const { return current_position_; }
  void set_current_position(int position);  // clamped; emits current_position_changed when it moves
  void step(int delta) { set_current_position(current_position_ + delta); }

  // Where the panorama view looks (radians): azimuth relative to the frame's heading, and the horizontal
  // field of view. The map draws it as the view cone.
  double look_azimuth() const { return look_azimuth_; }
  double look_fov() const { return look_fov_; }
  void set_look(double azimuth, double fov);

 signals:
  void changed(unsigned flags);
  void current_position_changed(int position);
  void look_changed();
  void file_name_changed(const QString& file);
  void modified_changed(bool modified);

 private:
  Project project_;
  QString file_name_;
  QString load_warning_;
  QUndoStack* undo_stack_;
  unsigned plan_revision_ = 0;
  std::shared_ptr<const SharedVisibilityIndex> visibility_index_;  // of plan_revision_, or null
  std::shared_ptr<std::atomic<int>> index_builds_ = std::make_shared<std::atomic<int>>(0);
  int batch_depth_ = 0;
  unsigned pending_flags_ = 0;
  int current_position_ = 0;
  double look_azimuth_ = 0.0;
  double look_fov_ = 1.5707963267948966;
};

// RAII batch: one `changed` for everything done in its scope.
class ChangeBatch {
 public:
  explicit ChangeBatch(ProjectDocument& document) : document_(document) { document_.begin_batch(); }
  ~ChangeBatch() { document_.end_batch(); }
  ChangeBatch(const ChangeBatch&) = delete;
  ChangeBatch& operator=(const ChangeBatch&) = delete;

 private:
  ProjectDocument& document_;
};

}  // namespace plenopath::widgets
