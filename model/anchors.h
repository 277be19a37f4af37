#pragma once
// Author's corrections: "frame i was really here".
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace plenopath {

struct Anchor {
  int frame = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // plan frame, metres
  std::optional<double> heading;                       // radians, when the author fixed it too
};
bool operator==(const Anchor& l, const Anchor& r);

using Anchors = std::vector<Anchor>;

}  // namespace plenopath
