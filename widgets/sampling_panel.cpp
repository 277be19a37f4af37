#include "widgets/sampling_panel.h"

#include <QComboBox>
#include <QCoreApplication>
#include <QFormLayout>
#include <QLabel>
#include <QSlider>
#include <QTimer>
#include <QUndoStack>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <optional>

#include "model/error.h"
#include "processing/pipeline/sample_step.h"
#include "processing/sampling/keyframe_sampler.h"
#include "processing/sampling/sampling_session.h"
#include "processing/sampling/uniform_sampling.h"
#include "widgets/clean_plate_box.h"
#include "widgets/coalescing_runner.h"
#include "widgets/document_commands.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

namespace {
constexpr double kMinRatio = 2.0;
constexpr double kMaxRatio = 500.0;
constexpr int kSliderSteps = 200;
}  // namespace

// One request for the worker: a snapshot of the project and what to do with it.
struct SamplingPanel::Job {
  Project snapshot;
  SamplingRequest request;
  int merge_session = 0;
  SamplingOutcome outcome;  // filled by the worker
};

// What the worker keeps between runs. The runner (widgets/coalescing_runner.h) runs one job at a time, the
// newest request replacing one still waiting and stopping the running one; the session is touched only by
// the running job.
struct SamplingPanel::Worker {
  SamplingSession session;
  bool newest_is_sample = false;  // the newest request given to the runner resamples (else it measures)
  // The loss last measured, and for which keyframes.
  std::optional<SamplingOutcome> measured;
};

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
      statistics_(new QLabel(this)),
      progress_timer_(new QTimer(this)),
      worker_(std::make_unique<Worker>()),
      runner_(std::make_unique<CoalescingRunner>()) {
  // Item data: the method's name (model/enums.h), and ":cells" for the visibility cell rule.
  method_->addItem(tr("Uniform by arc length"), QString(to_string(SamplingMethod::kUniform)));
  method_->addItem(tr("Visibility: least expected loss"), QString(to_string(SamplingMethod::kVisibility)));
  method_->addItem(tr("Visibility: cells, l^k / v (seed)"), "visibility:cells");
  method_->addItem(tr("Depth: volume changes"), QString(to_string(SamplingMethod::kDepth)));
  method_->setToolTip(
      tr("How keyframes are chosen along the path. Visibility needs the visibility cells "
         "(Process > Compute visibility); depth needs the capture's depth maps."));
  budget_->setRange(0, kSliderSteps);
  budget_->setToolTip(tr("Budget: frames per keyframe (reduction ratio)"));
  exponent_->setRange(0, 50);  // 0.0 .. 5.0
  exponent_->setToolTip(tr("Exponent of the cell length in l^k / v (cell and depth sampling)"));
  boost_->setRange(0, 50);  // 0.0 .. 5.0
  boost_->setToolTip(tr("Extra samples where the cell size changes much between neighbouring cells"));
  statistics_->setWordWrap(true);
  statistics_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  progress_timer_->setInterval(150);
  connect(progress_timer_, &QTimer::timeout, this, [this] { update_statistics(); });
  connect(runner_.get(), &CoalescingRunner::failed, this,
          [this](const QString& error) { message_ = tr("Cannot sample: %1").arg(error); });
  connect(runner_.get(), &CoalescingRunner::job_finished, this, [this] {
    if (!runner_->busy()) progress_timer_->stop();
    update_statistics();
    emit worker_finished();
  });

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
  clean_plates_ = new CleanPlateBox(document_, this);
  layout->addWidget(clean_plates_);
  layout->addStretch(1);

  for (QSlider* s : {budget_, exponent_, boost_}) {
    connect(s, &QSlider::sliderPressed, this, [this] { drag_session_ = next_session_++; });
    connect(s, &QSlider::sliderReleased, this, [this] { drag_session_ = 0; });
    connect(s, &QSlider::valueChanged, this, [this, s] { on_control_changed(s); });
  }
  connect(method_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this] { on_control_changed(nullptr); });
  connect(&document_, &ProjectDocument::changed, this, [this](unsigned flags) {
    if (flags & (kKeyframesChanged | kPathChanged | kVisibilityChanged | kPlanChanged | kCaptureChanged)) {
      if (flags & (kVisibilityChanged | kCaptureChanged)) message_.clear();
      show_parameters(document_.project().keyframes.parameters);
      request_loss();
      update_statistics();
    }
  });
  show_parameters(document_.project().keyframes.parameters);
  request_loss();
  update_statistics();
}

SamplingPanel::~SamplingPanel() {
  runner_.reset();  // cancels and waits for the running job before the session goes
}

QString SamplingPanel::statistics_text() const { return statistics_->text(); }

bool SamplingPanel::busy() const { return runner_->busy(); }

void SamplingPanel::wait() { runner_->wait(); }

SamplingParameters SamplingPanel::parameters() const {
  SamplingParameters p = document_.project().keyframes.parameters;
  const QString data = method_->currentData().toString();
  p.method = enum_from_string<SamplingMethod>(data.section(':', 0, 0).toStdString());
  if (p.method == SamplingMethod::kVisibility)
    p.rule = data == "visibility:cells" ? VisibilityRule::cell_rule : VisibilityRule::expected_loss;
  p.count = 0;
  p.ratio = ratio_of_slider(budget_->value());
  p.exponent = exponent_->value() / 10.0;
  p.transition_boost = boost_->value() / 10.0;
  return p;
}

void SamplingPanel::show_parameters(const SamplingParameters& p) {
  showing_ = true;
  // The document records the method and, for visibility, the rule.
  const QString shown = p.method == SamplingMethod::kVisibility && p.rule == VisibilityRule::cell_rule
                            ? QString("visibility:cells")
                            : QString(to_string(p.method));
  const int method = method_->findData(shown);
  method_->setCurrentIndex(method >= 0 ? method : 0);
  budget_->setValue(slider_of_ratio(p.ratio));
  exponent_->setValue(static_cast<int>(std::lround(p.exponent * 10)));
  boost_->setValue(static_cast<int>(std::lround(p.transition_boost * 10)));
  showing_ = false;
  budget_label_->setText(tr("1 per %1").arg(ratio_of_slider(budget_->value()), 0, 'f', 0));
  exponent_label_->setText(QString::number(exponent_->value() / 10.0, 'f', 1));
  boost_label_->setText(QString::number(boost_->value() / 10.0, 'f', 1));
  // Exponent and boost shape the cell rule only (visibility cells and depth).
  const QString data = method_->currentData().toString();
  const bool cells = data == "visibility:cells" || data == "depth";
  exponent_->setEnabled(cells);
  boost_->setEnabled(cells);
}

void SamplingPanel::on_control_changed(QSlider* slider) {
  budget_label_->setText(tr("1 per %1").arg(ratio_of_slider(budget_->value()), 0, 'f', 0));
  exponent_label_->setText(QString::number(exponent_->value() / 10.0, 'f', 1));
  boost_label_->setText(QString::number(boost_->value() / 10.0, 'f', 1));
  const QString data = method_->currentData().toString();
  exponent_->setEnabled(data == "visibility:cells" || data == "depth");
  boost_->setEnabled(exponent_->isEnabled());
  if (showing_) return;
  resample(slider && slider->isSliderDown() ? drag_session_ : 0);
}

void SamplingPanel::resample(int merge_session) {
  const Project& p = document_.project();
  if (p.path.empty()) return;
  const SamplingParameters parameters = this->parameters();
  message_.clear();
  if (parameters.method == SamplingMethod::kUniform) {
    // Fast (no geometry): at once, so a slider drag follows the hand; the loss follows on the worker.
    Keyframes keyframes;
    try {
      SamplingInputs inputs;
      inputs.path = &p.path;
      keyframes = sample_keyframes(inputs, parameters, p.keyframes.pinned);
    } catch (const std::exception& e) {
      message_ = tr("Cannot sample: %1").arg(QString::fromStdString(e.what()));
      update_statistics();
      return;
    }
    if (worker_->newest_is_sample) runner_->cancel();  // a visibility/depth run would overwrite this choice
    worker_->newest_is_sample = false;
    if (!(keyframes == p.keyframes))
      document_.undo_stack()->push(new SetKeyframesCommand(document_, std::move(keyframes), merge_session));
    return;
  }
  if (parameters.method == SamplingMethod::kVisibility && p.visibility.empty()) {
    message_ = tr("Visibility sampling needs the visibility cells: run Process > Compute visibility first.");
    update_statistics();
    return;
  }
  if (parameters.method == SamplingMethod::kDepth && (p.capture.empty() || p.capture.depth_folder.empty())) {
    message_ = tr("Depth sampling needs the capture's depth maps: import the capture with its depth folder.");
    update_statistics();
    return;
  }
  Job job;
  job.snapshot = p;
  job.request.parameters = parameters;
  job.request.pinned = p.keyframes.pinned;
  job.merge_session = merge_session;
  start(std::move(job));
}

// Measure the loss of the document's keyframes unless it is known (or a resample will measure it).
void SamplingPanel::request_loss() {
  const Project& p = document_.project();
  if (p.path.empty() || p.keyframes.empty() || p.plan.occluder_segments().empty()) return;
  if (worker_->measured && worker_->measured->keyframes == p.keyframes) return;
  // A resample still waiting to start measures its own result.
  if (worker_->newest_is_sample && runner_->waiting()) return;
  Job job;
  job.snapshot = p;
  job.request.sample = false;
  job.request.keyframes = p.keyframes;
  start(std::move(job));
}

void SamplingPanel::start(Job job_in) {
  worker_->newest_is_sample = job_in.request.sample;
  auto job = std::make_shared<Job>(std::move(job_in));
  Worker* w = worker_.get();
  runner_->request([this, w, job](Progress& progress) -> CoalescingRunner::Delivery {
    pipeline::SampleStepOptions options;
    options.request = job->request;
    job->outcome = pipeline::run_sample(job->snapshot, options, progress, &w->session).outcome;
    return [this, job] { on_done(*job); };
  });
  progress_timer_->start();
  update_statistics();
}

// The newest job's result, on the GUI thread.
void SamplingPanel::on_done(const Job& job) {
  Worker* w = worker_.get();
  const Project& p = document_.project();
  if (job.request.sample) {
    w->newest_is_sample = false;
    // The project may have changed under the worker: a result for another path is resampled.
    if (!(job.snapshot.path == p.path) || !(job.snapshot.visibility == p.visibility) ||
        !(job.snapshot.plan == p.plan)) {
      resample(job.merge_session);
      return;
    }
    w->measured = job.outcome;
    if (!(job.outcome.keyframes == p.keyframes))
      document_.undo_stack()->push(
          new SetKeyframesCommand(document_, job.outcome.keyframes, job.merge_session));
  } else {
    w->measured = job.outcome;
    request_loss();  // the keyframes moved on meanwhile
  }
}

void SamplingPanel::update_statistics() {
  const Project& p = document_.project();
  if (p.path.empty()) {
    statistics_->setText(tr("No path yet: keyframes are sampled along the camera path."));
    return;
  }
  const SamplingStatistics s = sampling_statistics(p.path, p.keyframes);
  QString text;
  if (!message_.isEmpty()) text += "<b>" + message_.toHtmlEscaped() + "</b><br>";
  text += tr("<b>kept %1 of %2 frames</b><br>ratio %3 : 1<br>spacing mean %4 m, max gap %5 m")
              .arg(s.kept)
              .arg(s.total)
              .arg(s.ratio, 0, 'f', 1)
              .arg(s.mean_gap_m, 0, 'f', 2)
              .arg(s.max_gap_m, 0, 'f', 2);
  const Worker& w = *worker_;
  if (w.measured && w.measured->keyframes == p.keyframes && w.measured->loss.has_geometric)
    text += tr("<br>geometric loss mean %1, p95 %2")
                .arg(w.measured->loss.geometric.mean, 0, 'f', 3)
                .arg(w.measured->loss.geometric.p95, 0, 'f', 3);
  text += tr("<br>%1 visibility cells").arg(p.visibility.cells.size());
  if (runner_->busy())
    text += tr("<br><i>working: %1 %2 %</i>")
                .arg(QString::fromStdString(runner_->stage()))
                .arg(static_cast<int>(runner_->fraction() * 100));
  statistics_->setText(text);
}

}  // namespace plenopath::widgets
