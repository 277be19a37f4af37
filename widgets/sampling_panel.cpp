#include "widgets/sampling_panel.h"

#include <QComboBox>
#include <QFormLayout>
#include <QLabel>
#include <QMessageBox>
#include <QSlider>
#include <QUndoStack>
#include <QVBoxLayout>
#include <cmath>
#include <exception>

#include "processing/uniform_sampling.h"
#include "widgets/document_commands.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {
constexpr double kMinRatio = 2.0;
constexpr double kMaxRatio = 500.0;
constexpr int kSliderSteps = 200;
}  // namespace

double SamplingPanel::ratio_of_slider(int value) {
  return kMinRatio * std::pow(kMaxRatio / kMinRatio, value / static_cast<double>(kSliderSteps));
}

int SamplingPanel::slider_of_ratio(double ratio) {
  const double t = std::log(std::max(kMinRatio, ratio) / kMinRatio) / std::log(kMaxRatio / kMinRatio);
  return std::clamp(static_cast<int>(std::lround(t * kSliderSteps)), 0, kSliderSteps);
}

SamplingPanel::SamplingPanel(ProjectDocument& document, QWidget* parent)
    : QWidget(parent),
      document_(document),
      method_(new QComboBox(this)),
      budget_(new QSlider(Qt::Horizontal, this)),
      exponent_(new QSlider(Qt::Horizontal, this)),
      boost_(new QSlider(Qt::Horizontal, this)),
      budget_label_(new QLabel(this)),
      exponent_label_(new QLabel(this)),
      boost_label_(new QLabel(this)),
      statistics_(new QLabel(this)) {
  method_->addItem(tr("Uniform by arc length"), "uniform");
  method_->setToolTip(tr("How keyframes are chosen along the path"));
  budget_->setRange(0, kSliderSteps);
  budget_->setToolTip(tr("Budget: frames per keyframe (reduction ratio)"));
  exponent_->setRange(10, 50);  // 1.0 .. 5.0
  exponent_->setToolTip(tr("Exponent of the cell length in l^k / v (visibility sampling)"));
  boost_->setRange(0, 50);  // 0.0 .. 5.0
  boost_->setToolTip(tr("Extra samples where the envelope changes much between cells"));
  statistics_->setWordWrap(true);
  statistics_->setTextInteractionFlags(Qt::TextSelectableByMouse);

  auto* form = new QFormLayout;
  form->addRow(tr("Method"), method_);
  auto row = [&](QSlider* slider, QLabel* label) {
    auto* w = new QWidget(this);
    auto* l = new QHBoxLayout(w);
    l->setContentsMargins(0, 0, 0, 0);
    l->addWidget(slider, 1);
    label->setMinimumWidth(70);
    l->addWidget(label);
    return w;
  };
  form->addRow(tr("Budget"), row(budget_, budget_label_));
  form->addRow(tr("Exponent"), row(exponent_, exponent_label_));
  form->addRow(tr("Transition boost"), row(boost_, boost_label_));
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(statistics_);
  layout->addStretch(1);

  for (QSlider* s : {budget_, exponent_, boost_}) {
    connect(s, &QSlider::sliderPressed, this, [this] { drag_session_ = next_session_++; });
    connect(s, &QSlider::sliderReleased, this, [this] { drag_session_ = 0; });
    connect(s, &QSlider::valueChanged, this, [this, s] { on_control_changed(s); });
  }
  connect(method_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] { on_control_changed(nullptr); });
  connect(&document_, &ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & (kKeyframesChanged | kPathChanged | kVisibilityChanged)) {
      show_parameters(document_.project().keyframes.parameters);
      update_statistics();
    }
  });
  show_parameters(document_.project().keyframes.parameters);
  update_statistics();
}

SamplingParameters SamplingPanel::parameters() const {
  SamplingParameters p = document_.project().keyframes.parameters;
  p.method = method_->currentData().toString().toStdString();
  p.count = 0;
  p.ratio = ratio_of_slider(budget_->value());
  p.exponent = exponent_->value() / 10.0;
  p.transition_boost = boost_->value() / 10.0;
  return p;
}

void SamplingPanel::show_parameters(const SamplingParameters& p) {
  showing_ = true;
  const int method = method_->findData(QString::fromStdString(p.method));
  method_->setCurrentIndex(method >= 0 ? method : 0);
  budget_->setValue(slider_of_ratio(p.ratio));
  exponent_->setValue(static_cast<int>(std::lround(p.exponent * 10)));
  boost_->setValue(static_cast<int>(std::lround(p.transition_boost * 10)));
  showing_ = false;
  budget_label_->setText(tr("1 per %1").arg(ratio_of_slider(budget_->value()), 0, 'f', 0));
  exponent_label_->setText(QString::number(exponent_->value() / 10.0, 'f', 1));
  boost_label_->setText(QString::number(boost_->value() / 10.0, 'f', 1));
  // Exponent and boost shape visibility sampling only.
  const bool uniform = method_->currentData().toString() == "uniform";
  exponent_->setEnabled(!uniform);
  boost_->setEnabled(!uniform);
}

void SamplingPanel::on_control_changed(QSlider* slider) {
  budget_label_->setText(tr("1 per %1").arg(ratio_of_slider(budget_->value()), 0, 'f', 0));
  exponent_label_->setText(QString::number(exponent_->value() / 10.0, 'f', 1));
  boost_label_->setText(QString::number(boost_->value() / 10.0, 'f', 1));
  if (showing_) return;
  resample(slider && slider->isSliderDown() ? drag_session_ : 0);
}

void SamplingPanel::resample(int merge_session) {
  const Project& p = document_.project();
  if (p.path.empty()) return;
  Keyframes keyframes;
  try {
    keyframes = sample_uniform_by_arc_length(p.path, parameters(), p.keyframes.pinned);
    keyframes.parameters = parameters();
  } catch (const std::exception& e) {
    statistics_->setText(tr("Cannot sample: %1").arg(QString::fromStdString(e.what())));
    return;
  }
  if (keyframes == p.keyframes) return;
  document_.undo_stack()->push(new SetKeyframesCommand(document_, std::move(keyframes), merge_session));
}

void SamplingPanel::update_statistics() {
  const Project& p = document_.project();
  if (p.path.empty()) {
    statistics_->setText(tr("No path yet: keyframes are sampled along the camera path."));
    return;
  }
  const SamplingStatistics s = sampling_statistics(p.path, p.keyframes);
  statistics_->setText(tr("<b>kept %1 of %2 frames</b><br>ratio %3 : 1<br>spacing mean %4 m, max %5 m"
                          "<br>%6 visibility cells")
                           .arg(s.kept)
                           .arg(s.total)
                           .arg(s.ratio, 0, 'f', 1)
                           .arg(s.mean_gap_m, 0, 'f', 2)
                           .arg(s.max_gap_m, 0, 'f', 2)
                           .arg(p.visibility.cells.size()));
}

}  // namespace plenopath::widgets
