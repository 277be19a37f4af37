#pragma once
// Long work off the GUI thread. A task receives a SNAPSHOT of the project (never the live document) and a
// Progress (processing/util/progress.h) to report to and poll for cancellation; it returns the changed
// project and which parts it changed. The runner applies the result as one undoable ReplacePartsCommand.
// Cancel sets the Progress' flag; a task that then ends by Cancelled (or returns anyway) is dropped and
// arrives as `cancelled(title)`, never as a failure. Every other exception a task throws is caught on the
// worker and arrives as `failed(title, message)`.
#include <QObject>
#include <QString>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "model/project.h"
#include "processing/util/progress.h"

class QTimer;

namespace plenopath::widgets {

class ProjectDocument;

// Shared between the GUI and the worker: progress out, cancellation in.
class TaskProgress final : public CancellableProgress {
 public:
  // fraction in [0, 1]; stage optional ("frame 120 of 3000"), empty keeps the last.
  void report(double fraction, const std::string& stage = {}) override;
  double fraction() const { return permille_.load() / 1000.0; }
  std::string message() const;
  // Tests: called on the worker inside every report (a test pauses a task there to cancel it).
  std::function<void(double fraction, const std::string& stage)> hook;

 private:
  std::atomic<int> permille_{0};
  mutable std::mutex message_mutex_;
  std::string message_;
};

struct TaskResult {
  Project project;       // the snapshot, changed
  unsigned changed = 0;  // ChangeFlag bits of the parts to apply
};
using TaskFunction = std::function<TaskResult(Project snapshot, Progress& progress)>;

class TaskRunner : public QObject {
  Q_OBJECT
 public:
  explicit TaskRunner(ProjectDocument& document, QObject* parent = nullptr);
  ~TaskRunner() override;  // cancels and waits for a running task

  // Starts `task` on a worker thread with a snapshot of the document. Returns false (and does nothing)
  // while another task runs. `title` names the undo step ("Compute visibility").
  bool start(const QString& title, TaskFunction task);
  bool is_running() const { return running_; }
  // Asks the task to stop; `cancelled(title)` and `finished(false)` follow once the worker returns.
  void cancel();
  // Tests: called on the worker thread inside every report of the tasks started from now on.
  void set_report_hook(std::function<void(double fraction, const std::string& stage)> hook);
  // Blocks (processing events) until no task runs; for tests and for closing the window.
  void wait();

 signals:
  void started(const QString& title);
  void progress(double fraction, const QString& message);
  void finished(bool applied);  // applied: the result became an undo step
  void failed(const QString& title, const QString& message);
  void cancelled(const QString& title);  // before finished(false)

 private:
  struct Run;
  void on_worker_done();

  ProjectDocument& document_;
  std::shared_ptr<Run> run_;
  QTimer* poll_timer_;
  bool running_ = false;
  std::function<void(double, const std::string&)> report_hook_;
};

}  // namespace plenopath::widgets
