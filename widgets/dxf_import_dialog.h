#pragma once
// Importing a DXF floor plan: the file, a unit override, the layers with an occluder checkbox each, and a
// preview of the plan as it will be imported (occluders dark and thick).
#include <QDialog>

#include "model/floor_plan.h"

class QComboBox;
class QLabel;
class QLineEdit;
class QTableWidget;

namespace plenopath::widgets {

class PlanPreview;

class DxfImportDialog : public QDialog {
  Q_OBJECT
 public:
  explicit DxfImportDialog(QWidget* parent = nullptr, const QString& file = {});
  // The plan with the chosen units and occluder layers; valid after the dialog was accepted.
  const FloorPlan& plan() const { return plan_; }
  QString file() const;

  void set_file(const QString& file);  // reads it (messages in the dialog, never thrown)

 private:
  void reload();
  void fill_layers();
  void apply_occluders();

  QLineEdit* file_edit_;
  QComboBox* units_;
  QTableWidget* layers_;
  PlanPreview* preview_;
  QLabel* report_;
  FloorPlan plan_;
  bool filling_ = false;
};

// Draws a FloorPlan scaled to fit (used by the DXF dialog).
class PlanPreview : public QWidget {
  Q_OBJECT
 public:
  explicit PlanPreview(QWidget* parent = nullptr);
  void set_plan(const FloorPlan* plan);
  QSize sizeHint() const override { return {360, 260}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  const FloorPlan* plan_ = nullptr;
};

}  // namespace plenopath::widgets
