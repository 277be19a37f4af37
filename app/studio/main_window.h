#pragma once
// The studio's main window. Thin: actions live in small classes, views in widgets/.
#include <QMainWindow>
#include <memory>

#include "model/project.h"

class QLabel;

namespace plenopath::studio {

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  // Opens a project file; shows a message box (and returns false) on error.
  bool open_project(const QString& file);
  const Project& project() const { return project_; }

 private:
  void create_actions();
  void update_title();
  void show_summary();

  Project project_;
  QString project_file_;
  QLabel* summary_ = nullptr;
};

}  // namespace plenopath::studio
