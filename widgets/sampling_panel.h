#pragma once
// Keyframe sampling: method (uniform, visibility by expected loss or by the seed's cell rule, depth),
// budget, exponent and transition boost, with live statistics including the geometric loss. Moving a
// control resamples and pushes one undoable SetKeyframesCommand; a slider drag merges into one undo step.
// Uniform sampling runs at once; visibility and depth sampling and the loss measures run on a worker
// (processing/sampling/sampling_session.h keeps envelopes and depth volumes between runs) through a
// CoalescingRunner (the newest request wins), so the panel never blocks the editor.
#include <QString>
#include <QWidget>
#include <memory>

#include "model/keyframes.h"

class QComboBox;
class QLabel;
class QSlider;
class QTimer;

namespace plenopath::widgets {

class CleanPlateBox;
class CoalescingRunner;
class ProjectDocument;

class SamplingPanel : public QWidget {
  Q_OBJECT
 public:
  explicit SamplingPanel(ProjectDocument& document, QWidget* parent = nullptr);
  ~SamplingPanel() override;  // cancels and waits for the worker

  QSlider* budget_slider() const { return budget_; }
  QSlider* exponent_slider() const { return exponent_; }
  QSlider* boost_slider() const { return boost_; }
  QComboBox* method_box() const { return method_; }
  // How keyframes are exported: without people and rig, the nadir patch, faces (clean_plate_box.h).
  CleanPlateBox* clean_plate_box() const { return clean_plates_; }
  QString statistics_text() const;

  // The parameters the controls show now.
  SamplingParameters parameters() const;
  // Resamples with the controls' parameters and pushes the result (merge_session 0 = its own undo step).
  // Visibility and depth sampling finish later, on the worker.
  void resample(int merge_session);
  // Whether the worker is sampling or measuring the loss; wait() lets events run until it is done
  // (tests, the command line's --resample).
  bool busy() const;
  void wait();

  // Slider value <-> reduction ratio (frames per keyframe), logarithmic from 2 to 500.
  static double ratio_of_slider(int value);
  static int slider_of_ratio(double ratio);

 signals:
  // A worker run ended (keyframes pushed, loss measured, failed or superseded).
  void worker_finished();

 private:
  struct Worker;
  struct Job;
  void show_parameters(const SamplingParameters& parameters);
  void update_statistics();
  void on_control_changed(QSlider* slider);
  void request_loss();
  void start(Job job);
  void on_done(const Job& job);

  ProjectDocument& document_;
  QComboBox* method_;
  QSlider* budget_;
  QSlider* exponent_;
  QSlider* boost_;
  QLabel* budget_label_;
  QLabel* exponent_label_;
  QLabel* boost_label_;
  QLabel* statistics_;
  QTimer* progress_timer_;
  CleanPlateBox* clean_plates_;
  int next_session_ = 1;
  int drag_session_ = 0;
  bool showing_ = false;  // controls are being set from the document: no resampling
  QString message_;       // why the last resample could not run ("" = none)

  std::unique_ptr<Worker> worker_;
  std::unique_ptr<CoalescingRunner> runner_;  // newest request wins (widgets/coalescing_runner.h)
};

}  // namespace plenopath::widgets
