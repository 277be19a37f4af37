#pragma once
// Visibility along the path: the events where the visible set changes and the cells between them.
#include <Eigen/Core>
#include <vector>

namespace plenopath {

struct VisibilityEvent {
  int frame = 0;   // the path segment [frame, frame+1] holds the event
  double s = 0.0;  // arc length along the path, metres
};
bool operator==(const VisibilityEvent& l, const VisibilityEvent& r);

struct VisibilityCell {
  int first_frame = 0;
  int last_frame = 0;
  double s_begin = 0.0;
  double s_end = 0.0;
  double length = 0.0;     // l: path length inside the cell, metres
  double area_mid = 0.0;   // v: envelope area at the middle of the interval, m^2
  double area_mean = 0.0;  // v averaged over the interval, m^2
};
bool operator==(const VisibilityCell& l, const VisibilityCell& r);

// A critical line clipped to free space, for display of the cell decomposition.
struct CriticalLine {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
};
bool operator==(const CriticalLine& l, const CriticalLine& r);

struct VisibilityCells {
  std::vector<VisibilityEvent> events;
  std::vector<VisibilityCell> cells;
  std::vector<CriticalLine> critical_lines;  // may be capped for large plans
  bool empty() const { return cells.empty(); }
};
bool operator==(const VisibilityCells& l, const VisibilityCells& r);

}  // namespace plenopath
