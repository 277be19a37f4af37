#include "processing/util/progress.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace plenopath {

namespace {

class NullProgress final : public Progress {
 public:
  void report(double, const std::string&) override {}
  bool is_cancelled() const override { return false; }
};

double clamp_fraction(double f) { return std::isfinite(f) ? std::clamp(f, 0.0, 1.0) : 0.0; }

}  // namespace

Progress& null_progress() {
  static NullProgress none;
  return none;
}

SubProgress::SubProgress(Progress& parent, double begin, double end, std::string stage)
    : parent_(parent),
      begin_(clamp_fraction(begin)),
      end_(std::max(clamp_fraction(begin), clamp_fraction(end))),
      stage_(std::move(stage)) {}

double SubProgress::parent_fraction(double fraction) const {
  return begin_ + (end_ - begin_) * clamp_fraction(fraction);
}

void SubProgress::report(double fraction, const std::string& stage) {
  const double f = parent_fraction(fraction);
  if (stage_.empty()) {
    parent_.report(f, stage);
  } else if (!stage.empty()) {
    named_ = true;
    parent_.report(f, stage_ + ": " + stage);
  } else if (!named_.exchange(true)) {
    parent_.report(f, stage_);
  } else {
    parent_.report(f);
  }
}

void FunctionProgress::report(double fraction, const std::string& stage) {
  if (!on_report_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  on_report_(clamp_fraction(fraction), stage);
}

}  // namespace plenopath
