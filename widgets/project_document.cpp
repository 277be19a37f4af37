#include "widgets/project_document.h"

#include <QFileInfo>
#include <QUndoStack>
#include <algorithm>
#include <filesystem>
#include <utility>

#include "model/error.h"
#include "model/path_points.h"
#include "model/project_io.h"
#include "processing/visibility/shared_visibility_index.h"

namespace plenopath::widgets {

ProjectDocument::ProjectDocument(QObject* parent) : QObject(parent), undo_stack_(new QUndoStack(this)) {
  connect(undo_stack_, &QUndoStack::cleanChanged, this,
          [this](bool clean) { emit modified_changed(!clean); });
}

ProjectDocument::~ProjectDocument() = default;

bool ProjectDocument::is_modified() const { return !undo_stack_->isClean(); }

void ProjectDocument::reset(Project project, const QString& file_name) {
  undo_stack_->clear();
  load_warning_.clear();
  project_ = std::move(project);
  ++plan_revision_;
  visibility_index_.reset();
  file_name_ = file_name.isEmpty() ? QString() : QFileInfo(file_name).absoluteFilePath();
  current_position_ = 0;
  look_azimuth_ = 0.0;
  emit file_name_changed(file_name_);
  emit changed(kEverythingChanged);
  emit current_position_changed(current_position_);
  emit look_changed();
  emit modified_changed(false);
}

void ProjectDocument::load(const QString& file) {
  Project project = load_project(file.toStdString());
  QString warning;
  const std::string points_file = points_file_beside(file.toStdString());
  std::error_code ec;
  if (std::filesystem::exists(points_file, ec)) {
    try {
      project.path_points = read_path_points_file(points_file);
    } catch (const Error& e) {
      warning = QString::fromStdString(
          std::string(e.what()) + " (the tracker's points are not loaded: Place path on plan needs them)");
    }
  }
  reset(std::move(project), file);
  load_warning_ = warning;
}

void ProjectDocument::save(const QString& file) {
  save_project(project_, file.toStdString());
  // The points beside the project; an older sidecar stays when there are none (never delete data).
  if (!project_.path_points.empty())
    write_path_points_file(project_.path_points, points_file_beside(file.toStdString()));
  const QString absolute = QFileInfo(file).absoluteFilePath();
  if (absolute != file_name_) {
    file_name_ = absolute;
    emit file_name_changed(file_name_);
  }
  undo_stack_->setClean();
}

void ProjectDocument::modify(const std::function<void(Project&)>& edit, unsigned flags) {
  edit(project_);
  if (flags & kPlanChanged) {
    ++plan_revision_;
    visibility_index_.reset();  // workers holding the old one keep it alive until they finish
  }
  pending_flags_ |= flags;
  if (batch_depth_ > 0) return;
  const unsigned f = std::exchange(pending_flags_, 0u);
  // The path may have shrunk under the play head.
  if (current_position_ >= frame_count()) set_current_position(frame_count() - 1);
  emit changed(f);
}

std::shared_ptr<const SharedVisibilityIndex> ProjectDocument::visibility_index() {
  if (!visibility_index_)
    visibility_index_ = std::make_shared<const SharedVisibilityIndex>(project_.plan, index_builds_);
  return visibility_index_;
}

void ProjectDocument::begin_batch() { ++batch_depth_; }

void ProjectDocument::end_batch() {
  if (--batch_depth_ > 0 || pending_flags_ == 0) return;
  const unsigned f = std::exchange(pending_flags_, 0u);
  if (current_position_ >= frame_count()) set_current_position(frame_count() - 1);
  emit changed(f);
}

int ProjectDocument::frame_count() const {
  return project_.path.empty() ? project_.capture.frame_count : static_cast<int>(project_.path.size());
}

int ProjectDocument::frame_index_at(int position) const {
  if (!project_.path.empty() && position >= 0 && position < static_cast<int>(project_.path.size()))
    return project_.path.frames[position].index;
  return position;
}

int ProjectDocument::position_of_frame_index(int frame_index) const {
  if (project_.path.empty()) return frame_index >= 0 && frame_index < frame_count() ? frame_index : -1;
  const auto& frames = project_.path.frames;
  auto it = std::lower_bound(frames.begin(), frames.end(), frame_index,
                             [](const PathFrame& f, int i) { return f.index < i; });
  return (it != frames.end() && it->index == frame_index) ? static_cast<int>(it - frames.begin()) : -1;
}

void ProjectDocument::set_current_position(int position) {
  position = std::clamp(position, 0, std::max(0, frame_count() - 1));
  if (position == current_position_) return;
  current_position_ = position;
  emit current_position_changed(position);
}

void ProjectDocument::set_look(double azimuth, double fov) {
  if (azimuth == look_azimuth_ && fov == look_fov_) return;
  look_azimuth_ = azimuth;
  look_fov_ = fov;
  emit look_changed();
}

}  // namespace plenopath::widgets
