#include "processing/walk/walk_navigator.h"

#include <algorithm>
#include <cmath>

#include "model/error.h"

namespace plenopath {

void WalkOptions::check() const {
  if (!(speed_m_per_s > 0)) throw Error("walk: speed must be > 0");
  if (!(min_step_s >= 0 && max_step_s >= min_step_s)) throw Error("walk: need 0 <= min_step_s <= max_step_s");
  if (!(fade_s >= 0)) throw Error("walk: fade must be >= 0");
}

WalkNavigator::WalkNavigator(const CameraPath& path, const Keyframes& keyframes, const WalkOptions& options)
    : options_(options), frames_(path.frames), s_(path.arc_lengths()) {
  options_.check();
  if (frames_.empty()) throw Error("walk: the project has no camera path");
  for (int frame : keyframes.indices) {
    auto it = std::lower_bound(frames_.begin(), frames_.end(), frame,
                               [](const PathFrame& f, int i) { return f.index < i; });
    if (it == frames_.end() || it->index != frame) continue;
    const std::size_t i = static_cast<std::size_t>(it - frames_.begin());
    keyframes_.push_back({frame, s_[i], it->position(), it->heading});
  }
  if (keyframes_.empty()) throw Error("walk: no keyframe has a pose in the path (run sampling first)");
  std::sort(keyframes_.begin(), keyframes_.end(),
            [](const WalkKeyframe& a, const WalkKeyframe& b) { return a.s < b.s; });
  s_now_ = keyframes_.front().s;
  yaw_ = keyframes_.front().heading;
  current_ = previous_ = 0;
}

Eigen::Vector2d WalkNavigator::position_at(double s) const {
  if (frames_.size() == 1 || s <= s_.front()) return frames_.front().position();
  if (s >= s_.back()) return frames_.back().position();
  const std::size_t hi = static_cast<std::size_t>(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin());
  const std::size_t lo = hi - 1;
  const double span = s_[hi] - s_[lo];
  const double t = span > 0 ? (s - s_[lo]) / span : 0.0;
  return frames_[lo].position() + t * (frames_[hi].position() - frames_[lo].position());
}

Eigen::Vector2d WalkNavigator::tangent_at(double s) const {
  // The direction of the first path segment of non-zero length at or after s (else before it).
  std::size_t i = static_cast<std::size_t>(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin());
  i = i == 0 ? 0 : i - 1;
  for (std::size_t k = i; k + 1 < frames_.size(); ++k) {
    const Eigen::Vector2d d = frames_[k + 1].position() - frames_[k].position();
    if (d.norm() > 1e-9) return d.normalized();
  }
  for (std::size_t k = std::min(i, frames_.size() - 1); k > 0; --k) {
    const Eigen::Vector2d d = frames_[k].position() - frames_[k - 1].position();
    if (d.norm() > 1e-9) return d.normalized();
  }
  const double h = frames_.front().heading;
  return {std::cos(h), std::sin(h)};
}

double WalkNavigator::nearest_s(const Eigen::Vector2d& p) const {
  double best_s = s_.front(), best_d = (frames_.front().position() - p).squaredNorm();
  for (std::size_t i = 0; i + 1 < frames_.size(); ++i) {
    const Eigen::Vector2d a = frames_[i].position(), d = frames_[i + 1].position() - a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double dist = (a + t * d - p).squaredNorm();
    if (dist < best_d) {
      best_d = dist;
      best_s = s_[i] + t * (s_[i + 1] - s_[i]);
    }
  }
  return best_s;
}

int WalkNavigator::nearest_keyframe(double s) const {
  int best = 0;
  for (int i = 1; i < static_cast<int>(keyframes_.size()); ++i)
    if (std::abs(keyframes_[i].s - s) < std::abs(keyframes_[best].s - s)) best = i;
  return best;
}

double WalkNavigator::fade() const {
  return options_.fade_s <= 0 ? 1.0 : std::min(1.0, since_switch_ / options_.fade_s);
}

bool WalkNavigator::step(int direction) {
  const Eigen::Vector2d look(std::cos(yaw_), std::sin(yaw_));
  const double along = look.dot(tangent_at(s_now_)) >= 0 ? 1.0 : -1.0;
  const double sign = direction * along;
  const double from = moving_ ? to_ : s_now_;
  const WalkKeyframe* target = nullptr;
  for (const WalkKeyframe& k : keyframes_) {
    if (sign > 0 && k.s > from + 1e-6 && (!target || k.s < target->s)) target = &k;
    if (sign < 0 && k.s < from - 1e-6 && (!target || k.s > target->s)) target = &k;
  }
  if (!target) return false;
  walk_to(target->s);
  return true;
}

void WalkNavigator::walk_to(double s) {
  s = std::clamp(s, 0.0, path_length());
  from_ = s_now_;
  to_ = s;
  t_ = 0.0;
  duration_ =
      std::clamp(std::abs(to_ - from_) / options_.speed_m_per_s, options_.min_step_s, options_.max_step_s);
  moving_ = true;
}

void WalkNavigator::jump_to(double s) {
  s_now_ = std::clamp(s, 0.0, path_length());
  moving_ = false;
  settle_keyframe();
}

void WalkNavigator::settle_keyframe() {
  const int k = nearest_keyframe(s_now_);
  if (k != current_) {
    previous_ = current_;
    current_ = k;
    since_switch_ = 0.0;
  }
}

bool WalkNavigator::advance(double dt) {
  since_switch_ += dt;
  if (moving_) {
    t_ += dt;
    const double u = duration_ > 0 ? std::min(1.0, t_ / duration_) : 1.0;
    const double ease = u < 0.5 ? 2 * u * u : 1 - 2 * (1 - u) * (1 - u);
    s_now_ = from_ + (to_ - from_) * ease;
    if (u >= 1.0) moving_ = false;
    settle_keyframe();
  }
  return moving_ || fade() < 1.0;
}

}  // namespace plenopath
