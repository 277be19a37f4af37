#include "app/studio/autosave.h"

#include <QDateTime>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QStandardPaths>
#include <QTimer>
#include <QUndoStack>
#include <exception>

#include "model/atomic_file.h"
#include "model/json_reader.h"
#include "model/project_io.h"
#include "widgets/project_document.h"

namespace plenopath::studio {

Autosave::Autosave(widgets::ProjectDocument& document, int interval_ms, QObject* parent)
    : QObject(parent), document_(document), timer_(new QTimer(this)) {
  timer_->setInterval(interval_ms);
  connect(timer_, &QTimer::timeout, this, [this] { write_now(); });
  timer_->start();
  // A new document starts from its own state.
  connect(&document_, &widgets::ProjectDocument::file_name_changed, this, [this] { saved_index_ = -1; });
  connect(document_.undo_stack(), &QUndoStack::cleanChanged, this, [this](bool clean) {
    // Back to the saved state (saved, or undone to it): nothing to recover any more.
    if (clean) discard();
  });
}

QString Autosave::side_file(const QString& project_file) {
  if (!project_file.isEmpty()) return project_file + ".autosave";
  const QString folder = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
  return QDir(folder).filePath("untitled.plenopath.autosave");
}

bool Autosave::recovery_available(const QString& project_file) {
  const QFileInfo side(side_file(project_file));
  if (!side.exists()) return false;
  if (project_file.isEmpty()) return true;
  const QFileInfo project(project_file);
  return !project.exists() || side.lastModified() >= project.lastModified();
}

Project Autosave::read(const QString& project_file) {
  const std::string side = side_file(project_file).toStdString();
  const std::string base = project_file.isEmpty() ? QDir::homePath().toStdString()
                                                  : QFileInfo(project_file).absolutePath().toStdString();
  return project_from_json(read_json_file(side), base, side);
}

void Autosave::set_interval(int interval_ms) { timer_->start(interval_ms); }
int Autosave::interval() const { return timer_->interval(); }

bool Autosave::write_now() {
  const int index = document_.undo_stack()->index();
  if (!document_.is_modified() || index == saved_index_) return false;
  const QString file = document_.file_name();
  const QString side = side_file(file);
  const std::string base =
      file.isEmpty() ? QDir::homePath().toStdString() : QFileInfo(file).absolutePath().toStdString();
  try {
    QDir().mkpath(QFileInfo(side).absolutePath());
    write_file_atomically(side.toStdString(),
                          project_to_json(document_.project(), base)
                                  .dump(1, ' ', false, nlohmann::json::error_handler_t::replace) +
                              "\n",
                          false);
  } catch (const std::exception& e) {
    last_error_ = QString::fromStdString(e.what());
    return false;
  }
  last_error_.clear();
  saved_index_ = index;
  emit written(side);
  return true;
}

void Autosave::discard() {
  QFile::remove(side_file(document_.file_name()));
  saved_index_ = document_.undo_stack()->index();
}

}  // namespace plenopath::studio
