#pragma once
// The Anchors dock: one row per drift anchor (frame, x, y, heading, residual = how far the path's frame
// is from its anchor, in metres). Frame, x, y and heading are editable (an empty heading leaves it free);
// an edit corrects the path with the anchors like a drag on the map does. Del or the button removes the
// selected anchors (the path stays). Selecting a row goes to that frame. Every edit is one undo step
// (widgets/anchor_commands.h). The "Refine path with anchors" action belongs to the main window; the
// panel shows it as a button.
#include <QWidget>

class QAction;
class QLabel;
class QTableWidget;
class QTableWidgetItem;
class QToolButton;

namespace plenopath::widgets {

class ProjectDocument;

class AnchorsPanel : public QWidget {
  Q_OBJECT
 public:
  enum Column { kFrameColumn = 0, kXColumn, kYColumn, kHeadingColumn, kResidualColumn, kColumnCount };

  explicit AnchorsPanel(ProjectDocument& document, QWidget* parent = nullptr);

  QTableWidget* table() const { return table_; }
  QToolButton* delete_button() const { return delete_; }
  // Shown as a button under the table (the action itself runs the refinement task).
  void set_refine_action(QAction* action);
  // Removes the anchors of the selected rows: one undo step.
  void delete_selected();
  // The line under the table: anchor count, largest residual, or the last problem with an edit.
  QString summary() const;

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void refill();
  void on_item_changed(QTableWidgetItem* item);
  void show_problem(const QString& problem);

  ProjectDocument& document_;
  QTableWidget* table_;
  QLabel* summary_;
  QToolButton* delete_;
  QToolButton* refine_;
  bool filling_ = false;
};

}  // namespace plenopath::widgets
