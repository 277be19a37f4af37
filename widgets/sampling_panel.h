#pragma once
// Keyframe sampling: method, budget, exponent and transition boost, with live statistics. Moving a
// control resamples at once (processing/) and pushes one undoable SetKeyframesCommand; a slider drag merges
// into one undo step.
#include <QWidget>

#include "model/keyframes.h"

class QComboBox;
class QLabel;
class QSlider;

namespace plenopath::widgets {

class ProjectDocument;

class SamplingPanel : public QWidget {
  Q_OBJECT
 public:
  explicit SamplingPanel(ProjectDocument& document, QWidget* parent = nullptr);

  QSlider* budget_slider() const { return budget_; }
  QSlider* exponent_slider() const { return exponent_; }
  QSlider* boost_slider() const { return boost_; }
  QComboBox* method_box() const { return method_; }

  // The parameters the controls show now.
  SamplingParameters parameters() const;
  // Resamples with the controls' parameters and pushes the result (merge_session 0 = its own undo step).
  void resample(int merge_session);

  // Slider value <-> reduction ratio (frames per keyframe), logarithmic from 2 to 500.
  static double ratio_of_slider(int value);
  static int slider_of_ratio(double ratio);

 private:
  void show_parameters(const SamplingParameters& parameters);
  void update_statistics();
  void on_control_changed(QSlider* slider);

  ProjectDocument& document_;
  QComboBox* method_;
  QSlider* budget_;
  QSlider* exponent_;
  QSlider* boost_;
  QLabel* budget_label_;
  QLabel* exponent_label_;
  QLabel* boost_label_;
  QLabel* statistics_;
  int next_session_ = 1;
  int drag_session_ = 0;
  bool showing_ = false;  // controls are being set from the document: no resampling
};

}  // namespace plenopath::widgets
