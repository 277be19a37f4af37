#pragma once
// The one contract for long work (issue 17): a step reports the fraction done and what it is doing, and
// polls for cancellation, which ends the run with the one `Cancelled` error. The command line and the
// studio both implement it (a console line with Ctrl+C; the task runner's progress bar with Cancel).
//
//   void long_step(..., Progress& progress = null_progress()) {
//     for (int i = 0; i < n; ++i) {
//       progress.checkpoint(double(i) / n, "frame " + std::to_string(i));  // report, throw when cancelled
//       ...
//     }
//     refine(..., SubProgress(progress, 0.5, 1.0, "refinement"));          // a nested step's [0, 1]
//   }
//
// A step that is cancelled throws `Cancelled` and returns nothing: no partial result is applied anywhere.
// Inside a solver that must not be unwound by an exception (Ceres' iteration callback), poll
// is_cancelled(), stop the solver, and throw_if_cancelled() once it has returned.
// Every member is safe to call from several threads at once (reports from worker threads, cancel from the
// GUI or a signal handler), as long as the implementation's report() is.
#include <atomic>
#include <functional>
#include <mutex>
#include <string>

#include "model/error.h"

namespace plenopath {

// Ends a run that was cancelled. An Error, so that a top-level handler that knows nothing of cancellation
// still ends cleanly; handlers that do know catch Cancelled first and say "cancelled", never "failed".
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled") {}
};

class Progress {
 public:
  virtual ~Progress() = default;
  // fraction: of this step, in [0, 1] (clamped by the implementations); stage: what is being done now
  // ("reading frame 12 of 300"); empty = the same as before.
  virtual void report(double fraction, const std::string& stage = {}) = 0;
  virtual bool is_cancelled() const = 0;

  // Throws Cancelled when cancellation was requested.
  void throw_if_cancelled() const {
    if (is_cancelled()) throw Cancelled();
  }
  // report(), then throw_if_cancelled(): the usual call in a loop.
  void checkpoint(double fraction, const std::string& stage = {}) {
    report(fraction, stage);
    throw_if_cancelled();
  }
};

// For callers that do not care: reports go nowhere, never cancelled.
Progress& null_progress();

// Owns an atomic cancel flag: the base of the concrete progress sinks.
class CancellableProgress : public Progress {
 public:
  bool is_cancelled() const override { return cancelled_.load(std::memory_order_relaxed); }
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }

 private:
  std::atomic<bool> cancelled_{false};
};

// A nested step: its [0, 1] maps onto [begin, end] of the parent, its stage text is carried to the parent
// ("refinement: iteration 3"; a report without stage text names the sub-range's stage once, then keeps
// what the parent shows) and cancellation is the parent's. Cheap; make one per nested call.
class SubProgress final : public Progress {
 public:
  SubProgress(Progress& parent, double begin, double end, std::string stage = {});
  void report(double fraction, const std::string& stage = {}) override;
  bool is_cancelled() const override { return parent_.is_cancelled(); }
  // Where `fraction` of this range lands in the parent's [0, 1].
  double parent_fraction(double fraction) const;

 private:
  Progress& parent_;
  double begin_, end_;
  std::string stage_;
  std::atomic<bool> named_{false};
};

// Reports to a function (tests, adapters at a boundary that has its own display), one call at a time even
// from several threads; cancel() cancels (also from inside the function).
class FunctionProgress final : public CancellableProgress {
 public:
  using Function = std::function<void(double fraction, const std::string& stage)>;
  explicit FunctionProgress(Function on_report = {}) : on_report_(std::move(on_report)) {}
  void report(double fraction, const std::string& stage = {}) override;

 private:
  Function on_report_;
  std::mutex mutex_;
};

}  // namespace plenopath
