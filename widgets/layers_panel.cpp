#include "widgets/layers_panel.h"

#include <QHeaderView>
#include <QTreeWidget>
#include <QUndoStack>
#include <QVBoxLayout>

#include "widgets/document_commands.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

LayersPanel::LayersPanel(ProjectDocument& document, QWidget* parent)
    : QWidget(parent), document_(document), tree_(new QTreeWidget(this)) {
  tree_->setColumnCount(3);
  tree_->setHeaderLabels({tr("Layer"), tr("Entities"), tr("Blocks sight")});
  tree_->setRootIsDecorated(false);
  tree_->header()->setSectionResizeMode(0, QHeaderView::Stretch);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->addWidget(tree_);
  connect(tree_, &QTreeWidget::itemChanged, this, [this](QTreeWidgetItem* item, int column) {
    if (filling_ || column != 2) return;
    const std::string layer = item->text(0).toStdString();
    const bool occluder = item->checkState(2) == Qt::Checked;
    const PlanLayer* l = document_.project().plan.find_layer(layer);
    if (l && l->occluder != occluder)
      document_.undo_stack()->push(new SetLayerOccluderCommand(document_, layer, occluder));
  });
  connect(&document_, &ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & kPlanChanged) refill();
  });
  refill();
}

void LayersPanel::refill() {
  filling_ = true;
  tree_->clear();
  for (const PlanLayer& layer : document_.project().plan.layers) {
    auto* item = new QTreeWidgetItem(tree_);
    item->setText(0, QString::fromStdString(layer.name));
    item->setText(1, QString::number(layer.entity_count));
    item->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable | Qt::ItemIsSelectable);
    item->setCheckState(2, layer.occluder ? Qt::Checked : Qt::Unchecked);
  }
  filling_ = false;
}

}  // namespace plenopath::widgets
