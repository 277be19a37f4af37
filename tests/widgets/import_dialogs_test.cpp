// The import dialogs: the DXF dialog lists the plan's layers with occluder checkboxes, applies them, and the
// unit override rescales the plan; the capture dialog hands over what was chosen.
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QSpinBox>
#include <QTableWidget>
#include <gtest/gtest.h>

#include "widgets/capture_import_dialog.h"
#include "widgets/dxf_import_dialog.h"

namespace plenopath {
namespace {

const QString kOfficeDxf = QString(PLENOPATH_SOURCE_DIR) + "/resources/samples/office/office.dxf";

TEST(DxfImportDialog, ListsLayersAppliesOccludersAndUnits) {
  widgets::DxfImportDialog dialog(nullptr, kOfficeDxf);
  const FloorPlan& plan = dialog.plan();
  ASSERT_FALSE(plan.empty()) << "office.dxf did not import";
  auto* table = dialog.findChild<QTableWidget*>();
  ASSERT_NE(table, nullptr);
  ASSERT_EQ(table->rowCount(), static_cast<int>(plan.layers.size()));
  int walls_row = -1;
  for (int row = 0; row < table->rowCount(); ++row)
    if (table->item(row, 0)->text() == "WALLS") walls_row = row;
  ASSERT_GE(walls_row, 0);
  EXPECT_EQ(table->item(walls_row, 2)->checkState(), Qt::Checked) << "walls guessed as occluders";

  // Unticking WALLS makes its segments see-through.
  table->item(walls_row, 2)->setCheckState(Qt::Unchecked);
  EXPECT_FALSE(dialog.plan().find_layer("WALLS")->occluder);
  for (const PlanSegment& s : dialog.plan().segments)
    if (s.layer == "WALLS") {
      EXPECT_FALSE(s.occluder);
    }

  // Overriding the units rescales: the same drawing read as cm is 10 times the size read as mm.
  auto* units = dialog.findChild<QComboBox*>();
  ASSERT_NE(units, nullptr);
  units->setCurrentIndex(units->findData("mm"));
  const Eigen::Vector2d mm = dialog.plan().extents().size();
  units->setCurrentIndex(units->findData("cm"));
  const Eigen::Vector2d cm = dialog.plan().extents().size();
  ASSERT_GT(mm.x(), 0.0);
  EXPECT_NEAR(cm.x() / mm.x(), 10.0, 1e-6);
  EXPECT_NEAR(cm.y() / mm.y(), 10.0, 1e-6);
}

TEST(DxfImportDialog, BadFileIsAMessageNotACrash) {
  widgets::DxfImportDialog dialog(nullptr, "/nonexistent/plan.dxf");
  EXPECT_TRUE(dialog.plan().empty());
  bool shown = false;
  for (QLabel* label : dialog.findChildren<QLabel*>())
    shown = shown || label->text().contains("plan.dxf");
  EXPECT_TRUE(shown);
}

TEST(CaptureImportDialog, HandsOverTheChoices) {
  widgets::CaptureImportDialog dialog(nullptr, "/data/walk.mp4");
  const auto spins = dialog.findChildren<QSpinBox*>();
  ASSERT_EQ(spins.size(), 3);
  spins[0]->setValue(10);  // first
  spins[1]->setValue(90);  // last
  spins[2]->setValue(3);   // stride
  const widgets::CaptureImportChoices c = dialog.choices();
  EXPECT_EQ(c.source, "/data/walk.mp4");
  EXPECT_EQ(c.options.first_frame, 10);
  EXPECT_EQ(c.options.last_frame, 90);
  EXPECT_EQ(c.options.stride, 3);
  EXPECT_DOUBLE_EQ(c.camera_height_m, 1.6);
}

}  // namespace
}  // namespace plenopath
