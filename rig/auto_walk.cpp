// The automatic walk: an occupancy grid of the plan (walls, pillars, furniture grown by the clearance),
// waypoints at the centres of open spaces (maxima of the distance to obstacles), a nearest-neighbour tour
// over geodesic distances whose legs prefer the middle of passages (so they go through doorways), then a
// smoothed curve sampled at a wobbling step with a wobbling heading: a hand-pushed trolley.
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <queue>

#include "model/error.h"
#include "model/option_check.h"
#include "rig/scene_textures.h"
#include "rig/synthetic_camera.h"

namespace plenopath {

void AutoWalkOptions::check() const {
  const std::string s = "AutoWalkOptions.";
  require_option(step > 0.0 && step <= 10.0, s + "step", "must be in (0, 10] m", step);
  require_option(step_wobble >= 0.0 && step_wobble < 1.0, s + "step_wobble", "must be in [0, 1)",
                 step_wobble);
  require_option(heading_wobble_deg >= 0.0 && heading_wobble_deg <= 45.0, s + "heading_wobble_deg",
                 "must be in [0, 45]", heading_wobble_deg);
  require_option(clearance > 0.0 && clearance <= 5.0, s + "clearance", "must be in (0, 5] m", clearance);
  require_option(room_spacing > 0.2, s + "room_spacing", "must be > 0.2 m", room_spacing);
  require_option(max_frames >= 0, s + "max_frames", "must be >= 0", max_frames);
  scene.check();
}

namespace {

constexpr double kCell = 0.1;  // metres per grid cell

// A smooth pseudo-random signal in [-1, 1]: a few sines with seeded frequencies and phases.
struct Wobble {
  double f[3], p[3];
  Wobble(std::uint64_t seed) {
    for (int k = 0; k < 3; ++k) {
      f[k] = 0.02 + 0.1 * hash_unit(seed + 2 * k) / (k + 1);
      p[k] = 2 * M_PI * hash_unit(seed + 2 * k + 1);
    }
  }
  double operator()(double x) const {
    return (0.5 * std::sin(2 * M_PI * f[0] * x + p[0]) + 0.3 * std::sin(2 * M_PI * f[1] * x * 3 + p[1]) +
            0.2 * std::sin(2 * M_PI * f[2] * x * 7 + p[2]));
  }
};

}  // namespace

CameraPath auto_walk(const FloorPlan& plan, const AutoWalkOptions& options) {
  options.check();
  const SyntheticScene scene = build_synthetic_scene(plan, options.scene);
  const Eigen::Vector2d origin = scene.floor_min;
  const int cols = static_cast<int>(std::ceil((scene.floor_max.x() - origin.x()) / kCell)) + 1;
  const int rows = static_cast<int>(std::ceil((scene.floor_max.y() - origin.y()) / kCell)) + 1;
  if (static_cast<double>(cols) * rows > 4e7)
    throw Error("auto walk: the plan is too large for the walk grid");
  auto to_cell = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::lround((p.x() - origin.x()) / kCell)),
                     static_cast<int>(std::lround((p.y() - origin.y()) / kCell)));
  };
  auto to_plan = [&](int cx, int cy) {
    return Eigen::Vector2d(origin.x() + cx * kCell, origin.y() + cy * kCell);
  };

  cv::Mat free_space(rows, cols, CV_8U, cv::Scalar(255));
  cv::rectangle(free_space, cv::Rect(0, 0, cols, rows), cv::Scalar(0), 1);
  for (const auto& f : scene.faces)
    cv::line(free_space, to_cell(f.a), to_cell(f.b), cv::Scalar(0), 1, cv::LINE_8);
  for (const auto& fp : scene.footprints) {
    std::vector<cv::Point> poly;
    for (const auto& p : fp.points) poly.push_back(to_cell(p));
    cv::fillPoly(free_space, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(0));
  }
  cv::Mat distance;  // metres to the nearest obstacle
  cv::distanceTransform(free_space, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  distance *= kCell;
  cv::Mat walkable = distance > options.clearance;

  // The walkable region: the largest component that does not touch the grid's border (the outside).
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(walkable, labels, stats, centroids, 4);
  int best = -1, best_area = 0, best_any = -1, best_any_area = 0;
  for (int i = 1; i < n; ++i) {
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    const int x = stats.at<int>(i, cv::CC_STAT_LEFT), y = stats.at<int>(i, cv::CC_STAT_TOP);
    const int w = stats.at<int>(i, cv::CC_STAT_WIDTH), h = stats.at<int>(i, cv::CC_STAT_HEIGHT);
    const bool touches = x <= 1 || y <= 1 || x + w >= cols - 1 || y + h >= rows - 1;
    if (area > best_any_area) best_any = i, best_any_area = area;
    if (!touches && area > best_area) best = i, best_area = area;
  }
  if (best < 0) best = best_any;
  if (best < 0 || stats.at<int>(best, cv::CC_STAT_AREA) < 4)
    throw Error((plan.source_file.empty() ? std::string("floor plan") : plan.source_file) +
                ": auto walk: no free space wide enough for the trolley (clearance " +
                std::to_string(options.clearance) + " m)");

  // Waypoints: greedy maxima of the distance, at least room_spacing apart.
  std::vector<std::pair<float, cv::Point>> candidates;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x)
      if (labels.at<int>(y, x) == best) candidates.push_back({distance.at<float>(y, x), cv::Point(x, y)});
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<cv::Point> waypoints;
  const double spacing_cells = options.room_spacing / kCell;
  for (const auto& [d, p] : candidates) {
    bool far = true;
    for (const auto& q : waypoints)
      if (std::hypot(p.x - q.x, p.y - q.y) < spacing_cells) {
        far = false;
        break;
      }
    if (far) waypoints.push_back(p);
  }

  // Step cost: longer near obstacles so legs keep to the middle of passages and doorways.
  auto cost = [&](int x, int y) {
    return 1.0 + 4.0 * std::max(0.0, 1.2 - static_cast<double>(distance.at<float>(y, x)));
  };
  std::vector<cv::Point> route{waypoints.front()};
  std::vector<char> visited(waypoints.size(), 0);
  visited[0] = 1;
  std::size_t current = 0;
  std::vector<double> dist(static_cast<std::size_t>(rows) * cols);
  std::vector<int> previous(dist.size());
  for (std::size_t leg = 1; leg < waypoints.size(); ++leg) {
    // Dijkstra from the current waypoint (8-connected).
    std::fill(dist.begin(), dist.end(), std::numeric_limits<double>::infinity());
    std::fill(previous.begin(), previous.end(), -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    const int start = waypoints[current].y * cols + waypoints[current].x;
    dist[start] = 0;
    queue.push({0.0, start});
    while (!queue.empty()) {
      const auto [d, i] = queue.top();
      queue.pop();
      if (d > dist[i]) continue;
      const int x = i % cols, y = i / cols;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (!dx && !dy) continue;
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= cols || ny >= rows || labels.at<int>(ny, nx) != best) continue;
          const double nd = d + std::hypot(dx, dy) * 0.5 * (cost(x, y) + cost(nx, ny));
          const int j = ny * cols + nx;
          if (nd < dist[j]) {
            dist[j] = nd;
            previous[j] = i;
            queue.push({nd, j});
          }
        }
    }
    std::size_t next = current;
    double next_d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < waypoints.size(); ++k) {
      const double d = dist[waypoints[k].y * cols + waypoints[k].x];
      if (!visited[k] && d < next_d) next = k, next_d = d;
    }
    if (next == current) break;
    std::vector<cv::Point> leg_cells;
    for (int i = waypoints[next].y * cols + waypoints[next].x; i != start; i = previous[i])
      leg_cells.push_back(cv::Point(i % cols, i / cols));
    route.insert(route.end(), leg_cells.rbegin(), leg_cells.rend());
    visited[next] = 1;
    current = next;
  }

  // Smooth: keep a point every 0.3 m, then Chaikin corner cutting.
  std::vector<Eigen::Vector2d> pts;
  for (std::size_t i = 0; i < route.size(); ++i)
    if (i % 3 == 0 || i + 1 == route.size()) pts.push_back(to_plan(route[i].x, route[i].y));
  // Where the route turns back (a dead end) the trolley makes a U-turn instead of reversing on the spot:
  // the way in keeps to the left, the way out to the right, joined by a half circle, as wide as the free
  // space there allows.
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const Eigen::Vector2d in = (pts[i] - pts[i - 1]).normalized(), out = (pts[i + 1] - pts[i]).normalized();
    if (in.dot(out) > -0.5) continue;  // turns of less than 120 degrees stay as they are
    const cv::Point cell = to_cell(pts[i]);
    const double room = distance.at<float>(std::clamp(cell.y, 0, rows - 1), std::clamp(cell.x, 0, cols - 1));
    const double r = std::clamp(room - options.clearance - 0.05, 0.15, 0.8);
    const Eigen::Vector2d left(-in.y(), in.x());
    const double lane = 1.5;  // metres over which the lanes merge back into the route
    for (std::size_t k = i; k-- > 0 && (pts[k] - pts[i]).norm() < lane;)
      pts[k] += r * (1.0 - (pts[k] - pts[i]).norm() / lane) * left;
    for (std::size_t k = i + 1; k < pts.size() && (pts[k] - pts[i]).norm() < lane; ++k)
      pts[k] -= r * (1.0 - (pts[k] - pts[i]).norm() / lane) * left;
    const Eigen::Vector2d centre = pts[i];
    const double start = std::atan2(left.y(), left.x());
    const int n = std::max(6, static_cast<int>(M_PI * r / 0.12));
    std::vector<Eigen::Vector2d> turn;
    for (int k = 0; k <= n; ++k) {  // clockwise from the left lane to the right lane
      const double a = start - M_PI * k / n;
      turn.push_back(centre + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    pts.erase(pts.begin() + static_cast<long>(i));
    pts.insert(pts.begin() + static_cast<long>(i), turn.begin(), turn.end());
    i += turn.size();
  }
  for (int iteration = 0; iteration < 4 && pts.size() > 2; ++iteration) {
    std::vector<Eigen::Vector2d> cut{pts.front()};
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      cut.push_back(0.75 * pts[i] + 0.25 * pts[i + 1]);
      cut.push_back(0.25 * pts[i] + 0.75 * pts[i + 1]);
    }
    cut.push_back(pts.back());
    pts.swap(cut);
  }
  if (pts.size() < 2) pts.push_back(pts.front() + Eigen::Vector2d(0.01, 0));
  std::vector<double> arc(pts.size(), 0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) arc[i] = arc[i - 1] + (pts[i] - pts[i - 1]).norm();
  auto at = [&](double s) {
    s = std::clamp(s, 0.0, arc.back());
    const std::size_t i =
        std::min<std::size_t>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin(), arc.size() - 1);
    const std::size_t i0 = i == 0 ? 0 : i - 1;
    const double span = arc[i] - arc[i0];
    const double t = span > 0 ? (s - arc[i0]) / span : 0.0;
    return Eigen::Vector2d((1 - t) * pts[i0] + t * pts[i]);
  };

  // Sample at a wobbling step; heading along the tangent with a small wobble.
  const Wobble speed(mix_hash(options.seed * 31ull + 1)), turn(mix_hash(options.seed * 31ull + 2));
  CameraPath path;
  path.scale_source = "ground_truth";
  double s = 0.0;
  char name[256];
  for (int i = 0; s <= arc.back(); ++i) {
    if (options.max_frames > 0 && i >= options.max_frames) break;
    const Eigen::Vector2d p = at(s);
    const Eigen::Vector2d tangent = at(s + 0.25) - at(s - 0.25);
    PathFrame f;
    f.index = i;
    f.x = p.x();
    f.y = p.y();
    f.heading =
        wrap_angle(std::atan2(tangent.y(), tangent.x()) + radians(options.heading_wobble_deg) * turn(i));
    if (!options.frame_pattern.empty()) {
      std::snprintf(name, sizeof(name), options.frame_pattern.c_str(), i);
      f.file = name;
    }
    path.frames.push_back(f);
    s += options.step * (1.0 + options.step_wobble * speed(i));
  }
  return path;
}

}  // namespace plenopath
