#pragma once
// Importing a DXF floor plan: the file, its units (what the file says, or the author's choice), the layers
// with a "blocks sight" checkbox each (pre-set from the importer's proposal, with its reason), a preview of
// the plan as it will be imported with the envelope of a clicked point, and the import report.
//
// The file is read on a worker thread and so is the envelope (building a visibility index for a big plan
// takes seconds): the dialog never freezes, a busy bar shows after a moment, and the newest request wins
// (at most one job of each kind runs; requests made meanwhile coalesce into one that runs next). Toggling a
// layer does not re-read the file: it sets the occluder flags on the plan and recomputes the envelope.
#include <QDialog>
#include <QFutureWatcher>
#include <QString>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "model/floor_plan.h"
#include "processing/plan/dxf_import.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QTableWidget;
class QToolButton;
class QTreeWidget;

namespace plenopath {
class VisibilityIndex;
}

namespace plenopath::widgets {

class PlanPreview;

class DxfImportDialog : public QDialog {
  Q_OBJECT
 public:
  explicit DxfImportDialog(QWidget* parent = nullptr, const QString& file = {});
  ~DxfImportDialog() override;

  // The plan with the chosen units and occluder layers; valid after the dialog was accepted.
  const FloorPlan& plan() const { return plan_; }
  QString file() const;
  const DxfImportReport& report() const { return report_; }
  // Starts reading `file` (the result arrives later; messages in the dialog, never thrown).
  void set_file(const QString& file);
  // An import or an envelope is being computed, or one is waiting to run.
  bool busy() const;

  // Table columns.
  enum Column { kLayerColumn, kEntitiesColumn, kBlocksSightColumn, kStateColumn, kWhyColumn, kColumns };

 signals:
  void plan_loaded();     // an import finished (a plan, or an error message) and is shown
  void envelope_shown();  // an envelope (or a state such as "on a wall") is shown for the marked point

 private:
  struct ImportOutcome;
  struct EnvelopeOutcome;

  void request_import();
  void start_import();
  void on_import_finished();
  void show_import(const ImportOutcome& outcome);
  void request_envelope();
  void start_envelope();
  void on_envelope_finished();
  void fill_layers();
  void fill_units();
  void fill_report();
  void apply_occluders();
  void update_ok();
  void update_busy();
  void show_plan_note();

  // Widgets.
  QLineEdit* file_edit_;
  QComboBox* units_;
  QLabel* units_reason_;
  QTableWidget* layers_;
  PlanPreview* preview_;
  QLabel* stray_label_;
  QCheckBox* keep_stray_;
  QLabel* summary_;
  QToolButton* details_button_;
  QWidget* details_;
  QLabel* details_text_;
  QTreeWidget* skipped_;
  QProgressBar* busy_bar_;
  QLabel* status_;
  QPushButton* ok_;

  // The plan shown and what the importer said about it.
  FloorPlan plan_;
  DxfImportReport report_;
  QString loaded_file_;  // the file plan_ came from ("" = none)
  QString error_;        // why the last import failed ("" = it did not)
  // What the file says about its units, kept while the author tries other units.
  QString file_units_, file_units_source_, file_units_reason_;
  // The author's ticks, kept across re-imports of the same file (units, stray entities).
  std::map<std::string, bool> chosen_occluders_;
  bool filling_ = false;

  // The import worker: newest request wins.
  QFutureWatcher<std::shared_ptr<ImportOutcome>> import_watcher_;
  int import_requested_ = 0;     // id of the newest request
  bool import_running_ = false;  // started, its finished() not handled yet
  bool import_pending_ = false;  // a request came while one was running

  // The envelope worker. occluders_key_ changes with the plan and its occluder flags; the index built for
  // a key is kept so that clicking elsewhere does not rebuild it.
  QFutureWatcher<std::shared_ptr<EnvelopeOutcome>> envelope_watcher_;
  int envelope_requested_ = 0;
  bool envelope_running_ = false;
  bool envelope_pending_ = false;
  std::uint64_t occluders_key_ = 0;
  std::uint64_t index_key_ = ~std::uint64_t{0};
  std::shared_ptr<const VisibilityIndex> index_;
};

}  // namespace plenopath::widgets
