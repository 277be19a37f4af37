#include "widgets/coalescing_runner.h"

#include <QCoreApplication>
#include <QThread>
#include <QThreadPool>
#include <exception>
#include <utility>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include "widgets/task_runner.h"

namespace plenopath::widgets {

namespace {

// Background work yields the processor to the GUI thread (and the renderer's threads): the worker thread
// and the threads it starts (cells, Ceres; they inherit it) run at nice 10. On two cores an anchor edit's
// refinement and cells otherwise slowed the map's redraw during the edit to over 100 ms.
void lower_this_threads_priority() {
#ifdef __linux__
  static thread_local const bool lowered =
      setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10) == 0;
  (void)lowered;
#endif
}

}  // namespace

// What a running job shares with the GUI thread.
struct CoalescingRunner::Run {
  unsigned long long sequence = 0;
  TaskProgress progress;
  Delivery delivery;
  bool ok = false;
  QString error;  // set when the job threw something other than Cancelled
};

CoalescingRunner::CoalescingRunner(QObject* parent)
    : QObject(parent), pool_(std::make_unique<QThreadPool>()) {
  pool_->setMaxThreadCount(1);
  pool_->setExpiryTimeout(-1);  // keep the thread: requests come in bursts
}

CoalescingRunner::~CoalescingRunner() {
  waiting_.reset();
  if (running_) running_->progress.cancel();
  pool_->waitForDone();
  // The worker's queued call to on_done dies with this object; the job's delivery is never called.
}

void CoalescingRunner::request(Job job) {
  ++newest_;
  if (running_) {
    running_->progress.cancel();  // stale now; the newest starts once it has returned
    waiting_ = std::make_unique<Job>(std::move(job));
    return;
  }
  launch(std::move(job));
}

void CoalescingRunner::cancel() {
  ++newest_;  // whatever runs now is stale
  waiting_.reset();
  if (running_) running_->progress.cancel();
}

bool CoalescingRunner::busy() const { return running_ != nullptr || waiting_ != nullptr; }

void CoalescingRunner::wait() {
  while (busy()) {
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
    if (busy()) QThread::msleep(1);
  }
}

double CoalescingRunner::fraction() const { return running_ ? running_->progress.fraction() : 0.0; }

std::string CoalescingRunner::stage() const {
  return running_ ? running_->progress.message() : std::string();
}

void CoalescingRunner::launch(Job job) {
  auto run = std::make_shared<Run>();
  run->sequence = newest_;
  running_ = run;
  ++started_;
  QThreadPool* pool = pool_.get();
  pool->start([this, run, job = std::move(job)] {
    lower_this_threads_priority();
    // Top-level catch: nothing a job throws escapes the worker.
    try {
      run->delivery = job(run->progress);
      run->ok = !run->progress.is_cancelled();
    } catch (const Cancelled&) {
    } catch (const std::exception& e) {
      run->error = QString::fromStdString(e.what());
    } catch (...) {
      run->error = QStringLiteral("unknown error");
    }
    // Back on the GUI thread; dropped when the runner is gone (its destructor waits for this thread).
    QMetaObject::invokeMethod(
        this, [this, run] { on_done(run); }, Qt::QueuedConnection);
  });
}

void CoalescingRunner::on_done(std::shared_ptr<Run> run) {
  if (running_ == run) running_.reset();
  const bool newest = run->sequence == newest_;
  if (waiting_) {
    // A newer request waited: this result is stale.
    std::unique_ptr<Job> next = std::move(waiting_);
    launch(std::move(*next));
  } else if (newest && run->ok && run->delivery) {
    // The delivery may request again (it runs with the runner idle).
    run->delivery();
  } else if (newest && !run->error.isEmpty()) {
    emit failed(run->error);
  }
  emit job_finished();
}

}  // namespace plenopath::widgets
