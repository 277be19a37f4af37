#pragma once
// Autosave: every few minutes, a modified document is written to a side file next to the project
// (FILE.plenopath.autosave; untitled documents go to the application data folder), atomically. Saving or
// closing cleanly removes it; finding one newer than the project at open time means the editor crashed,
// and the main window offers to recover it.
#include <QObject>
#include <QString>

#include "model/project.h"

class QTimer;

namespace plenopath::widgets {
class ProjectDocument;
}

namespace plenopath::studio {

class Autosave : public QObject {
  Q_OBJECT
 public:
  Autosave(widgets::ProjectDocument& document, int interval_ms, QObject* parent = nullptr);

  // The side file of a project file ("" = untitled).
  static QString side_file(const QString& project_file);
  // An autosave that is newer than the project file (or exists at all, for untitled): worth recovering.
  static bool recovery_available(const QString& project_file);
  // Reads a side file; media paths resolve against the project's folder. Throws plenopath::Error.
  static Project read(const QString& project_file);

  void set_interval(int interval_ms);
  int interval() const;
  // Writes the side file now if the document changed since the last autosave; returns whether it wrote.
  bool write_now();
  // Removes the document's side file (after a save, or when the author discards the changes).
  void discard();
  const QString& last_error() const { return last_error_; }

 signals:
  void written(const QString& side_file);

 private:
  widgets::ProjectDocument& document_;
  QTimer* timer_;
  int saved_index_ = -1;  // undo-stack index at the last autosave
  QString last_error_;
};

}  // namespace plenopath::studio
