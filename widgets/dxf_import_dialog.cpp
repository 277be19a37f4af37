#include "widgets/dxf_import_dialog.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QScreen>
#include <QSplitter>
#include <QTableWidget>
#include <QTimer>
#include <QToolButton>
#include <QTreeWidget>
#include <QVBoxLayout>
#include <QtConcurrent>
#include <algorithm>
#include <exception>
#include <utility>
#include <vector>

#include "processing/visibility/visibility.h"
#include "widgets/plan_preview.h"

namespace plenopath::widgets {

struct DxfImportDialog::ImportOutcome {
  int id = 0;
  QString file;
  bool units_overridden = false;
  FloorPlan plan;
  DxfImportReport report;
  QString error;  // "" = the file was read
};

struct DxfImportDialog::EnvelopeOutcome {
  int id = 0;
  std::uint64_t occluders_key = 0;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  std::shared_ptr<const VisibilityIndex> index;
  Envelope envelope;
  QString error;  // "" = the index was built
};

namespace {

// Busy indicator only for work that takes long enough to be noticed.
constexpr int kBusyDelayMs = 150;

// The units the author can choose, with their names in words.
const std::pair<const char*, const char*> kUnits[] = {
    {"mm", QT_TRANSLATE_NOOP("DxfImportDialog", "millimetres")},
    {"cm", QT_TRANSLATE_NOOP("DxfImportDialog", "centimetres")},
    {"dm", QT_TRANSLATE_NOOP("DxfImportDialog", "decimetres")},
    {"m", QT_TRANSLATE_NOOP("DxfImportDialog", "metres")},
    {"in", QT_TRANSLATE_NOOP("DxfImportDialog", "inches")},
    {"ft", QT_TRANSLATE_NOOP("DxfImportDialog", "feet")},
    {"yd", QT_TRANSLATE_NOOP("DxfImportDialog", "yards")},
};

// "AC1015" -> "R2000 (AC1015)"; unknown codes as written.
QString version_text(const std::string& acadver) {
  static const std::map<std::string, const char*> releases = {
      {"AC1006", "R10"},   {"AC1009", "R12"},   {"AC1012", "R13"},   {"AC1014", "R14"},
      {"AC1015", "R2000"}, {"AC1018", "R2004"}, {"AC1021", "R2007"}, {"AC1024", "R2010"},
      {"AC1027", "R2013"}, {"AC1032", "R2018"}};
  const QString code = QString::fromStdString(acadver);
  const auto it = releases.find(acadver);
  return it == releases.end() ? code : QStringLiteral("%1 (%2)").arg(it->second, code);
}

// "12 DIMENSION, 3 3DSOLID": the most frequent first.
QString skipped_text(const std::map<std::string, int>& by_kind) {
  std::vector<std::pair<std::string, int>> kinds(by_kind.begin(), by_kind.end());
  std::stable_sort(kinds.begin(), kinds.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  QStringList parts;
  for (const auto& [kind, count] : kinds)
    parts << QStringLiteral("%1 %2").arg(count).arg(QString::fromStdString(kind));
  return parts.join(", ");
}

// "1 warning", "3 warnings".
QString count_text(int n, const char* one, const char* many) {
  return QStringLiteral("%1 %2").arg(n).arg(QString::fromUtf8(n == 1 ? one : many));
}

QString metres(double v) { return QString::number(v, 'f', v < 10 ? 2 : v < 1000 ? 1 : 0); }

QString envelope_words(const Envelope& envelope) {
  switch (envelope.status) {
    case EnvelopeStatus::ok:
      return DxfImportDialog::tr("Seen from the red point: %1 m²").arg(metres(envelope.area));
    case EnvelopeStatus::on_wall:
      return DxfImportDialog::tr("The point is on a wall: click inside a room");
    case EnvelopeStatus::inside_obstacle:
      return DxfImportDialog::tr("The point is inside a closed obstacle (a column?): click inside a room");
    case EnvelopeStatus::outside:
      return DxfImportDialog::tr("The point is outside the building: click inside a room");
  }
  return {};
}

// The plan reduced to what blocks sight: all a visibility index looks at, cheap to hand to a worker.
std::shared_ptr<const FloorPlan> occluders_only(const FloorPlan& plan) {
  auto out = std::make_shared<FloorPlan>();
  out->units = plan.units;
  out->metres_per_unit = plan.metres_per_unit;
  out->segments = plan.occluder_segments();
  return out;
}

}  // namespace

DxfImportDialog::DxfImportDialog(QWidget* parent, const QString& file)
    : QDialog(parent),
      file_edit_(new QLineEdit(this)),
      units_(new QComboBox(this)),
      units_reason_(new QLabel(this)),
      layers_(new QTableWidget(0, kColumns, this)),
      preview_(new PlanPreview(this)),
      stray_label_(new QLabel(this)),
      keep_stray_(new QCheckBox(tr("Keep stray entities"), this)),
      summary_(new QLabel(this)),
      details_button_(new QToolButton(this)),
      details_(new QWidget(this)),
      details_text_(new QLabel(details_)),
      skipped_(new QTreeWidget(details_)),
      busy_bar_(new QProgressBar(this)),
      status_(new QLabel(this)) {
  setWindowTitle(tr("Import floor plan (DXF)"));

  // File and units.
  auto* browse = new QPushButton(tr("Browse…"), this);
  browse->setAutoDefault(false);
  file_edit_->setPlaceholderText(tr("A DXF drawing (ASCII or binary, R12 to R2018)"));
  auto* file_row = new QHBoxLayout;
  file_row->addWidget(file_edit_, 1);
  file_row->addWidget(browse);
  units_reason_->setWordWrap(true);
  units_reason_->setStyleSheet("color: #555;");
  units_reason_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  auto* units_column = new QVBoxLayout;
  units_column->setSpacing(2);
  units_column->addWidget(units_);
  units_column->addWidget(units_reason_);
  units_->setSizeAdjustPolicy(QComboBox::AdjustToContents);
  units_->setSizePolicy(QSizePolicy::Maximum, QSizePolicy::Fixed);
  units_->setMinimumContentsLength(28);
  auto* form = new QFormLayout;
  form->addRow(tr("File"), file_row);
  form->addRow(tr("Units"), units_column);

  // Layers.
  layers_->setHorizontalHeaderLabels(
      {tr("Layer"), tr("Entities"), tr("Blocks sight"), tr("In file"), tr("Why")});
  layers_->horizontalHeaderItem(kBlocksSightColumn)
      ->setToolTip(tr("Ticked layers are walls: they block sight in the envelopes and visibility"));
  layers_->horizontalHeaderItem(kWhyColumn)
      ->setToolTip(tr("Why the importer proposed the layer as blocking sight"));
  layers_->horizontalHeaderItem(kStateColumn)
      ->setToolTip(tr("Whether the layer is on or off in the drawing"));
  QHeaderView* header = layers_->horizontalHeader();
  header->setSectionResizeMode(kLayerColumn, QHeaderView::Interactive);
  header->setSectionResizeMode(kEntitiesColumn, QHeaderView::ResizeToContents);
  header->setSectionResizeMode(kBlocksSightColumn, QHeaderView::ResizeToContents);
  header->setSectionResizeMode(kStateColumn, QHeaderView::ResizeToContents);
  header->setStretchLastSection(true);
  layers_->setColumnWidth(kLayerColumn, 140);
  layers_->setMinimumWidth(360);
  layers_->verticalHeader()->hide();
  layers_->setSelectionMode(QAbstractItemView::NoSelection);
  layers_->setWordWrap(false);
  layers_->setTextElideMode(Qt::ElideRight);

  // Preview with the stray-entity note under it.
  stray_label_->setWordWrap(true);
  auto* stray_row = new QHBoxLayout;
  stray_row->addWidget(stray_label_, 1);
  stray_row->addWidget(keep_stray_);
  auto* preview_box = new QWidget(this);
  auto* preview_column = new QVBoxLayout(preview_box);
  preview_column->setContentsMargins(0, 0, 0, 0);
  preview_column->addWidget(preview_, 1);
  preview_column->addLayout(stray_row);
  auto* splitter = new QSplitter(Qt::Horizontal, this);
  splitter->addWidget(layers_);
  splitter->addWidget(preview_box);
  splitter->setStretchFactor(0, 1);
  splitter->setStretchFactor(1, 1);
  splitter->setChildrenCollapsible(false);
  splitter->setSizes({440, 540});

  // Report: a summary line, the details on demand.
  summary_->setWordWrap(true);
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  details_button_->setText(tr("Details…"));
  details_button_->setCheckable(true);
  details_button_->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  details_button_->setArrowType(Qt::RightArrow);
  details_button_->setAutoRaise(true);
  auto* summary_row = new QHBoxLayout;
  summary_row->addWidget(summary_, 1);
  summary_row->addWidget(details_button_, 0, Qt::AlignTop);
  details_text_->setWordWrap(true);
  details_text_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  skipped_->setColumnCount(4);
  skipped_->setHeaderLabels({tr("Line"), tr("Entity"), tr("Layer"), tr("Why skipped")});
  skipped_->setRootIsDecorated(false);
  skipped_->setUniformRowHeights(true);
  skipped_->setMinimumHeight(110);
  skipped_->setMaximumHeight(220);
  auto* details_layout = new QVBoxLayout(details_);
  details_layout->setContentsMargins(0, 0, 0, 0);
  details_layout->addWidget(details_text_);
  details_layout->addWidget(skipped_, 1);
  details_->hide();

  // Busy bar, why OK is off, the buttons.
  busy_bar_->setRange(0, 0);  // indeterminate
  busy_bar_->setMaximumWidth(120);
  busy_bar_->setMaximumHeight(14);
  busy_bar_->setTextVisible(false);
  busy_bar_->hide();
  status_->setWordWrap(true);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  ok_ = buttons->button(QDialogButtonBox::Ok);
  ok_->setText(tr("Import"));
  ok_->setDefault(true);
  buttons->button(QDialogButtonBox::Cancel)->setAutoDefault(false);
  auto* bottom = new QHBoxLayout;
  bottom->addWidget(busy_bar_);
  bottom->addWidget(status_, 1);
  bottom->addWidget(buttons);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(splitter, 1);
  layout->addLayout(summary_row);
  layout->addWidget(details_);
  layout->addLayout(bottom);

  fill_units();

  connect(browse, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getOpenFileName(this, tr("Floor plan"), file_edit_->text(),
                                                   tr("DXF drawings (*.dxf *.DXF)"));
    if (!f.isEmpty()) set_file(f);
  });
  // Typing a path disables OK until Enter reads it (Enter must not accept the plan of the previous file).
  connect(file_edit_, &QLineEdit::textEdited, this, [this] { update_ok(); });
  connect(file_edit_, &QLineEdit::editingFinished, this, [this] {
    if (file_edit_->text() != loaded_file_ || !error_.isEmpty()) set_file(file_edit_->text());
  });
  connect(units_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] { request_import(); });
  connect(keep_stray_, &QCheckBox::toggled, this, [this] { request_import(); });
  connect(layers_, &QTableWidget::itemChanged, this, [this](QTableWidgetItem* item) {
    if (!filling_ && item->column() == kBlocksSightColumn) apply_occluders();
  });
  connect(preview_, &PlanPreview::point_clicked, this, [this] { request_envelope(); });
  connect(details_button_, &QToolButton::toggled, this, [this](bool on) {
    // The details get room of their own: the dialog grows (within the screen) instead of the preview
    // shrinking.
    const int before = height();
    details_->setVisible(on);
    details_button_->setArrowType(on ? Qt::DownArrow : Qt::RightArrow);
    const int extra = details_->sizeHint().height() + this->layout()->spacing();
    const QScreen* screen = this->screen();
    const int room = screen ? screen->availableGeometry().height() - 60 : before + extra;
    resize(width(), on ? std::min(before + extra, std::max(before, room))
                       : std::max(minimumSizeHint().height(), before - extra));
  });
  connect(&import_watcher_, &QFutureWatcher<std::shared_ptr<ImportOutcome>>::finished, this,
          &DxfImportDialog::on_import_finished);
  connect(&envelope_watcher_, &QFutureWatcher<std::shared_ptr<EnvelopeOutcome>>::finished, this,
          &DxfImportDialog::on_envelope_finished);
  connect(buttons, &QDialogButtonBox::accepted, this, [this] {
    if (ok_->isEnabled()) accept();
  });
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);

  resize(1000, 640);
  fill_report();
  show_plan_note();
  if (!file.isEmpty()) set_file(file);
  update_ok();
}

// Running jobs own copies of what they read: they finish on their own and their results are dropped.
DxfImportDialog::~DxfImportDialog() {
  import_watcher_.disconnect(this);
  envelope_watcher_.disconnect(this);
}

QString DxfImportDialog::file() const { return file_edit_->text(); }

bool DxfImportDialog::busy() const {
  return import_running_ || import_pending_ || envelope_running_ || envelope_pending_;
}

void DxfImportDialog::set_file(const QString& file) {
  file_edit_->setText(file);
  // A new drawing: what the author chose for the previous one no longer applies.
  chosen_occluders_.clear();
  file_units_.clear();
  file_units_source_.clear();
  file_units_reason_.clear();
  {
    const QSignalBlocker block_units(units_);
    const QSignalBlocker block_stray(keep_stray_);
    units_->setCurrentIndex(0);
    keep_stray_->setChecked(false);
  }
  preview_->set_marked_point(std::nullopt);
  preview_->set_envelope({});
  fill_units();
  request_import();
}

void DxfImportDialog::request_import() {
  ++import_requested_;
  if (import_running_)
    import_pending_ = true;  // runs with the newest options when the current one ends
  else
    start_import();
  update_busy();
  update_ok();
}

void DxfImportDialog::start_import() {
  import_pending_ = false;
  import_running_ = true;
  const QString file = file_edit_->text();
  DxfImportOptions options;
  options.units_override = units_->currentData().toString().toStdString();
  options.keep_stray = keep_stray_->isChecked();
  const int id = import_requested_;
  import_watcher_.setFuture(QtConcurrent::run([id, file, options]() {
    auto out = std::make_shared<ImportOutcome>();
    out->id = id;
    out->file = file;
    out->units_overridden = !options.units_override.empty();
    if (file.isEmpty()) return out;
    try {
      out->plan = import_dxf(file.toStdString(), options, &out->report);
    } catch (const std::exception& e) {
      out->error = QString::fromStdString(e.what());
    } catch (...) {
      out->error = tr("unexpected error reading %1").arg(file);
    }
    return out;
  }));
}

void DxfImportDialog::on_import_finished() {
  import_running_ = false;
  const std::shared_ptr<ImportOutcome> outcome = import_watcher_.result();
  if (import_pending_) {
    start_import();  // a newer request came in: this result is already stale
  } else if (outcome && outcome->id == import_requested_) {
    show_import(*outcome);
  }
  update_busy();
  update_ok();
}

void DxfImportDialog::show_import(const ImportOutcome& outcome) {
  // Keep the marked point on the same spot of the drawing when only the units changed.
  std::optional<Eigen::Vector2d> point = preview_->marked_point();
  if (point && outcome.file == loaded_file_ && !outcome.plan.empty() && plan_.metres_per_unit > 0) {
    const Eigen::Vector2d drawing = (*point + plan_.dxf_origin_m) / plan_.metres_per_unit;
    point = drawing * outcome.plan.metres_per_unit - outcome.plan.dxf_origin_m;
  } else {
    point.reset();
  }
  plan_ = outcome.plan;
  report_ = outcome.report;
  error_ = outcome.error;
  loaded_file_ = outcome.file;
  if (!outcome.units_overridden && error_.isEmpty()) {
    file_units_ = QString::fromStdString(report_.units);
    file_units_source_ = QString::fromStdString(report_.units_source);
    if (file_units_source_.isEmpty() && report_.units_from_header) file_units_source_ = "header";
    file_units_reason_ = QString::fromStdString(report_.units_reason);
  }
  // The author's ticks survive a re-import of the same drawing.
  for (const auto& [layer, occluder] : chosen_occluders_)
    if (plan_.find_layer(layer)) plan_.set_layer_occluder(layer, occluder);
  ++occluders_key_;

  fill_units();
  fill_layers();
  fill_report();
  preview_->set_plan(&plan_);
  preview_->set_marked_point(point);
  preview_->set_envelope({});
  emit plan_loaded();
  if (point)
    request_envelope();
  else
    show_plan_note();
}

void DxfImportDialog::fill_units() {
  const QSignalBlocker block(units_);
  const int current = std::max(0, units_->currentIndex());
  units_->clear();
  QString from_file = tr("From the file");
  if (!file_units_.isEmpty())
    from_file = file_units_source_.isEmpty()
                    ? tr("From the file (%1)").arg(file_units_)
                    : tr("From the file (%1, %2)").arg(file_units_, file_units_source_);
  units_->addItem(from_file, QString());
  units_->setItemData(0, file_units_reason_, Qt::ToolTipRole);
  for (const auto& [code, name] : kUnits)
    units_->addItem(QStringLiteral("%1 (%2)").arg(code, tr(name)), QString(code));
  units_->setCurrentIndex(current);
  units_->setToolTip(file_units_reason_);

  QString reason = file_units_reason_;
  const QString chosen = units_->currentData().toString();
  if (!chosen.isEmpty())
    reason = file_units_.isEmpty() ? tr("Read as %1 (chosen here).").arg(chosen)
                                   : tr("Read as %1 (chosen here); the file says %2. %3")
                                         .arg(chosen, file_units_, file_units_reason_);
  units_reason_->setText(reason);
  units_reason_->setVisible(!reason.trimmed().isEmpty());
}

void DxfImportDialog::fill_layers() {
  filling_ = true;
  layers_->setRowCount(static_cast<int>(plan_.layers.size()));
  for (int row = 0; row < static_cast<int>(plan_.layers.size()); ++row) {
    const PlanLayer& layer = plan_.layers[row];
    const QString name_text = QString::fromStdString(layer.name);
    auto* name = new QTableWidgetItem(name_text);
    name->setFlags(Qt::ItemIsEnabled);
    name->setToolTip(name_text);
    auto* count = new QTableWidgetItem(QString::number(layer.entity_count));
    count->setFlags(Qt::ItemIsEnabled);
    count->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    auto* occluder = new QTableWidgetItem;
    occluder->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable);
    occluder->setCheckState(layer.occluder ? Qt::Checked : Qt::Unchecked);
    auto* state = new QTableWidgetItem(layer.visible ? tr("on") : tr("off"));
    state->setFlags(Qt::ItemIsEnabled);
    if (!layer.visible) state->setForeground(QColor(150, 150, 150));
    const auto reason_it = report_.occluder_reasons.find(layer.name);
    const QString reason =
        reason_it == report_.occluder_reasons.end() ? QString() : QString::fromStdString(reason_it->second);
    auto* why = new QTableWidgetItem(reason);
    why->setFlags(Qt::ItemIsEnabled);
    why->setToolTip(reason);
    layers_->setItem(row, kLayerColumn, name);
    layers_->setItem(row, kEntitiesColumn, count);
    layers_->setItem(row, kBlocksSightColumn, occluder);
    layers_->setItem(row, kStateColumn, state);
    layers_->setItem(row, kWhyColumn, why);
  }
  layers_->resizeRowsToContents();
  // Names as wide as they need, within reason: the reason column must stay in view.
  layers_->resizeColumnToContents(kLayerColumn);
  layers_->setColumnWidth(kLayerColumn, std::clamp(layers_->columnWidth(kLayerColumn), 90, 200));
  filling_ = false;
}

void DxfImportDialog::fill_report() {
  if (!error_.isEmpty()) {
    summary_->setText(tr("<b>Cannot read the plan:</b> %1").arg(error_.toHtmlEscaped()));
  } else if (loaded_file_.isEmpty()) {
    summary_->setText(file_edit_->text().isEmpty() ? tr("Choose a DXF file.") : QString());
  } else {
    QStringList parts;
    if (!report_.version.empty()) parts << version_text(report_.version);
    parts << (report_.binary ? tr("binary") : tr("ASCII"));
    if (!report_.codepage.empty()) parts << QString::fromStdString(report_.codepage);
    parts << count_text(report_.entities_read, "entity read", "entities read");
    const QString by_kind = skipped_text(report_.skipped_by_kind);
    if (!by_kind.isEmpty())
      parts << tr("%1 skipped").arg(by_kind);
    else if (report_.entities_skipped > 0)
      parts << count_text(report_.entities_skipped, "entity skipped", "entities skipped");
    if (report_.blocks_expanded > 0)
      parts << count_text(report_.blocks_expanded, "block expanded", "blocks expanded");
    QString text = parts.join(" · ").toHtmlEscaped();
    const PlanExtents e = plan_.extents();
    text += "<br>" + count_text(static_cast<int>(plan_.segments.size()), "segment", "segments");
    if (e.valid) text += " · " + tr("%1 × %2 m").arg(metres(e.size().x()), metres(e.size().y()));
    if (!report_.warnings.empty())
      text += " · <span style='color:#a05a00'>⚠ " +
              count_text(static_cast<int>(report_.warnings.size()), "warning", "warnings") + "</span>";
    summary_->setText(text);
  }

  // Details: warnings, clean-up figures, the skipped entities with line and why.
  QStringList lines;
  for (const std::string& w : report_.warnings) lines << "⚠ " + QString::fromStdString(w).toHtmlEscaped();
  if (!loaded_file_.isEmpty() && error_.isEmpty()) {
    lines << tr("Clean-up: %1 endpoints snapped, %2 zero-length and %3 duplicate segments dropped, %4 "
                "collinear "
                "merged, %5 split at crossings; %6 curves tessellated, %7 hatch/solid outlines.")
                 .arg(report_.snapped_endpoints)
                 .arg(report_.zero_length_dropped)
                 .arg(report_.duplicates_dropped)
                 .arg(report_.collinear_merged)
                 .arg(report_.intersections_split)
                 .arg(report_.arcs_tessellated)
                 .arg(report_.hatch_outlines);
    if (!report_.origin_m.isZero())
      lines << tr("Re-centred: the plan's origin is at (%1, %2) m in the drawing.")
                   .arg(report_.origin_m.x(), 0, 'f', 3)
                   .arg(report_.origin_m.y(), 0, 'f', 3);
    if (report_.entities_skipped > static_cast<int>(report_.skipped.size()) && !report_.skipped.empty())
      lines << tr("The first %1 of %2 skipped entities are listed.")
                   .arg(report_.skipped.size())
                   .arg(report_.entities_skipped);
  }
  details_text_->setText(lines.join("<br>"));
  details_text_->setVisible(!lines.isEmpty());
  skipped_->clear();
  QList<QTreeWidgetItem*> rows;
  for (const DxfSkippedEntity& s : report_.skipped)
    rows << new QTreeWidgetItem(QStringList{QString::number(s.line), QString::fromStdString(s.kind),
                                            QString::fromStdString(s.layer), QString::fromStdString(s.why)});
  skipped_->addTopLevelItems(rows);
  skipped_->setVisible(!rows.isEmpty());
  for (int c = 0; c < 3; ++c) skipped_->resizeColumnToContents(c);
  details_button_->setEnabled(!lines.isEmpty() || !rows.isEmpty());

  // Stray entities: say how many, offer to keep them.
  const bool strays = report_.stray_entities > 0;
  stray_label_->setText(
      strays ? (keep_stray_->isChecked() ? tr("%1 far from the drawing's bulk: kept.")
                                         : tr("%1 far from the drawing's bulk: left out of the plan."))
                   .arg(count_text(report_.stray_entities, "stray entity", "stray entities"))
             : QString());
  stray_label_->setVisible(strays);
  keep_stray_->setVisible(strays || keep_stray_->isChecked());
}

void DxfImportDialog::apply_occluders() {
  for (int row = 0; row < layers_->rowCount() && row < static_cast<int>(plan_.layers.size()); ++row) {
    const bool occluder = layers_->item(row, kBlocksSightColumn)->checkState() == Qt::Checked;
    if (plan_.layers[row].occluder == occluder) continue;
    plan_.set_layer_occluder(plan_.layers[row].name, occluder);
    chosen_occluders_[plan_.layers[row].name] = occluder;
  }
  ++occluders_key_;
  preview_->plan_changed();
  update_ok();
  if (preview_->marked_point())
    request_envelope();
  else
    show_plan_note();
}

void DxfImportDialog::request_envelope() {
  if (!preview_->marked_point()) return;
  if (plan_.occluder_segments().empty()) {
    // Nothing to see against: no worker, just say so (and drop any answer still on its way).
    ++envelope_requested_;
    envelope_pending_ = false;
    preview_->set_envelope({});
    preview_->set_note(tr("No layer blocks sight: tick the wall layers to see what is seen from here"));
    update_busy();
    emit envelope_shown();
    return;
  }
  ++envelope_requested_;
  preview_->set_note(tr("Computing what is seen from the red point…"));
  if (envelope_running_)
    envelope_pending_ = true;
  else
    start_envelope();
  update_busy();
}

void DxfImportDialog::start_envelope() {
  envelope_pending_ = false;
  envelope_running_ = true;
  const int id = envelope_requested_;
  const std::uint64_t key = occluders_key_;
  const Eigen::Vector2d point = *preview_->marked_point();
  // The index built for these occluders is reused; otherwise the worker builds one from a snapshot.
  std::shared_ptr<const VisibilityIndex> index = index_key_ == key ? index_ : nullptr;
  std::shared_ptr<const FloorPlan> occluders = index ? nullptr : occluders_only(plan_);
  envelope_watcher_.setFuture(QtConcurrent::run([id, key, point, index, occluders]() {
    auto out = std::make_shared<EnvelopeOutcome>();
    out->id = id;
    out->occluders_key = key;
    out->point = point;
    try {
      out->index = index ? index : std::make_shared<const VisibilityIndex>(*occluders);
      out->envelope = out->index->envelope(point);
    } catch (const std::exception& e) {
      out->error = QString::fromStdString(e.what());
    } catch (...) {
      out->error = tr("unexpected error");
    }
    return out;
  }));
}

void DxfImportDialog::on_envelope_finished() {
  envelope_running_ = false;
  const std::shared_ptr<EnvelopeOutcome> outcome = envelope_watcher_.result();
  if (outcome && outcome->index && outcome->occluders_key == occluders_key_) {
    index_ = outcome->index;  // still the current occluders: keep it for the next click
    index_key_ = outcome->occluders_key;
  }
  if (envelope_pending_) {
    start_envelope();
  } else if (outcome && outcome->id == envelope_requested_) {
    if (!outcome->error.isEmpty()) {
      preview_->set_envelope({});
      preview_->set_note(tr("Cannot compute what is seen: %1").arg(outcome->error));
    } else {
      preview_->set_envelope(outcome->envelope.polygon);
      preview_->set_note(envelope_words(outcome->envelope));
    }
    emit envelope_shown();
  }
  update_busy();
}

void DxfImportDialog::show_plan_note() {
  const PlanExtents e = plan_.extents();
  if (plan_.empty() || !e.valid) {
    preview_->set_note({});
    return;
  }
  preview_->set_envelope({});
  preview_->set_note(tr("%1 × %2 m · click a point to see what is seen from it")
                         .arg(metres(e.size().x()), metres(e.size().y())));
}

void DxfImportDialog::update_ok() {
  QString why;
  const bool importing = import_running_ || import_pending_;
  if (importing)
    why = tr("Reading %1…").arg(QFileInfo(file_edit_->text()).fileName());
  else if (file_edit_->text() != loaded_file_)
    why = tr("Press Enter to read the file.");
  else if (!error_.isEmpty())
    why = tr("The file could not be read (see above).");
  else if (plan_.empty())
    why = loaded_file_.isEmpty() ? tr("Choose a DXF file.") : tr("The drawing holds no plan geometry.");
  else if (plan_.occluder_segments().empty())
    why = tr("No layer blocks sight: tick the wall layers.");
  ok_->setEnabled(why.isEmpty());
  status_->setText(why);
  status_->setStyleSheet(importing || why.isEmpty() ? QString() : QStringLiteral("color: #a03000;"));
}

void DxfImportDialog::update_busy() {
  const bool running = import_running_ || envelope_running_;
  // Shown only once a job has run for a moment (the timer calls back), hidden as soon as all are done.
  if (!running) {
    busy_bar_->hide();
  } else if (!busy_bar_->isVisible()) {
    QTimer::singleShot(kBusyDelayMs, this, [this] {
      if (import_running_ || envelope_running_) busy_bar_->show();
    });
  }
}

}  // namespace plenopath::widgets
