// The import dialogs. DXF: the layers table with the importer's proposal and real clicks on its checkboxes,
// the envelope of a clicked point against processing's own envelope and hand-computed areas, units that
// rescale the plan by the unit ratio, the newest of several requests winning, OK/Enter/Esc, the report.
// Capture: the dialog hands over what was chosen.
#include <gtest/gtest.h>

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QStyleOptionViewItem>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QToolButton>
#include <QTreeWidget>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "app/studio/studio_tasks.h"
#include "model/error.h"
#include "processing/visibility/visibility.h"
#include "tests/widgets/test_project.h"
#include "tests/widgets/test_studio.h"
#include "tests/widgets/wait_until.h"
#include "widgets/capture_import_dialog.h"
#include "widgets/dxf_import_dialog.h"
#include "widgets/plan_preview.h"
#include "widgets/project_document.h"

namespace plenopath {
namespace {

using widgets::DxfImportDialog;
using widgets::PlanPreview;

const QString kFixtures = QString(PLENOPATH_SOURCE_DIR) + "/tests/data/dxf/";

// A DXF file written here, in the same plain form as tests/data/dxf/make_dxf.py: header with $INSUNITS,
// a layer table, the entities. Records the line of each entity's "0" tag (for the skipped-entity list).
struct DxfWriter {
  std::vector<std::string> lines;
  std::vector<int> entity_lines;  // 1-based line of each entity's "0" tag, in the order added

  explicit DxfWriter(int insunits, const std::vector<std::string>& layers) {
    add({"0", "SECTION", "2", "HEADER",    "9",  "$ACADVER",
         "1", "AC1015",  "9", "$INSUNITS", "70", std::to_string(insunits),
         "0", "ENDSEC",  "0", "SECTION",   "2",  "TABLES",
         "0", "TABLE",   "2", "LAYER",     "70", std::to_string(layers.size())});
    for (const std::string& name : layers)
      add({"0", "LAYER", "2", name, "70", "0", "62", "7", "6", "CONTINUOUS"});
    add({"0", "ENDTAB", "0", "ENDSEC", "0", "SECTION", "2", "ENTITIES"});
  }
  void add(const std::vector<std::string>& tags) { lines.insert(lines.end(), tags.begin(), tags.end()); }
  void entity(const std::vector<std::string>& tags) {
    entity_lines.push_back(static_cast<int>(lines.size()) + 1);
    add(tags);
  }
  void line(const std::string& layer, double x0, double y0, double x1, double y1) {
    entity({"0", "LINE", "8", layer, "10", num(x0), "20", num(y0), "30", "0", "11", num(x1), "21", num(y1),
            "31", "0"});
  }
  void square(const std::string& layer, double x0, double y0, double side) {
    line(layer, x0, y0, x0 + side, y0);
    line(layer, x0 + side, y0, x0 + side, y0 + side);
    line(layer, x0 + side, y0 + side, x0, y0 + side);
    line(layer, x0, y0 + side, x0, y0);
  }
  static std::string num(double v) { return QString::number(v, 'g', 17).toStdString(); }
  QString write(const QTemporaryDir& dir, const QString& name) const {
    std::string text;
    for (const std::string& l : lines) text += l + "\n";
    text += "0\nENDSEC\n0\nEOF\n";
    const QString path = dir.filePath(name);
    QFile f(path);
    EXPECT_TRUE(f.open(QIODevice::WriteOnly));
    f.write(text.data(), static_cast<qint64>(text.size()));
    return path;
  }
};

// A room on WALLS (metres) with 0.2 m thick walls drawn as two squares, 10 m outside and 9.6 m inside,
// split in two by a single-line partition at x = 5 on PARTITION from the inner wall's face to the other's.
QString write_partitioned_room(const QTemporaryDir& dir) {
  DxfWriter dxf(6, {"WALLS", "PARTITION"});
  dxf.square("WALLS", 0, 0, 10);
  dxf.square("WALLS", 0.2, 0.2, 9.6);
  dxf.line("PARTITION", 5, 0.2, 5, 9.8);
  return dxf.write(dir, "partitioned.dxf");
}

// Opens the dialog on `file`, shows it, and waits for the import to be shown.
struct OpenDialog {
  DxfImportDialog dialog;
  explicit OpenDialog(const QString& file) : dialog(nullptr, file) {
    dialog.show();
    EXPECT_TRUE(QTest::qWaitForWindowExposed(&dialog));
    EXPECT_TRUE(test::wait_until([this] { return !dialog.busy(); })) << "the import did not finish";
  }
  QTableWidget* table() { return dialog.findChild<QTableWidget*>(); }
  PlanPreview* preview() { return dialog.findChild<PlanPreview*>(); }
  QComboBox* units() { return dialog.findChild<QComboBox*>(); }
  QPushButton* ok() {
    for (QPushButton* b : dialog.findChildren<QPushButton*>())
      if (b->isDefault()) return b;
    return nullptr;
  }
  int row_of(const QString& layer) {
    for (int row = 0; row < table()->rowCount(); ++row)
      if (table()->item(row, DxfImportDialog::kLayerColumn)->text() == layer) return row;
    return -1;
  }
  bool ticked(const QString& layer) {
    return table()->item(row_of(layer), DxfImportDialog::kBlocksSightColumn)->checkState() == Qt::Checked;
  }
  // A real click on the layer's "blocks sight" checkbox, where the style draws it.
  void click_blocks_sight(const QString& layer) {
    QTableWidget* t = table();
    QTableWidgetItem* item = t->item(row_of(layer), DxfImportDialog::kBlocksSightColumn);
    QStyleOptionViewItem option;
    option.initFrom(t->viewport());
    option.rect = t->visualItemRect(item);
    option.features = QStyleOptionViewItem::HasCheckIndicator;
    option.checkState = item->checkState();
    const QRect check = t->style()->subElementRect(QStyle::SE_ItemViewItemCheckIndicator, &option, t);
    QTest::mouseClick(t->viewport(), Qt::LeftButton, {}, check.center());
  }
  // A real click on the preview at a plan point; waits for the envelope (or its state) to be shown.
  void click_plan(const Eigen::Vector2d& p) {
    QTest::mouseClick(preview(), Qt::LeftButton, {}, preview()->widget_from_plan(p).toPoint());
    EXPECT_TRUE(test::wait_until([this] { return !dialog.busy(); })) << "the envelope did not arrive";
  }
  bool any_label_contains(const QString& text) {
    for (QLabel* label : dialog.findChildren<QLabel*>())
      if (label->isVisible() && label->text().contains(text)) return true;
    return false;
  }
  void choose_units(const QString& code) {
    QComboBox* combo = units();
    combo->setFocus();
    // Real keys: from the top ("From the file") down to the wanted unit.
    while (combo->currentIndex() > 0) QTest::keyClick(combo, Qt::Key_Up);
    while (combo->currentData().toString() != code && combo->currentIndex() + 1 < combo->count())
      QTest::keyClick(combo, Qt::Key_Down);
    ASSERT_EQ(combo->currentData().toString(), code);
  }
  void wait() {
    EXPECT_TRUE(test::wait_until([this] { return !dialog.busy(); }));
  }
};

// Where a key typed now would go (the dialog itself when nothing has focus, as without a window manager).
QWidget* focused(QWidget& window) {
  QWidget* w = QApplication::focusWidget();
  return w && w->window() == &window ? w : &window;
}

double shoelace_area(const std::vector<Eigen::Vector2d>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::abs(twice);
}

int occluders_on(const FloorPlan& plan, const std::string& layer) {
  int n = 0;
  for (const PlanSegment& s : plan.segments) n += s.layer == layer && s.occluder;
  return n;
}

TEST(DxfImportDialog, ProposalTicksTheWallLayersAndClicksToggleTheOccluders) {
  OpenDialog d(kFixtures + "lines_mm.dxf");
  const FloorPlan& plan = d.dialog.plan();
  ASSERT_FALSE(plan.empty()) << "lines_mm.dxf did not import";
  ASSERT_EQ(d.table()->rowCount(), static_cast<int>(plan.layers.size()));
  ASSERT_GE(d.row_of("WALLS"), 0);
  ASSERT_GE(d.row_of("FURNITURE"), 0);
  EXPECT_TRUE(d.ticked("WALLS")) << "the wall layer is proposed as blocking sight";
  EXPECT_FALSE(d.ticked("FURNITURE"));
  // The fixture's square: 4 wall segments once the duplicate and the zero-length line are dropped.
  EXPECT_EQ(occluders_on(plan, "WALLS"), 4);
  EXPECT_EQ(occluders_on(plan, "FURNITURE"), 0);
  EXPECT_TRUE(d.ok()->isEnabled());
  // HIDDEN is off in the file (negative colour).
  ASSERT_GE(d.row_of("HIDDEN"), 0);
  EXPECT_EQ(d.table()->item(d.row_of("HIDDEN"), DxfImportDialog::kStateColumn)->text(), "off");

  // Unticking WALLS: no segment blocks sight, and OK says why it is off.
  d.click_blocks_sight("WALLS");
  EXPECT_FALSE(d.ticked("WALLS"));
  EXPECT_FALSE(plan.find_layer("WALLS")->occluder);
  EXPECT_EQ(occluders_on(plan, "WALLS"), 0);
  EXPECT_TRUE(plan.occluder_segments().empty());
  EXPECT_FALSE(d.ok()->isEnabled());
  EXPECT_TRUE(d.any_label_contains("No layer blocks sight: tick the wall layers"));

  // Ticking FURNITURE: its one segment blocks sight and OK comes back.
  d.click_blocks_sight("FURNITURE");
  EXPECT_EQ(occluders_on(plan, "FURNITURE"), 1);
  EXPECT_TRUE(d.ok()->isEnabled());
  d.click_blocks_sight("WALLS");
  EXPECT_EQ(occluders_on(plan, "WALLS"), 4);
}

TEST(DxfImportDialog, BlockColumnsAreProposedAndCanBeUnticked) {
  OpenDialog d(kFixtures + "blocks_in.dxf");
  const FloorPlan& plan = d.dialog.plan();
  ASSERT_GE(d.row_of("COLUMNS"), 0);
  EXPECT_TRUE(d.ticked("COLUMNS"));
  // 3 x 2 array of COL, each one line plus one nested TICK line, all inheriting COLUMNS from layer 0.
  EXPECT_EQ(occluders_on(plan, "COLUMNS"), 12);
  d.click_blocks_sight("COLUMNS");
  EXPECT_EQ(occluders_on(plan, "COLUMNS"), 0);
  EXPECT_FALSE(d.ok()->isEnabled());
}

TEST(DxfImportDialog, ClickedPointShowsItsEnvelopeLiveWithTheLayers) {
  QTemporaryDir dir;
  OpenDialog d(write_partitioned_room(dir));
  const FloorPlan& plan = d.dialog.plan();
  ASSERT_FALSE(plan.empty());
  ASSERT_TRUE(d.ticked("WALLS"));
  const bool partition_blocks = d.ticked("PARTITION");

  // Seen from (2.5, 4) in the left half: the whole 9.6 x 9.6 m room, or its 4.8 x 9.6 m half behind the
  // partition.
  d.click_plan({2.5, 4.0});
  PlanPreview* preview = d.preview();
  ASSERT_TRUE(preview->marked_point().has_value());
  const Eigen::Vector2d p = *preview->marked_point();
  EXPECT_LT((p - Eigen::Vector2d(2.5, 4.0)).norm(), 1.5 / preview->pixels_per_metre())
      << "click lands on the point";
  auto check_envelope = [&](double hand_area) {
    ASSERT_GE(preview->envelope().size(), 3u) << preview->note().toStdString();
    const double shown = shoelace_area(preview->envelope());
    const Envelope direct = VisibilityIndex(plan).envelope(p);  // processing, straight on the dialog's plan
    ASSERT_EQ(direct.status, EnvelopeStatus::ok);
    EXPECT_NEAR(shown, direct.area, 1e-9);
    EXPECT_NEAR(shown, hand_area, 1e-3);
    EXPECT_TRUE(preview->note().contains("m²")) << preview->note().toStdString();
  };
  const double half = 4.8 * 9.6, whole = 9.6 * 9.6;
  check_envelope(partition_blocks ? half : whole);

  // Toggling the partition recomputes the envelope at once (no re-import, the same point).
  d.click_blocks_sight("PARTITION");
  d.wait();
  EXPECT_EQ(d.ticked("PARTITION"), !partition_blocks);
  EXPECT_EQ(occluders_on(plan, "PARTITION"), partition_blocks ? 0 : 1);
  check_envelope(partition_blocks ? whole : half);
  d.click_blocks_sight("PARTITION");
  d.wait();
  check_envelope(partition_blocks ? half : whole);

  // Outside the building: no envelope, the state in words.
  d.click_plan({-2.0, 5.0});
  EXPECT_TRUE(preview->envelope().empty());
  EXPECT_TRUE(preview->note().contains("outside the building")) << preview->note().toStdString();
  // In the body of the 0.2 m thick wall.
  d.click_plan({0.1, 5.0});
  EXPECT_TRUE(preview->envelope().empty());
  EXPECT_TRUE(preview->note().contains("on a wall")) << preview->note().toStdString();

  // No layer blocks sight: said so, nothing drawn.
  d.click_plan({7.5, 5.0});
  EXPECT_FALSE(preview->envelope().empty());
  d.click_blocks_sight("WALLS");
  if (d.ticked("PARTITION")) d.click_blocks_sight("PARTITION");
  d.wait();
  EXPECT_TRUE(preview->envelope().empty());
  EXPECT_TRUE(preview->note().contains("No layer blocks sight")) << preview->note().toStdString();
}

TEST(DxfImportDialog, UnitsRescaleThePlanByTheUnitRatio) {
  OpenDialog d(kFixtures + "lines_mm.dxf");
  // The fixture is a 10 000 x 10 000 unit square with $INSUNITS = 4 (mm).
  EXPECT_TRUE(d.units()->itemText(0).contains("mm")) << d.units()->itemText(0).toStdString();
  const Eigen::Vector2d from_file = d.dialog.plan().extents().size();
  EXPECT_NEAR(from_file.x(), 10.0, 1e-9);
  EXPECT_NEAR(from_file.y(), 10.0, 1e-9);
  // A point marked in the room stays on the same spot of the drawing when the units change.
  d.click_plan({3.0, 4.0});
  const Eigen::Vector2d marked = *d.preview()->marked_point();

  d.choose_units("cm");
  d.wait();
  EXPECT_NEAR(d.dialog.plan().extents().size().x(), 100.0, 1e-9);  // 10 000 cm
  EXPECT_NEAR(d.dialog.plan().extents().size().y(), 100.0, 1e-9);
  EXPECT_EQ(d.dialog.plan().units, "cm");
  ASSERT_TRUE(d.preview()->marked_point().has_value());
  EXPECT_NEAR((*d.preview()->marked_point() - 10.0 * marked).norm(), 0.0, 1e-9);
  EXPECT_NEAR(shoelace_area(d.preview()->envelope()), 100.0 * 100.0, 1e-3)
      << "the envelope follows the units";

  d.choose_units("ft");
  d.wait();
  EXPECT_NEAR(d.dialog.plan().extents().size().x(), 10000 * 0.3048, 1e-6);
  EXPECT_NEAR(d.dialog.plan().metres_per_unit, 0.3048, 1e-12);

  // Back to what the file says.
  d.units()->setFocus();
  while (d.units()->currentIndex() > 0) QTest::keyClick(d.units(), Qt::Key_Up);
  d.wait();
  EXPECT_NEAR(d.dialog.plan().extents().size().x(), 10.0, 1e-9);
}

TEST(DxfImportDialog, TheNewestOfSeveralRequestsWins) {
  OpenDialog d(kFixtures + "lines_mm.dxf");
  QComboBox* combo = d.units();
  combo->setFocus();
  // Four unit changes faster than the imports: only the last one may end up in the plan.
  for (const char* code : {"m", "in", "cm", "dm"}) {
    combo->setCurrentIndex(combo->findData(QString(code)));
    EXPECT_FALSE(d.ok()->isEnabled()) << "no OK while the plan is being read";
  }
  d.wait();
  EXPECT_EQ(d.dialog.plan().units, "dm");
  EXPECT_NEAR(d.dialog.plan().extents().size().x(), 1000.0, 1e-9);  // 10 000 dm
  EXPECT_TRUE(d.ok()->isEnabled());
}

TEST(DxfImportDialog, AuthorsTicksSurviveAUnitChange) {
  QTemporaryDir dir;
  OpenDialog d(write_partitioned_room(dir));
  const bool partition_blocks = d.ticked("PARTITION");
  d.click_blocks_sight("PARTITION");
  d.choose_units("mm");
  d.wait();
  EXPECT_EQ(d.ticked("PARTITION"), !partition_blocks);
  EXPECT_EQ(occluders_on(d.dialog.plan(), "PARTITION"), partition_blocks ? 0 : 1);
}

TEST(DxfImportDialog, EnterAcceptsOnlyAPlanWithWallsAndEscCancels) {
  {
    OpenDialog d(kFixtures + "lines_mm.dxf");
    QApplication::setActiveWindow(&d.dialog);
    d.table()->setFocus();
    d.click_blocks_sight("WALLS");  // now nothing blocks sight
    QTest::keyClick(focused(d.dialog), Qt::Key_Return);
    EXPECT_TRUE(d.dialog.isVisible()) << "Enter must not accept a plan without walls";
    d.click_blocks_sight("WALLS");
    QTest::keyClick(focused(d.dialog), Qt::Key_Return);
    EXPECT_FALSE(d.dialog.isVisible());
    EXPECT_EQ(d.dialog.result(), QDialog::Accepted);
    EXPECT_EQ(d.dialog.file(), kFixtures + "lines_mm.dxf");
    EXPECT_EQ(d.dialog.plan().occluder_segments().size(), 4u);
  }
  {
    OpenDialog d(kFixtures + "lines_mm.dxf");
    QApplication::setActiveWindow(&d.dialog);
    QTest::keyClick(&d.dialog, Qt::Key_Escape);
    EXPECT_FALSE(d.dialog.isVisible());
    EXPECT_EQ(d.dialog.result(), QDialog::Rejected);
  }
}

TEST(DxfImportDialog, TypingAFileNameReadsItOnEnterInsteadOfAccepting) {
  OpenDialog d(kFixtures + "lines_mm.dxf");
  QApplication::setActiveWindow(&d.dialog);
  auto* edit = d.dialog.findChild<QLineEdit*>();
  ASSERT_NE(edit, nullptr);
  edit->setFocus();
  edit->selectAll();
  QTest::keyClicks(edit, kFixtures + "feet.dxf");
  EXPECT_FALSE(d.ok()->isEnabled()) << "the plan shown is not the file typed";
  QTest::keyClick(edit, Qt::Key_Return);
  EXPECT_TRUE(d.dialog.isVisible()) << "Enter read the file instead of accepting the old plan";
  d.wait();
  EXPECT_EQ(d.dialog.plan().units, "ft");
  EXPECT_NEAR(d.dialog.plan().extents().size().x(), 3.048, 1e-9);  // a 10 ft wall
  EXPECT_TRUE(d.ok()->isEnabled());
}

TEST(DxfImportDialog, BadFileIsAMessageNotACrash) {
  OpenDialog d("/nonexistent/plan.dxf");
  EXPECT_TRUE(d.dialog.plan().empty());
  EXPECT_TRUE(d.any_label_contains("Cannot read the plan"));
  EXPECT_TRUE(d.any_label_contains("plan.dxf"));
  EXPECT_FALSE(d.ok()->isEnabled());
  // Not a DXF at all, and a file cut in half: messages too.
  for (const char* name : {"binary.dxf", "truncated.dxf", "no_geometry.dxf"}) {
    d.dialog.set_file(kFixtures + name);
    d.wait();
    if (d.dialog.plan().empty()) {
      EXPECT_TRUE(d.any_label_contains("Cannot read the plan") || d.any_label_contains("no plan geometry"))
          << name;
      EXPECT_FALSE(d.ok()->isEnabled()) << name;
    }
  }
}

TEST(DxfImportDialog, ReportSummaryListsSkippedEntitiesWithTheirLines) {
  QTemporaryDir dir;
  DxfWriter dxf(6, {"WALLS", "DIMS"});
  dxf.square("WALLS", 0, 0, 10);
  for (int i = 0; i < 2; ++i)
    dxf.entity({"0", "DIMENSION", "8", "DIMS", "10", "1", "20", "1", "30", "0", "70", "0", "1", "5"});
  const std::vector<int> dimension_lines(dxf.entity_lines.end() - 2, dxf.entity_lines.end());
  OpenDialog d(dxf.write(dir, "dims.dxf"));
  ASSERT_FALSE(d.dialog.plan().empty());
  EXPECT_TRUE(d.any_label_contains("R2000 (AC1015)") || d.dialog.report().version.empty());
  EXPECT_TRUE(d.any_label_contains("ASCII"));
  EXPECT_TRUE(d.any_label_contains("10.0 × 10.0 m"));
  const DxfImportReport& report = d.dialog.report();
  if (report.skipped_by_kind.empty()) GTEST_SKIP() << "the importer does not fill skipped_by_kind yet";
  EXPECT_TRUE(d.any_label_contains("2 DIMENSION skipped"));
  // Details: one row per skipped entity, on the line of its "0" tag.
  auto* details = d.dialog.findChild<QTreeWidget*>();
  ASSERT_NE(details, nullptr);
  ASSERT_EQ(details->topLevelItemCount(), 2);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(details->topLevelItem(i)->text(1), "DIMENSION");
    EXPECT_EQ(details->topLevelItem(i)->text(0).toInt(), dimension_lines[i]);
  }
}

TEST(DxfImportDialog, StrayEntitiesCanBeKept) {
  QTemporaryDir dir;
  DxfWriter dxf(6, {"WALLS"});
  dxf.square("WALLS", 0, 0, 10);
  dxf.square("WALLS", 20, 0, 8);
  dxf.square("WALLS", 0, 20, 6);
  dxf.line("WALLS", 50000, 50000, 50001, 50000);  // 70 km away: a stray (1 of 13 entities)
  OpenDialog d(dxf.write(dir, "stray.dxf"));
  ASSERT_FALSE(d.dialog.plan().empty());
  // The file says metres; chosen explicitly so that the importer's unit inference (which today sees the
  // stray's 50 km extent and proposes mm) does not decide what this test is about.
  d.choose_units("m");
  d.wait();
  auto* keep = d.dialog.findChild<QCheckBox*>();
  ASSERT_NE(keep, nullptr);
  if (d.dialog.report().stray_entities == 0) {
    EXPECT_FALSE(keep->isVisible()) << "nothing to keep";
    GTEST_SKIP() << "the importer does not report stray entities yet";
  }
  EXPECT_TRUE(keep->isVisible());
  EXPECT_TRUE(d.any_label_contains("stray"));
  EXPECT_NEAR(d.dialog.plan().extents().size().x(), 28.0, 1e-9);  // the building: x 0..28, y 0..26
  EXPECT_NEAR(d.dialog.plan().extents().size().y(), 26.0, 1e-9);
  QTest::mouseClick(keep, Qt::LeftButton);
  d.wait();
  EXPECT_TRUE(keep->isChecked());
  EXPECT_NEAR(d.dialog.plan().extents().size().x(), 50001.0, 1e-6);
  EXPECT_NEAR(d.dialog.plan().extents().size().y(), 50000.0, 1e-6);
}

// Renders the dialog offscreen and checks the picture: walls dark and thick where the plan has them, the
// furniture light, the envelope filled. PLENOPATH_DIALOG_PNG=/tmp/x.png also saves it for a look.
TEST(DxfImportDialog, PreviewDrawsThePlanAsImported) {
  OpenDialog d(kFixtures + "lines_mm.dxf");
  d.dialog.resize(1000, 640);
  d.wait();
  d.click_plan({6.0, 6.0});
  PlanPreview* preview = d.preview();
  const QImage image = preview->grab().toImage();
  ASSERT_FALSE(image.isNull());
  auto grey = [&](const Eigen::Vector2d& p) {
    return qGray(image.pixel(preview->widget_from_plan(p).toPoint()));
  };
  EXPECT_LT(grey({5.0, 0.0}), 90) << "a wall is drawn dark";
  EXPECT_GT(grey({2.5, 2.0}), 110) << "furniture is drawn light";
  EXPECT_LT(grey({2.5, 2.0}), 235) << "furniture is drawn";
  const QColor inside = image.pixelColor(preview->widget_from_plan({8.0, 3.0}).toPoint());
  EXPECT_GT(inside.blue(), inside.red() + 20) << "the envelope is filled";
  // Scale bar: the plan is 10 m across a few hundred pixels, so the bar is a whole 1-2-5 number of metres.
  const double bar = preview->scale_bar_metres();
  EXPECT_TRUE(bar == 1.0 || bar == 2.0 || bar == 5.0) << bar;
  if (const char* png = std::getenv("PLENOPATH_DIALOG_PNG")) d.dialog.grab().save(png);
}

// A 2 MB drawing (a 150 m floor of 20 000 lines) is read and its visibility index built on workers: the
// event loop keeps running (no gap near the import's duration), the busy bar shows meanwhile.
TEST(DxfImportDialog, ABigPlanNeverFreezesTheDialog) {
  QTemporaryDir dir;
  DxfWriter dxf(6, {"WALLS", "FURNITURE"});
  dxf.square("WALLS", 0, 0, 150);
  // Cubicles: 0.05 m apart pairs of short partitions and desks, 19 996 lines in all.
  for (int i = 0; i < 9998; ++i) {
    const double x = 1 + (i % 100) * 1.48, y = 1 + (i / 100) * 1.48;
    dxf.line(i % 2 ? "FURNITURE" : "WALLS", x, y, x + 0.6, y);
    dxf.line("FURNITURE", x, y + 0.3, x + 0.6, y + 0.3);
  }
  const QString file = dxf.write(dir, "big.dxf");
  ASSERT_GT(QFileInfo(file).size(), 1500000);

  DxfImportDialog dialog(nullptr, QString());
  dialog.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&dialog));
  auto* busy_bar = dialog.findChild<QProgressBar*>();
  ASSERT_NE(busy_bar, nullptr);
  // The work runs on workers: the call that starts it returns with the dialog busy, and the event loop keeps
  // turning until it is done (its longest pause is printed, not asserted: CI machines are shared).
  auto watch = [&](const char* what) {
    EXPECT_TRUE(dialog.busy()) << what
                               << " ran on the GUI thread: the dialog was idle when the call returned";
    QElapsedTimer total, turn;
    total.start();
    turn.start();
    qint64 longest = 0;
    bool bar_seen = false;
    while (dialog.busy() && total.elapsed() < 60000) {
      QCoreApplication::processEvents(QEventLoop::AllEvents, 5);
      longest = std::max(longest, turn.restart());
      bar_seen = bar_seen || busy_bar->isVisible();
    }
    EXPECT_FALSE(dialog.busy()) << what << " did not finish";
    const qint64 took = total.elapsed();
    if (took > 600) {
      EXPECT_TRUE(bar_seen) << what << " took " << took << " ms without the busy bar";
    }
    std::cerr << what << ": " << took << " ms, longest event-loop pause " << longest << " ms\n";
  };
  dialog.set_file(file);
  watch("import");
  ASSERT_FALSE(dialog.plan().empty());
  EXPECT_NEAR(dialog.plan().extents().size().x(), 150.0, 1e-6);
  auto* preview = dialog.findChild<PlanPreview*>();
  QTest::mouseClick(preview, Qt::LeftButton, {}, preview->widget_from_plan({75.3, 0.5}).toPoint());
  watch("envelope");
  EXPECT_FALSE(preview->envelope().empty()) << preview->note().toStdString();
}

// Every fixture: the dialog either draws the plan (walls as dark pixels in the preview, the layers listed)
// or says why it cannot, naming the file. PLENOPATH_DIALOG_PNG_DIR=/tmp/dir saves each picture for a look.
TEST(DxfImportDialog, EveryFixtureRendersThePlanOrAMessage) {
  const QStringList files = QDir(kFixtures).entryList({"*.dxf"}, QDir::Files, QDir::Name);
  ASSERT_GE(files.size(), 10);
  const char* png_dir = std::getenv("PLENOPATH_DIALOG_PNG_DIR");
  for (const QString& name : files) {
    SCOPED_TRACE(name.toStdString());
    OpenDialog d(kFixtures + name);
    d.dialog.resize(1000, 640);
    QCoreApplication::processEvents();
    const FloorPlan& plan = d.dialog.plan();
    if (plan.empty()) {
      EXPECT_TRUE(d.any_label_contains(name) || d.any_label_contains("no plan geometry"));
      EXPECT_FALSE(d.ok()->isEnabled());
    } else {
      EXPECT_EQ(d.table()->rowCount(), static_cast<int>(plan.layers.size()));
      const QImage image = d.preview()->grab().toImage();
      int dark = 0, light = 0;
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
          const int g = qGray(image.pixel(x, y));
          dark += g < 90;
          light += g > 200;
        }
      if (!plan.occluder_segments().empty()) {
        EXPECT_GT(dark, 100) << "walls drawn";
      }
      EXPECT_GT(light, image.width() * image.height() / 2) << "a readable background";
      // Every column of the layers table is in view: nothing clipped off to the right.
      const QTableWidget* t = d.table();
      int columns = 0;
      for (int c = 0; c < t->columnCount(); ++c) columns += t->columnWidth(c);
      EXPECT_LE(columns, t->viewport()->width() + 1);
    }
    if (png_dir) d.dialog.grab().save(QString(png_dir) + "/" + QFileInfo(name).baseName() + ".png");
    // The details, opened with a real click, list what the summary counts.
    auto* details = d.dialog.findChild<QToolButton*>();
    ASSERT_NE(details, nullptr);
    if (details->isEnabled()) {
      QTest::mouseClick(details, Qt::LeftButton);
      QCoreApplication::processEvents();
      auto* skipped = d.dialog.findChild<QTreeWidget*>();
      EXPECT_EQ(skipped->topLevelItemCount(), static_cast<int>(d.dialog.report().skipped.size()));
      if (png_dir) d.dialog.grab().save(QString(png_dir) + "/" + QFileInfo(name).baseName() + "_details.png");
    }
  }
}

// The studio takes the dialog's plan (File > Import floor plan): the author's ticks reach the document.
TEST(DxfImportDialog, TheStudioImportsWhatTheDialogShows) {
  test::TestStudio s;
  bool clicked = false;
  QTimer poll;
  QObject::connect(&poll, &QTimer::timeout, [&] {
    auto* dialog = qobject_cast<DxfImportDialog*>(QApplication::activeModalWidget());
    if (!dialog || dialog->busy() || clicked) return;
    clicked = true;
    poll.stop();
    auto* table = dialog->findChild<QTableWidget*>();
    for (int row = 0; row < table->rowCount(); ++row)
      if (table->item(row, DxfImportDialog::kLayerColumn)->text() == "FURNITURE")
        table->item(row, DxfImportDialog::kBlocksSightColumn)->setCheckState(Qt::Checked);
    if (const char* png = std::getenv("PLENOPATH_STUDIO_DIALOG_PNG")) {
      QCoreApplication::processEvents();  // the layout after the tick
      dialog->grab().save(png);
    }
    for (QPushButton* b : dialog->findChildren<QPushButton*>())
      if (b->isDefault()) QTest::mouseClick(b, Qt::LeftButton);
  });
  poll.start(20);
  s.window.import_plan(kFixtures + "lines_mm.dxf");  // returns when the dialog closes
  ASSERT_TRUE(clicked) << "the dialog never became ready";
  const FloorPlan& plan = s.window.document().project().plan;
  EXPECT_NEAR(plan.extents().size().x(), 10.0, 1e-9);
  EXPECT_EQ(occluders_on(plan, "WALLS"), 4);
  EXPECT_EQ(occluders_on(plan, "FURNITURE"), 1);
  EXPECT_TRUE(s.errors.isEmpty()) << s.errors.join("; ").toStdString();
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
  EXPECT_TRUE(c.gps_file.empty()) << "GPS is optional";

  QLineEdit* gps = nullptr;
  for (QLineEdit* edit : dialog.findChildren<QLineEdit*>())
    if (edit->placeholderText().contains("GPX")) gps = edit;
  ASSERT_NE(gps, nullptr);
  gps->setText(" /data/walk.nmea ");
  const auto doubles = dialog.findChildren<QDoubleSpinBox*>();
  QDoubleSpinBox* offset = nullptr;
  for (QDoubleSpinBox* d : doubles)
    if (d->suffix() == " s") offset = d;
  ASSERT_NE(offset, nullptr);
  offset->setValue(-2.5);
  EXPECT_EQ(dialog.choices().gps_file, "/data/walk.nmea");
  EXPECT_DOUBLE_EQ(dialog.choices().gps_time_offset_s, -2.5);
}

TEST(CaptureImport, AttachesTheGpsTrackInAnyFormat) {
  // The test project's 30 frames with an NMEA log of three fixes one second apart (hand-written; the
  // reference sentence of NMEA 0183 moved by 1 s steps, checksums left out as the standard allows).
  const auto& t = test::test_project("import-gps");
  QTemporaryDir dir;
  const QString nmea = dir.filePath("walk.log");
  {
    QFile f(nmea);
    ASSERT_TRUE(f.open(QIODevice::WriteOnly));
    for (int s = 19; s <= 21; ++s)
      f.write(
          QString("$GPRMC,1235%1,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W\r\n").arg(s).toLatin1());
  }
  widgets::CaptureImportChoices choices;
  choices.source = QDir(t.folder).filePath("frames").toStdString();
  choices.gps_file = nmea.toStdString();
  choices.gps_time_offset_s = 0.5;
  const widgets::TaskResult result = studio::import_capture_task(choices)(t.project, null_progress());
  EXPECT_EQ(result.project.capture.frame_count, 30);
  ASSERT_EQ(result.project.capture.gps_track.size(), 3u);
  EXPECT_DOUBLE_EQ(result.project.capture.gps_track[2].time_s, 2.0);
  EXPECT_NEAR(result.project.capture.gps_track[0].latitude_deg, 48.0 + 7.038 / 60.0, 1e-12);
  EXPECT_DOUBLE_EQ(result.project.capture.gps_time_offset_s, 0.5);

  // A file that is no GPS track stops the import with its name.
  choices.gps_file = QDir(t.folder).filePath("test.plenopath").toStdString();
  try {
    studio::import_capture_task(choices)(t.project, null_progress());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.plenopath"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plenopath
