#include "processing/visibility/shared_visibility_index.h"

#include <exception>
#include <utility>

#include "processing/visibility/visibility.h"

namespace plenopath {

SharedVisibilityIndex::SharedVisibilityIndex(FloorPlan plan, std::shared_ptr<std::atomic<int>> builds)
    : plan_(std::move(plan)), builds_(std::move(builds)) {}

SharedVisibilityIndex::~SharedVisibilityIndex() = default;

std::shared_ptr<const VisibilityIndex> SharedVisibilityIndex::get() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!tried_) {
    tried_ = true;
    if (plan_.occluder_segments().empty()) {
      error_ = "the plan has no occluder layer";
    } else {
      if (builds_) ++*builds_;
      try {
        index_ = std::make_shared<const VisibilityIndex>(plan_);
      } catch (const std::exception& e) {
        error_ = e.what();  // a plan CGAL cannot take: the callers do without
      }
    }
    ready_ = true;
  }
  return index_;
}

std::string SharedVisibilityIndex::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

}  // namespace plenopath
