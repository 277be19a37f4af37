#pragma once
// Long work off the GUI thread. A task receives a SNAPSHOT of the project (never the live document) and a
// TaskProgress to report to and poll for cancellation; it returns the changed project and which parts it
// changed. The runner applies the result as one undoable ReplacePartsCommand, or drops it when cancelled.
// Every exception a task throws is caught on the worker and arrives as `failed(message)`.
#include <QObject>
#include <QString>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "model/project.h"

class QTimer;

namespace plenopath::widgets {

class ProjectDocument;

// Shared between the GUI and the worker: progress out, cancellation in.
class TaskProgress {
 public:
  // fraction in [0, 1]; message optional ("frame 120 of 3000").
  void report(double fraction, const std::string& message = {});
  bool cancelled() const { return cancel_requested_.load(); }
  // Throws TaskCancelled when cancellation was requested: call it in loops.
  void throw_if_cancelled() const;

  void request_cancel() { cancel_requested_ = true; }
  double fraction() const { return permille_.load() / 1000.0; }
  std::string message() const;

 private:
  std::atomic<bool> cancel_requested_{false};
  std::atomic<int> permille_{0};
  mutable std::mutex message_mutex_;
  std::string message_;
};

struct TaskCancelled {};

struct TaskResult {
  Project project;       // the snapshot, changed
  unsigned changed = 0;  // ChangeFlag bits of the parts to apply
};
using TaskFunction = std::function<TaskResult(Project snapshot, TaskProgress& progress)>;

class TaskRunner : public QObject {
  Q_OBJECT
 public:
  explicit TaskRunner(ProjectDocument& document, QObject* parent = nullptr);
  ~TaskRunner() override;  // cancels and waits for a running task

  // Starts `task` on a worker thread with a snapshot of the document. Returns false (and does nothing)
  // while another task runs. `title` names the undo step ("Compute visibility").
  bool start(const QString& title, TaskFunction task);
  bool is_running() const { return running_; }
  // Asks the task to stop; `finished(false)` follows once the worker returns.
  void cancel();
  // Blocks (processing events) until no task runs; for tests and for closing the window.
  void wait();

 signals:
  void started(const QString& title);
  void progress(double fraction, const QString& message);
  void finished(bool applied);  // applied: the result became an undo step
  void failed(const QString& title, const QString& message);

 private:
  struct Run;
  void on_worker_done();

  ProjectDocument& document_;
  std::shared_ptr<Run> run_;
  QTimer* poll_timer_;
  bool running_ = false;
};

}  // namespace plenopath::widgets
