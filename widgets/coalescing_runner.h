#pragma once
// Background work where only the newest request matters (the map's envelope index, the timeline's
// profiles, the sampling panel's resampling, anchor edits): one worker at a time, off the GUI thread.
//   - a request replaces the one still waiting (it never runs);
//   - a running job is cancelled through its Progress when a newer request arrives, and the newer one
//     starts once it has returned, so jobs never overlap (a job may keep state between runs);
//   - the result of a job that is no longer the newest request is dropped;
//   - results are delivered on the GUI thread (the runner's thread).
// A job runs on the worker with a Progress to report to and poll (processing/util/progress.h); it must not
// touch the live document: give it a snapshot, or the shared pointers it needs, in its closure. It returns
// the delivery: a function called on the GUI thread when the job is still the newest request. A job that
// ends with Cancelled is dropped silently; any other exception arrives as `failed(message)` (when newest).
#include <QObject>
#include <QString>
#include <functional>
#include <memory>
#include <string>

#include "processing/util/progress.h"

class QThreadPool;

namespace plenopath::widgets {

class CoalescingRunner : public QObject {
  Q_OBJECT
 public:
  using Delivery = std::function<void()>;
  using Job = std::function<Delivery(Progress& progress)>;

  explicit CoalescingRunner(QObject* parent = nullptr);
  ~CoalescingRunner() override;  // drops the waiting request, cancels the running job and waits for it

  // Starts `job` now when idle; otherwise it waits, replacing the request that waited, and the running
  // job is asked to stop.
  void request(Job job);
  // Drops the waiting request and asks the running job to stop; nothing is delivered.
  void cancel();
  // A job runs or waits.
  bool busy() const;
  // A request waits for the running job to return.
  bool waiting() const { return waiting_ != nullptr; }
  // Lets events run until idle (tests, closing).
  void wait();

  // The running job's progress (0 and "" when none runs).
  double fraction() const;
  std::string stage() const;
  // Jobs started since construction (tests: a burst of requests runs at most two).
  int started_count() const { return started_; }

 signals:
  // A job returned and the runner moved on (its result delivered, dropped or failed).
  void job_finished();
  // The newest request's job failed (not cancelled): what it threw.
  void failed(const QString& message);

 private:
  struct Run;
  void launch(Job job);
  void on_done(std::shared_ptr<Run> run);

  std::unique_ptr<QThreadPool> pool_;  // one thread: jobs never overlap
  std::shared_ptr<Run> running_;
  std::unique_ptr<Job> waiting_;
  unsigned long long newest_ = 0;  // sequence number of the newest request
  int started_ = 0;
};

}  // namespace plenopath::widgets
