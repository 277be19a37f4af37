#include "processing/walk/walk_route.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <queue>

#include "model/error.h"

namespace plenopath {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

void WalkRouteOptions::check() const {
  if (!(cell_m > 0)) throw Error("WalkRouteOptions.cell_m must be > 0");
  if (!(clearance_m >= 0)) throw Error("WalkRouteOptions.clearance_m must be >= 0");
  if (!(wall_cost >= 0)) throw Error("WalkRouteOptions.wall_cost must be >= 0");
  if (!(margin_m >= 0)) throw Error("WalkRouteOptions.margin_m must be >= 0");
}

WalkRouter::WalkRouter(const FloorPlan& plan, const WalkRouteOptions& options) : options_(options) {
  options.check();
  walls_ = plan.occluder_segments();
  Eigen::Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  for (const PlanSegment& s : walls_) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  if (walls_.empty()) lo = hi = Eigen::Vector2d::Zero();
  origin_ = lo - Eigen::Vector2d::Constant(options.margin_m);
  const Eigen::Vector2d size = hi - lo + Eigen::Vector2d::Constant(2 * options.margin_m);
  const int cols = std::max(1, static_cast<int>(std::ceil(size.x() / options.cell_m)) + 1);
  const int rows = std::max(1, static_cast<int>(std::ceil(size.y() / options.cell_m)) + 1);
  if (static_cast<double>(cols) * rows > 4e7)
    throw Error("the plan is too large for a walking route at " + std::to_string(options.cell_m) +
                " m cells");
  blocked_ = cv::Mat::zeros(rows, cols, CV_8U);
  for (const PlanSegment& s : walls_)
    cv::line(blocked_, cell_of(s.a), cell_of(s.b), cv::Scalar(255), 1, cv::LINE_8);
  cv::Mat free = blocked_ == 0;
  cv::distanceTransform(free, distance_, cv::DIST_L2, 3);
  distance_ *= options.cell_m;
}

cv::Point WalkRouter::cell_of(const Eigen::Vector2d& p) const {
  return {static_cast<int>(std::lround((p.x() - origin_.x()) / options_.cell_m)),
          static_cast<int>(std::lround((p.y() - origin_.y()) / options_.cell_m))};
}

Eigen::Vector2d WalkRouter::centre_of(const cv::Point& c) const {
  return origin_ + options_.cell_m * Eigen::Vector2d(c.x, c.y);
}

bool crosses_any_wall(const std::vector<PlanSegment>& walls, const Eigen::Vector2d& a,
                      const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  for (const PlanSegment& w : walls) {
    const Eigen::Vector2d e = w.b - w.a;
    const double denom = cross(d, e);
    if (std::abs(denom) < 1e-12) continue;
    const Eigen::Vector2d ap = w.a - a;
    const double t = cross(ap, e) / denom, s = cross(ap, d) / denom;
    if (t > 1e-9 && t < 1 - 1e-9 && s >= 0 && s <= 1) return true;
  }
  return false;
}

bool WalkRouter::crosses_wall(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  return crosses_any_wall(walls_, a, b);
}

std::vector<Eigen::Vector2d> WalkRouter::route(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  if (!crosses_wall(a, b)) return {a, b};
  const cv::Point start = cell_of(a), goal = cell_of(b);
  const cv::Rect inside(0, 0, blocked_.cols, blocked_.rows);
  if (!inside.contains(start) || !inside.contains(goal)) return {};
  // Dijkstra with the straight-line distance as A*'s heuristic, on cells; walls blocked.
  const int cols = blocked_.cols;
  const auto id = [cols](const cv::Point& c) { return c.y * cols + c.x; };
  std::vector<double> cost(static_cast<std::size_t>(blocked_.total()),
                           std::numeric_limits<double>::infinity());
  std::vector<int> from(static_cast<std::size_t>(blocked_.total()), -1);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const auto heuristic = [&](const cv::Point& c) { return std::hypot(c.x - goal.x, c.y - goal.y); };
  cost[static_cast<std::size_t>(id(start))] = 0.0;
  open.push({heuristic(start), id(start)});
  const int dx[8] = {1, -1, 0, 0, 1, 1, -1, -1}, dy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  bool reached = false;
  while (!open.empty()) {
    const auto [priority, here] = open.top();
    open.pop();
    const cv::Point c(here % cols, here / cols);
    if (priority - heuristic(c) > cost[static_cast<std::size_t>(here)] + 1e-9) continue;  // stale
    if (c == goal) {
      reached = true;
      break;
    }
    for (int k = 0; k < 8; ++k) {
      const cv::Point n(c.x + dx[k], c.y + dy[k]);
      if (!inside.contains(n) || blocked_.at<std::uint8_t>(n) != 0) continue;
      // A diagonal step may not squeeze between two wall cells.
      if (k >= 4 && (blocked_.at<std::uint8_t>(c.y, n.x) != 0 || blocked_.at<std::uint8_t>(n.y, c.x) != 0))
        continue;
      const double near =
          options_.clearance_m > 0 ? std::max(0.0, 1.0 - distance_.at<float>(n) / options_.clearance_m) : 0.0;
      const double step = (k < 4 ? 1.0 : M_SQRT2) * (1.0 + options_.wall_cost * near);
      const double next = cost[static_cast<std::size_t>(here)] + step;
      if (next < cost[static_cast<std::size_t>(id(n))]) {
        cost[static_cast<std::size_t>(id(n))] = next;
        from[static_cast<std::size_t>(id(n))] = here;
        open.push({next + heuristic(n), id(n)});
      }
    }
  }
  if (!reached) return {};
  std::vector<Eigen::Vector2d> cells;
  for (int at = id(goal); at >= 0; at = from[static_cast<std::size_t>(at)])
    cells.push_back(centre_of({at % cols, at / cols}));
  std::reverse(cells.begin(), cells.end());
  cells.front() = a;
  cells.back() = b;
  // Pulled taut: from each kept point, on to the farthest cell still in straight view of it.
  std::vector<Eigen::Vector2d> out = {a};
  std::size_t i = 0;
  while (i + 1 < cells.size()) {
    std::size_t j = cells.size() - 1;
    while (j > i + 1 && crosses_wall(cells[i], cells[j])) --j;
    out.push_back(cells[j]);
    i = j;
  }
  return out;
}

}  // namespace plenopath
