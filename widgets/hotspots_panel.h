#pragma once
// The Hotspots dock: the document's hotspots in a list (with a warning mark where validation found a
// problem), the selected one's properties (name, kind, media, trigger, action and its target) edited through
// undoable commands, its validation warnings as plain text, New / Go to / Delete buttons. Selecting a hotspot
// here selects it in the panorama view and moves there to a frame that sees it.
#include <QString>
#include <QWidget>
#include <functional>
#include <string>
#include <vector>

#include "processing/hotspots/hotspot_validation.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QPushButton;
class QTimer;

namespace plenopath::widgets {

class HotspotEditor;
class ProjectDocument;

class HotspotsPanel : public QWidget {
  Q_OBJECT
 public:
  HotspotsPanel(ProjectDocument& document, HotspotEditor& editor, QWidget* parent = nullptr);

  // Warnings of all hotspots as of the last check (checks run shortly after each change).
  const std::vector<HotspotWarning>& warnings() const { return warnings_; }
  // Runs the check now (tests; the panel otherwise waits for edits to settle).
  void validate_now();

  // Tests replace the file dialogs: returns the chosen file or "" (cancelled). `what` is "media" or "target".
  std::function<QString(const QString& what, const QString& current)> ask_file;

  QListWidget* list() const { return list_; }
  QLineEdit* title_edit() const { return title_; }
  QLineEdit* media_edit() const { return media_; }
  QComboBox* action_box() const { return action_; }
  QLineEdit* target_edit() const { return target_; }
  QLabel* warnings_label() const { return warning_text_; }

 private:
  void rebuild_list();
  void show_selected();
  // Applies `edit` to a copy of the selected hotspot and pushes it as one undoable step; edits of the same
  // field in a row merge.
  void edit_selected(const QString& field, const std::function<void(Hotspot&)>& edit);
  const Hotspot* selected_hotspot() const;

  ProjectDocument& document_;
  HotspotEditor& editor_;
  QListWidget* list_;
  QLineEdit* title_;
  QComboBox* kind_;
  QLineEdit* media_;
  QPushButton* choose_media_;
  QComboBox* trigger_;
  QDoubleSpinBox* distance_;
  QComboBox* action_;
  QLineEdit* target_;
  QPushButton* choose_target_;
  QLabel* info_;
  QLabel* warning_text_;
  QLabel* summary_;
  QPushButton* goto_;
  QPushButton* delete_;
  QCheckBox* play_;
  QTimer* validate_timer_;
  std::vector<HotspotWarning> warnings_;
  bool updating_ = false;
  QString last_field_;
  int merge_session_ = 0;
};

}  // namespace plenopath::widgets
