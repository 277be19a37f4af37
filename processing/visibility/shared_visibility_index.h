#pragma once
// The visibility index of one plan, built once, on first use, by whichever thread asks first (the others
// wait for it), then shared read-only: VisibilityIndex's const methods may be called from several threads.
// The studio's document hands one out per plan revision (widgets/project_document.h), so that the map's
// envelopes, the timeline's profile and the cells that follow an anchor edit share one index instead of
// each building its own (a second or more on a large plan). Ask for it on a worker: get() may build.
#include <atomic>
#include <memory>
#include <mutex>
#include <string>

#include "model/floor_plan.h"

namespace plenopath {

class VisibilityIndex;

class SharedVisibilityIndex {
 public:
  // `builds`, when given, counts the indexes actually built (tests and the studio's statistics).
  explicit SharedVisibilityIndex(FloorPlan plan, std::shared_ptr<std::atomic<int>> builds = nullptr);
  ~SharedVisibilityIndex();
  SharedVisibilityIndex(const SharedVisibilityIndex&) = delete;
  SharedVisibilityIndex& operator=(const SharedVisibilityIndex&) = delete;

  // The index of the plan, built by the first call (which blocks for the build; calls from other threads
  // meanwhile wait for it and get the same). Null when the plan has no occluders or the index cannot be
  // built (error() says why); the build is not tried again.
  std::shared_ptr<const VisibilityIndex> get() const;
  // Whether get() has finished once (never blocks).
  bool ready() const { return ready_.load(); }
  // Why get() returned null ("" when it did not, or before it was called).
  std::string error() const;
  const FloorPlan& plan() const { return plan_; }

 private:
  const FloorPlan plan_;
  std::shared_ptr<std::atomic<int>> builds_;
  mutable std::mutex mutex_;
  mutable bool tried_ = false;
  mutable std::atomic<bool> ready_{false};
  mutable std::shared_ptr<const VisibilityIndex> index_;
  mutable std::string error_;
};

}  // namespace plenopath
