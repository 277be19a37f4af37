#pragma once
// A uniform grid over 2-D segments for near-point and along-segment candidate queries (plain doubles).
// Used by visibility (wall lookup, path-window intersections) and by the DXF clean-up.
#include <Eigen/Core>
#include <vector>

namespace plenopath {

struct Segment2 {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
};

double distance_point_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// Parameters (t along [a0,a1], u along [b0,b1]) of the intersection of two segments, if they intersect in
// one point (parallel segments report no intersection). Closed segments: endpoints count.
bool intersect_segments(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                        const Eigen::Vector2d& b1, double* t, double* u);

class SegmentGrid {
 public:
  // cells_hint: about how many cells along the longer side of the bounding box.
  explicit SegmentGrid(std::vector<Segment2> segments, int cells_hint = 0);

  const std::vector<Segment2>& segments() const { return segments_; }
  // Indices of segments whose cells overlap the disc (p, radius); may hold extra candidates, no duplicates.
  std::vector<int> near(const Eigen::Vector2d& p, double radius) const;
  // Indices of segments whose cells the segment [a, b] passes through; may hold extras, no duplicates.
  std::vector<int> along(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  // Distance from p to the nearest segment within `radius` (or `radius` if none is closer).
  double distance_within(const Eigen::Vector2d& p, double radius) const;

 private:
  void collect_cell(int cx, int cy, std::vector<int>* out) const;
  // Calls fn(cx, cy) for every cell the segment [a, b] passes through (with a small margin), each once.
  template <typename Fn>
  void for_each_cell_along(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Fn fn) const;
  int cell_x(double x) const;
  int cell_y(double y) const;

  std::vector<Segment2> segments_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_size_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> cells_;
};

}  // namespace plenopath
