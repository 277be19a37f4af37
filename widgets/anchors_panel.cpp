#include "widgets/anchors_panel.h"

#include <QAction>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QKeyEvent>
#include <QLabel>
#include <QTableWidget>
#include <QTimer>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <set>

#include "model/error.h"
#include "widgets/anchor_commands.h"
#include "widgets/anchor_editor.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {

QTableWidgetItem* item_at(QTableWidget* table, int row, int column) {
  QTableWidgetItem* item = table->item(row, column);
  if (!item) {
    item = new QTableWidgetItem;
    item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    table->setItem(row, column, item);
  }
  return item;
}

}  // namespace

AnchorsPanel::AnchorsPanel(ProjectDocument& document, QWidget* parent)
    : QWidget(parent),
      document_(document),
      table_(new QTableWidget(this)),
      summary_(new QLabel(this)),
      delete_(new QToolButton(this)),
      refine_(new QToolButton(this)) {
  table_->setObjectName("anchors_table");
  table_->setColumnCount(kColumnCount);
  // Short headers: the dock is narrow; the tooltips say the rest.
  table_->setHorizontalHeaderLabels({tr("Frame"), tr("x (m)"), tr("y (m)"), tr("θ (°)"), tr("Resid. (m)")});
  table_->horizontalHeaderItem(kHeadingColumn)
      ->setToolTip(tr("Heading the frame must have, in degrees (empty: the refinement leaves it free)"));
  table_->horizontalHeaderItem(kResidualColumn)
      ->setToolTip(tr("Residual: how far the path's frame is from its anchor, in metres (after the last "
                      "correction or refinement)"));
  table_->verticalHeader()->hide();
  table_->verticalHeader()->setDefaultSectionSize(fontMetrics().height() + 6);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  table_->horizontalHeader()->setMinimumSectionSize(20);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setEditTriggers(QAbstractItemView::DoubleClicked | QAbstractItemView::EditKeyPressed |
                          QAbstractItemView::AnyKeyPressed);
  table_->installEventFilter(this);

  delete_->setText(tr("Delete"));
  delete_->setToolTip(tr("Remove the selected anchors (Del); the path stays where it is"));
  refine_->setToolButtonStyle(Qt::ToolButtonTextOnly);
  refine_->hide();
  summary_->setWordWrap(true);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(delete_);
  buttons->addWidget(refine_);
  buttons->addStretch(1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->addWidget(table_);
  layout->addLayout(buttons);
  layout->addWidget(summary_);

  connect(delete_, &QToolButton::clicked, this, &AnchorsPanel::delete_selected);
  connect(table_, &QTableWidget::itemChanged, this, &AnchorsPanel::on_item_changed);
  connect(table_, &QTableWidget::itemSelectionChanged, this, [this] {
    if (filling_) return;
    const QList<QTableWidgetItem*> selected = table_->selectedItems();
    delete_->setEnabled(!selected.isEmpty());
    if (selected.isEmpty()) return;
    const int row = selected.front()->row();
    const Anchors& anchors = document_.project().anchors;
    if (row < 0 || row >= static_cast<int>(anchors.size())) return;
    const int position = document_.position_of_frame_index(anchors[static_cast<std::size_t>(row)].frame);
    if (position >= 0) document_.set_current_position(position);
  });
  connect(&document_, &ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & (kAnchorsChanged | kPathChanged)) refill();
  });
  refill();
}

void AnchorsPanel::set_refine_action(QAction* action) {
  refine_->setDefaultAction(action);
  refine_->show();
}

QString AnchorsPanel::summary() const { return summary_->text(); }

void AnchorsPanel::refill() {
  // Items are updated in place (never deleted under an edit in progress).
  filling_ = true;
  const Project& p = document_.project();
  const std::vector<double> residuals = anchor_residuals(p.path, p.anchors);
  table_->setRowCount(static_cast<int>(p.anchors.size()));
  double worst = -1.0;
  for (std::size_t i = 0; i < p.anchors.size(); ++i) {
    const Anchor& a = p.anchors[i];
    const int row = static_cast<int>(i);
    item_at(table_, row, kFrameColumn)->setText(QString::number(a.frame));
    item_at(table_, row, kXColumn)->setText(QString::number(a.position.x(), 'f', 3));
    item_at(table_, row, kYColumn)->setText(QString::number(a.position.y(), 'f', 3));
    item_at(table_, row, kHeadingColumn)
        ->setText(a.heading ? QString::number(degrees(*a.heading), 'f', 1) : QString());
    QTableWidgetItem* residual = item_at(table_, row, kResidualColumn);
    residual->setFlags(residual->flags() & ~Qt::ItemIsEditable);
    residual->setText(residuals[i] < 0 ? tr("not on path") : QString::number(residuals[i], 'f', 3));
    worst = std::max(worst, residuals[i]);
  }
  if (p.anchors.empty())
    summary_->setText(tr("No anchors. Ctrl + drag a frame on the map to where it really was."));
  else
    summary_->setText(tr("%n anchor(s), largest residual %1 m", "", static_cast<int>(p.anchors.size()))
                          .arg(std::max(0.0, worst), 0, 'f', 3));
  delete_->setEnabled(!table_->selectedItems().isEmpty());
  filling_ = false;
}

void AnchorsPanel::show_problem(const QString& problem) {
  // Back to what the document holds, after the edit has finished.
  QTimer::singleShot(0, this, [this, problem] {
    refill();
    summary_->setText(problem);
  });
}

void AnchorsPanel::on_item_changed(QTableWidgetItem* item) {
  if (filling_) return;
  const Project& p = document_.project();
  const int row = item->row();
  if (row < 0 || row >= static_cast<int>(p.anchors.size())) return;
  Anchors anchors = p.anchors;
  Anchor& a = anchors[static_cast<std::size_t>(row)];
  const QString text = item->text().trimmed();
  bool ok = true;
  QString what;
  switch (item->column()) {
    case kFrameColumn: {
      const int frame = text.toInt(&ok);
      if (!ok) return show_problem(tr("Frame: \"%1\" is not a frame number").arg(text));
      if (!p.path.find_frame(frame)) return show_problem(tr("Frame %1 is not on the path").arg(frame));
      if (frame != a.frame &&
          std::any_of(anchors.begin(), anchors.end(), [&](const Anchor& o) { return o.frame == frame; }))
        return show_problem(tr("Frame %1 has an anchor already").arg(frame));
      what = tr("Move anchor from frame %1 to %2").arg(a.frame).arg(frame);
      a.frame = frame;
      std::sort(anchors.begin(), anchors.end(),
                [](const Anchor& l, const Anchor& r) { return l.frame < r.frame; });
      break;
    }
    case kXColumn:
    case kYColumn: {
      const double value = text.toDouble(&ok);
      if (!ok || !std::isfinite(value))
        return show_problem(tr("\"%1\" is not a coordinate in metres").arg(text));
      a.position[item->column() == kXColumn ? 0 : 1] = value;
      what = tr("Edit anchor of frame %1").arg(a.frame);
      break;
    }
    case kHeadingColumn: {
      if (text.isEmpty()) {
        a.heading.reset();
      } else {
        const double value = text.toDouble(&ok);
        if (!ok || !std::isfinite(value))
          return show_problem(tr("\"%1\" is not a heading in degrees").arg(text));
        a.heading = wrap_angle(radians(value));
      }
      what = tr("Edit heading of the anchor of frame %1").arg(a.frame);
      break;
    }
    default:
      return;
  }
  if (anchors == p.anchors) return;
  // Every edit corrects the path, as a drag on the map does: on a worker; one undo step when it lands.
  AnchorEditor::Callbacks callbacks;
  callbacks.context = this;
  callbacks.refused = [this](const QString& why) { show_problem(why); };
  AnchorEditor::of(document_).request(what, std::move(anchors), PathCorrection::kRefine, callbacks);
}

void AnchorsPanel::delete_selected() {
  std::set<int> rows;
  for (const QTableWidgetItem* item : table_->selectedItems()) rows.insert(item->row());
  const Anchors& anchors = document_.project().anchors;
  std::vector<int> frames;
  for (int row : rows)
    if (row >= 0 && row < static_cast<int>(anchors.size()))
      frames.push_back(anchors[static_cast<std::size_t>(row)].frame);
  if (frames.empty()) return;
  const QString text = frames.size() == 1 ? tr("Delete anchor of frame %1").arg(frames.front())
                                          : tr("Delete %1 anchors").arg(frames.size());
  AnchorEditor::of(document_).request(text, anchors_without(anchors, frames), PathCorrection::kNone);
}

bool AnchorsPanel::eventFilter(QObject* watched, QEvent* event) {
  if (watched == table_ && event->type() == QEvent::KeyPress) {
    const int key = static_cast<QKeyEvent*>(event)->key();
    if ((key == Qt::Key_Delete ||
         key == Qt::Key_Backspace)) {  // while a cell is edited, keys go to its editor
      delete_selected();
      return true;
    }
  }
  return QWidget::eventFilter(watched, event);
}

}  // namespace plenopath::widgets
