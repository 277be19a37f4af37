#include "widgets/task_runner.h"

#include <QCoreApplication>
#include <QFutureWatcher>
#include <QTimer>
#include <QUndoStack>
#include <QtConcurrent>
#include <algorithm>
#include <exception>
#include <utility>

#include "model/error.h"
#include "widgets/document_commands.h"
#include "widgets/project_document.h"

namespace plenopath::widgets {

void TaskProgress::report(double fraction, const std::string& message) {
  permille_ = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 1000.0 + 0.5);
  if (!message.empty()) {
    std::lock_guard<std::mutex> lock(message_mutex_);
    message_ = message;
  }
}

void TaskProgress::throw_if_cancelled() const {
  if (cancelled()) throw TaskCancelled{};
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
    run_->progress.request_cancel();
    run_->watcher.waitForFinished();
  }
}

bool TaskRunner::start(const QString& title, TaskFunction task) {
  if (running_) return false;
  run_ = std::make_shared<Run>();
  run_->title = title;
  running_ = true;
  std::shared_ptr<Run> run = run_;
  Project snapshot = document_.snapshot();
  connect(&run_->watcher, &QFutureWatcher<void>::finished, this, &TaskRunner::on_worker_done);
  run_->watcher.setFuture(
      QtConcurrent::run([run, task = std::move(task), snapshot = std::move(snapshot)]() mutable {
        // Top-level catch: nothing a task throws may escape the worker.
        try {
          run->result = task(std::move(snapshot), run->progress);
          run->ok = !run->progress.cancelled();
          run->cancelled = run->progress.cancelled();
        } catch (const TaskCancelled&) {
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
  if (run_) run_->progress.request_cancel();
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
  if (run->ok && run->result.changed != 0) {
    document_.undo_stack()->push(
        new ReplacePartsCommand(document_, run->title, run->result.project, run->result.changed));
    emit finished(true);
    return;
  }
  if (!run->error.isEmpty()) emit failed(run->title, run->error);
  emit finished(false);
}

}  // namespace plenopath::widgets
