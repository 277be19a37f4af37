#include "widgets/dxf_import_dialog.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPainter>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>
#include <exception>

#include "processing/plan/dxf_import.h"

namespace plenopath::widgets {

PlanPreview::PlanPreview(QWidget* parent) : QWidget(parent) { setMinimumSize(240, 180); }

void PlanPreview::set_plan(const FloorPlan* plan) {
  plan_ = plan;
  update();
}

void PlanPreview::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.fillRect(rect(), QColor(246, 245, 240));
  if (!plan_ || plan_->empty()) {
    painter.setPen(Qt::gray);
    painter.drawText(rect(), Qt::AlignCenter, tr("No plan"));
    return;
  }
  const PlanExtents e = plan_->extents();
  const double sx = (width() - 20) / std::max(1e-9, e.size().x());
  const double sy = (height() - 20) / std::max(1e-9, e.size().y());
  const double s = std::min(sx, sy);
  // Plan Y up, screen y down.
  auto map = [&](const Eigen::Vector2d& p) {
    return QPointF(width() / 2.0 + (p.x() - 0.5 * (e.min.x() + e.max.x())) * s,
                   height() / 2.0 - (p.y() - 0.5 * (e.min.y() + e.max.y())) * s);
  };
  for (int pass = 0; pass < 2; ++pass)
    for (const PlanSegment& seg : plan_->segments) {
      if (seg.occluder != (pass == 1)) continue;
      painter.setPen(seg.occluder ? QPen(QColor(30, 35, 45), 2.0) : QPen(QColor(160, 160, 160), 1.0));
      painter.drawLine(map(seg.a), map(seg.b));
    }
}

DxfImportDialog::DxfImportDialog(QWidget* parent, const QString& file)
    : QDialog(parent),
      file_edit_(new QLineEdit(this)),
      units_(new QComboBox(this)),
      layers_(new QTableWidget(0, 3, this)),
      preview_(new PlanPreview(this)),
      report_(new QLabel(this)) {
  setWindowTitle(tr("Import floor plan (DXF)"));
  auto* browse = new QPushButton(tr("Browse…"), this);
  auto* file_row = new QHBoxLayout;
  file_row->addWidget(file_edit_, 1);
  file_row->addWidget(browse);
  units_->addItem(tr("From the file ($INSUNITS)"), QString());
  for (const char* u : {"mm", "cm", "dm", "m", "in", "ft", "yd"}) units_->addItem(u, QString(u));
  layers_->setHorizontalHeaderLabels({tr("Layer"), tr("Entities"), tr("Blocks sight")});
  layers_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
  layers_->verticalHeader()->hide();
  report_->setWordWrap(true);

  auto* form = new QFormLayout;
  form->addRow(tr("File"), file_row);
  form->addRow(tr("Units"), units_);
  auto* middle = new QHBoxLayout;
  middle->addWidget(layers_, 1);
  middle->addWidget(preview_, 1);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addLayout(middle, 1);
  layout->addWidget(report_);
  layout->addWidget(buttons);

  connect(browse, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getOpenFileName(this, tr("Floor plan"), file_edit_->text(),
                                                   tr("DXF drawings (*.dxf *.DXF)"));
    if (!f.isEmpty()) set_file(f);
  });
  connect(file_edit_, &QLineEdit::editingFinished, this, &DxfImportDialog::reload);
  connect(units_, qOverload<int>(&QComboBox::currentIndexChanged), this, &DxfImportDialog::reload);
  connect(layers_, &QTableWidget::itemChanged, this, [this] { apply_occluders(); });
  connect(buttons, &QDialogButtonBox::accepted, this, [this] {
    if (!plan_.empty()) accept();
  });
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  resize(820, 520);
  if (!file.isEmpty()) set_file(file);
}

QString DxfImportDialog::file() const { return file_edit_->text(); }

void DxfImportDialog::set_file(const QString& file) {
  file_edit_->setText(file);
  reload();
}

void DxfImportDialog::reload() {
  plan_ = FloorPlan();
  DxfImportOptions options;
  options.units_override = units_->currentData().toString().toStdString();
  DxfImportReport report;
  try {
    if (!file_edit_->text().isEmpty()) plan_ = import_dxf(file_edit_->text().toStdString(), options, &report);
    QString text = tr("%1 segments · units %2%3 · %4 entities, %5 skipped, %6 blocks expanded")
                       .arg(plan_.segments.size())
                       .arg(QString::fromStdString(report.units))
                       .arg(report.units_from_header ? tr(" (from the file)") : QString())
                       .arg(report.entities_read)
                       .arg(report.entities_skipped)
                       .arg(report.blocks_expanded);
    for (const auto& w : report.warnings) text += "<br>⚠ " + QString::fromStdString(w).toHtmlEscaped();
    report_->setText(file_edit_->text().isEmpty() ? tr("Choose a DXF file.") : text);
  } catch (const std::exception& e) {
    report_->setText(tr("<b>Cannot read the plan:</b> %1").arg(QString::fromStdString(e.what()).toHtmlEscaped()));
  }
  fill_layers();
  preview_->set_plan(&plan_);
}

void DxfImportDialog::fill_layers() {
  filling_ = true;
  layers_->setRowCount(static_cast<int>(plan_.layers.size()));
  for (int row = 0; row < static_cast<int>(plan_.layers.size()); ++row) {
    const PlanLayer& layer = plan_.layers[row];
    auto* name = new QTableWidgetItem(QString::fromStdString(layer.name));
    name->setFlags(Qt::ItemIsEnabled);
    auto* count = new QTableWidgetItem(QString::number(layer.entity_count));
    count->setFlags(Qt::ItemIsEnabled);
    auto* occluder = new QTableWidgetItem;
    occluder->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable);
    occluder->setCheckState(layer.occluder ? Qt::Checked : Qt::Unchecked);
    layers_->setItem(row, 0, name);
    layers_->setItem(row, 1, count);
    layers_->setItem(row, 2, occluder);
  }
  filling_ = false;
}

void DxfImportDialog::apply_occluders() {
  if (filling_) return;
  for (int row = 0; row < layers_->rowCount() && row < static_cast<int>(plan_.layers.size()); ++row)
    plan_.set_layer_occluder(plan_.layers[row].name, layers_->item(row, 2)->checkState() == Qt::Checked);
  preview_->update();
}

}  // namespace plenopath::widgets
