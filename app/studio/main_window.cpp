#include "app/studio/main_window.h"

#include <QAction>
#include <QApplication>
#include <QFileDialog>
#include <QFileInfo>
#include <QKeySequence>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>

#include "model/error.h"
#include "model/project_io.h"

namespace plenopath::studio {

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  summary_ = new QLabel(this);
  summary_->setAlignment(Qt::AlignCenter);
  summary_->setText(tr("Open a project (Ctrl+O) to begin."));
  setCentralWidget(summary_);
  create_actions();
  update_title();
  resize(1280, 800);
  statusBar()->showMessage(tr("Ready"));
}

MainWindow::~MainWindow() = default;

void MainWindow::create_actions() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  QAction* open = file->addAction(tr("&Open…"), this, [this] {
    const QString f = QFileDialog::getOpenFileName(this, tr("Open project"), QString(),
                                                   tr("Plenopath projects (*.plenopath)"));
    if (!f.isEmpty()) open_project(f);
  });
  open->setShortcut(QKeySequence::Open);
  file->addSeparator();
  QAction* quit = file->addAction(tr("&Quit"), this, &QWidget::close);
  quit->setShortcut(QKeySequence::Quit);
}

bool MainWindow::open_project(const QString& file) {
  try {
    project_ = load_project(file.toStdString());
  } catch (const Error& e) {
    QMessageBox::critical(this, tr("Cannot open project"), QString::fromStdString(e.what()));
    return false;
  }
  project_file_ = QFileInfo(file).absoluteFilePath();
  update_title();
  show_summary();
  statusBar()->showMessage(tr("Opened %1").arg(project_file_), 5000);
  return true;
}

void MainWindow::update_title() {
  const QString name = project_file_.isEmpty() ? tr("Untitled") : QFileInfo(project_file_).fileName();
  setWindowTitle(tr("%1 — Plenopath Studio").arg(name));
}

void MainWindow::show_summary() {
  summary_->setText(tr("<b>%1</b><br>%2 plan segments · %3 frames · %4 keyframes")
                        .arg(QString::fromStdString(project_.tour.title).toHtmlEscaped())
                        .arg(project_.plan.segments.size())
                        .arg(project_.path.size())
                        .arg(project_.keyframes.indices.size()));
}

}  // namespace plenopath::studio
