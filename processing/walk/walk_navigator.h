#pragma once
// Walking along a plenoptic path between keyframes, as the studio's walk mode and the web player do:
// the viewer sits at an arc length s on the path, looks along a world yaw, and sees the keyframe nearest
// to s; "forward" is the way the viewer looks (along or against the path). Qt-free so it is tested alone.
#include <Eigen/Core>
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"

namespace plenopath {

struct WalkKeyframe {
  int frame = 0;
  double s = 0.0;  // arc length along the path, metres
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double heading = 0.0;
};

struct WalkOptions {
  double speed_m_per_s = 1.6;  // animation speed between keyframes
  double min_step_s = 0.2;     // shortest animation, seconds
  double max_step_s = 0.9;     // longest animation, seconds
  double fade_s = 0.35;        // cross-fade between keyframe images
  void check() const;
};

class WalkNavigator {
 public:
  // Throws Error when the path is empty or no keyframe has a pose in it.
  WalkNavigator(const CameraPath& path, const Keyframes& keyframes, const WalkOptions& options = {});

  const std::vector<WalkKeyframe>& keyframes() const { return keyframes_; }
  double path_length() const { return s_.empty() ? 0.0 : s_.back(); }

  // Position on the path at arc length s (clamped) and the path's direction there (unit, world frame).
  Eigen::Vector2d position_at(double s) const;
  Eigen::Vector2d tangent_at(double s) const;
  // Arc length of the path point nearest to a plan point (for clicks on the map).
  double nearest_s(const Eigen::Vector2d& point) const;
  // Index into keyframes() of the keyframe nearest to s.
  int nearest_keyframe(double s) const;

  // The state of the walk.
  double s() const { return s_now_; }
  double yaw() const { return yaw_; }  // world angle of the view direction, CCW from +X
  void set_yaw(double yaw) { yaw_ = yaw; }
  int current_keyframe() const { return current_; }
  int previous_keyframe() const { return previous_; }
  bool moving() const { return moving_; }
  // Weight of the current keyframe's image in the cross-fade (1 = fully shown).
  double fade() const;

  // One keyframe forward (+1) or back (-1), forward being where the viewer looks. Returns false at an end.
  bool step(int direction);
  // Animate to arc length s (e.g. a click on the map).
  void walk_to(double s);
  // Jump without animation.
  void jump_to(double s);
  // Advance the clock by dt seconds; returns true while something still changes (animation or fade).
  bool advance(double dt);

 private:
  void settle_keyframe();

  WalkOptions options_;
  std::vector<PathFrame> frames_;
  std::vector<double> s_;
  std::vector<WalkKeyframe> keyframes_;
  double s_now_ = 0.0, yaw_ = 0.0;
  double from_ = 0.0, to_ = 0.0, t_ = 0.0, duration_ = 0.0;
  bool moving_ = false;
  int current_ = 0, previous_ = 0;
  double since_switch_ = 1e9;
};

}  // namespace plenopath
