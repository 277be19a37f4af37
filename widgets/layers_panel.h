#pragma once
// The plan's layers with a "blocks sight" checkbox each; toggling one is an undoable edit.
#include <QWidget>

class QTreeWidget;

namespace plenopath::widgets {

class ProjectDocument;

class LayersPanel : public QWidget {
  Q_OBJECT
 public:
  explicit LayersPanel(ProjectDocument& document, QWidget* parent = nullptr);

 private:
  void refill();
  ProjectDocument& document_;
  QTreeWidget* tree_;
  bool filling_ = false;
};

}  // namespace plenopath::widgets
