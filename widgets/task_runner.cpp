#include "widgets/task_runner.h"

#include <QCoreApplication>
#include <QFutureWatcher>
#include <QTimer>
#include <QUndoStack>
#include <QtConcurrent>
#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "model/error.h"
#include "widgets/document_commands.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

void TaskProgress::report(double fraction, const std::string& stage) {
  const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  permille_ = static_cast<int>(f * 1000.0 + 0.5);
  if (!stage.empty()) {
    std::lock_guard<std::mutex> lock(message_mutex_);
    message_ = stage;
  }
  if (hook) hook(f, stage);
}

std::string TaskProgress::message() const {
  std::lock_guard<std::mutex> lock(message_mutex_);
  return message_;
}

// One run: what the worker shares with the GUI thread.
struct TaskRunner::Run {
  QString title;
  TaskProgress progress;
  TaskResult result;
  bool ok = false;
  bool cancelled = false;
  QString error;
  QFutureWatcher<void> watcher;
};

TaskRunner::TaskRunner(ProjectDocument& document, QObject* parent)
    : QObject(parent), document_(document), poll_timer_(new QTimer(this)) {
  poll_timer_->setInterval(100);
  connect(poll_timer_, &QTimer::timeout, this, [this] {
    if (run_) emit progress(run_->progress.fraction(), QString::fromStdString(run_->progress.message()));
  });
}

TaskRunner::~TaskRunner() {
  if (run_) {
    run_->progress.cancel();
    run_->watcher.waitForFinished();
  }
}

bool TaskRunner::start(const QString& title, TaskFunction task) {
  if (running_) return false;
  run_ = std::make_shared<Run>();
  run_->title = title;
  run_->progress.hook = report_hook_;
  running_ = true;
  std::shared_ptr<Run> run = run_;
  Project snapshot = document_.snapshot();
  connect(&run_->watcher, &QFutureWatcher<void>::finished, this, &TaskRunner::on_worker_done);
  run_->watcher.setFuture(
      QtConcurrent::run([run, task = std::move(task), snapshot = std::move(snapshot)]() mutable {
        // Top-level catch: nothing a task throws may escape the worker.
        try {
          run->result = task(std::move(snapshot), run->progress);
          // Cancelled too late to stop it: dropped all the same, as the author asked.
          run->cancelled = run->progress.is_cancelled();
          run->ok = !run->cancelled;
        } catch (const Cancelled&) {
          run->cancelled = true;
        } catch (const std::exception& e) {
          run->error = QString::fromStdString(e.what());
        } catch (...) {
          run->error = QObject::tr("unknown error");
        }
      }));
  poll_timer_->start();
  emit started(title);
  return true;
}

void TaskRunner::cancel() {
  if (run_) run_->progress.cancel();
}

void TaskRunner::set_report_hook(std::function<void(double fraction, const std::string& stage)> hook) {
  report_hook_ = std::move(hook);
}

void TaskRunner::wait() {
  while (running_) {
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
    if (run_ && run_->watcher.isFinished() && running_) QCoreApplication::processEvents();
  }
}

void TaskRunner::on_worker_done() {
  poll_timer_->stop();
  std::shared_ptr<Run> run = std::move(run_);
  running_ = false;
  if (!run) return;
  if (run->ok) {
    // The last word of the task ("exported 12 keyframes"), which the poll may have missed.
    emit progress(1.0, QString::fromStdString(run->progress.message()));
    if (run->result.changed != 0) {
      document_.undo_stack()->push(
          new ReplacePartsCommand(document_, run->title, run->result.project, run->result.changed));
      emit finished(true);
      return;
    }
  } else if (run->cancelled) {
    emit cancelled(run->title);
  } else if (!run->error.isEmpty()) {
    emit failed(run->title, run->error);
  }
  emit finished(false);
}

}  // namespace plenopath::widgets
