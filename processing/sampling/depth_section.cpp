#include "processing/sampling/depth_section.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <set>
#include <tuple>

#include "model/error.h"
#include "model/option_check.h"

namespace plenopath {

void DepthSectionOptions::check() const {
  const std::string s = "DepthSectionOptions.";
  require_option(cell_m > 0 && std::isfinite(cell_m), s + "cell_m", "must be > 0", cell_m);
  require_option(max_range_m > cell_m, s + "max_range_m", "must be > cell_m", max_range_m);
  require_option(join_ratio >= 0 && join_ratio < 1, s + "join_ratio", "must be in [0, 1)", join_ratio);
  require_option(max_columns >= 16, s + "max_columns", "must be >= 16", max_columns);
  require_option(simplify_m >= 0, s + "simplify_m", "must be >= 0", simplify_m);
  require_option(min_outline_m >= 0, s + "min_outline_m", "must be >= 0", min_outline_m);
  require_option(!layer.empty(), s + "layer", "must not be empty", layer);
}

DepthSectionBuilder::DepthSectionBuilder(const DepthSectionOptions& options) : options_(options) {
  options_.check();
}

void DepthSectionBuilder::add(const cv::Mat& depth_in, const PathFrame& pose) {
  if (depth_in.empty()) return;
  cv::Mat depth;
  if (depth_in.type() == CV_16U)
    depth_in.convertTo(depth, CV_32F, 0.001);
  else if (depth_in.type() == CV_32F)
    depth = depth_in;
  else
    throw Error("section from depth: CV_32F metres or CV_16U millimetres expected");
  const int h = depth.rows;
  // Every k-th column of a wide panorama (the column's centre azimuth is kept exact below).
  const int stride = (depth.cols + options_.max_columns - 1) / options_.max_columns;
  const int w = depth.cols / stride;
  // The nearer of the two rows astride the horizon, as envelope_from_depth reads them; 0 = nothing hit.
  const int upper = std::max(0, h / 2 - 1), lower = std::min(h - 1, h / 2);
  std::vector<double> range(static_cast<std::size_t>(w), 0.0);
  for (int u = 0; u < w; ++u)
    for (int v : {upper, lower}) {
      const float r = depth.at<float>(v, u * stride + stride / 2);
      double& best = range[static_cast<std::size_t>(u)];
      if (std::isfinite(r) && r > 0.0f && r <= options_.max_range_m && (best == 0.0 || r < best)) best = r;
    }
  Frame frame;
  frame.centre = pose.position();
  auto point = [&](int u, double r) {
    const double azimuth = (u * stride + stride / 2 + 0.5) / depth.cols * 2.0 * M_PI - M_PI;
    const double world = pose.heading - azimuth;  // ARCHITECTURE.md: clockwise azimuth from the heading
    return Eigen::Vector2d(frame.centre + r * Eigen::Vector2d(std::cos(world), std::sin(world)));
  };
  bool any_hit = false;
  for (int u = 0; u < w; ++u) {
    const double r = range[static_cast<std::size_t>(u)];
    frame.sight.push_back(point(u, r > 0 ? r : options_.max_range_m));
    any_hit = any_hit || r > 0;
  }
  if (!any_hit) return;
  auto same_surface = [&](int a, int b) {
    const double ra = range[static_cast<std::size_t>(a)], rb = range[static_cast<std::size_t>(b)];
    return ra > 0 && rb > 0 &&
           std::abs(ra - rb) < options_.join_ratio * std::max(ra, rb) + 2 * options_.cell_m;
  };
  // Start the runs at a break, so that a surface across the seam stays one run.
  int start = 0;
  while (start < w && same_surface((start + w - 1) % w, start)) ++start;
  const bool round = start == w;  // one surface all round (a round room)
  if (round) start = 0;
  std::vector<Eigen::Vector2d> run;
  for (int k = 0; k < w; ++k) {
    const int u = (start + k) % w;
    const bool joined = k > 0 && same_surface((u + w - 1) % w, u);
    if (!joined && !run.empty()) {
      frame.surfaces.push_back(std::move(run));
      run.clear();
    }
    if (range[static_cast<std::size_t>(u)] > 0.0) run.push_back(frame.sight[static_cast<std::size_t>(u)]);
  }
  if (round && !run.empty()) run.push_back(run.front());
  if (!run.empty()) frame.surfaces.push_back(std::move(run));
  frames_.push_back(std::move(frame));
}

DepthSection DepthSectionBuilder::finish(Progress& progress) const {
  if (frames_.empty()) throw Error("section from depth: no frame has depth at eye level (render with depth)");
  progress.checkpoint(0.0, "the space the frames saw through");
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Frame& f : frames_)
    for (const Eigen::Vector2d& p : f.sight) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const double cell = options_.cell_m;
  lo -= Eigen::Vector2d(3 * cell, 3 * cell);
  hi += Eigen::Vector2d(3 * cell, 3 * cell);
  const int cols = static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)) + 1;
  const int rows = static_cast<int>(std::ceil((hi.y() - lo.y()) / cell)) + 1;
  if (cols > 8000 || rows > 8000)
    throw Error("section from depth: the frames see " + std::to_string(cols) + " x " + std::to_string(rows) +
                " cells of " + std::to_string(cell) + " m; raise the cell size or lower max_range_m");
  auto to_cell = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::floor((p.x() - lo.x()) / cell)),
                     static_cast<int>(std::floor((p.y() - lo.y()) / cell)));
  };
  // Free: inside some frame's sight polygon; the surfaces where sight stopped are not free, so a wall
  // without thickness still parts the rooms on its two sides.
  cv::Mat free(rows, cols, CV_8U, cv::Scalar(0)), surfaces(rows, cols, CV_8U, cv::Scalar(0));
  for (const Frame& f : frames_) {
    std::vector<cv::Point> polygon;
    for (const Eigen::Vector2d& p : f.sight) polygon.push_back(to_cell(p));
    cv::fillPoly(free, std::vector<std::vector<cv::Point>>{polygon}, cv::Scalar(255), cv::LINE_8);
    for (const std::vector<Eigen::Vector2d>& run : f.surfaces) {
      surfaces.at<std::uint8_t>(to_cell(run.front())) = 255;
      for (std::size_t k = 1; k < run.size(); ++k)
        cv::line(surfaces, to_cell(run[k - 1]), to_cell(run[k]), cv::Scalar(255), 1, cv::LINE_8);
    }
    progress.throw_if_cancelled();
  }
  free.setTo(0, surfaces);
  // The free region's own cells near the camera centres are free whatever a stray hit said.
  for (const Frame& f : frames_) cv::circle(free, to_cell(f.centre), 1, cv::Scalar(255), cv::FILLED);
  progress.checkpoint(0.5, "tracing the free space's boundary");
  // Traced on the not-free side, so the outlines run along the surface cells themselves: the boundaries of
  // the holes of the not-free region are the rooms; its islands (not touching the raster's border) are
  // pillars and furniture.
  cv::Mat blocked = free == 0;
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(blocked, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);

  DepthSection section;
  section.frames_used = static_cast<int>(frames_.size());
  section.free_cells = cv::countNonZero(free);
  FloorPlan& plan = section.plan;
  plan.units = "m";
  plan.metres_per_unit = 1.0;
  PlanLayer walls_layer, limit_layer;
  walls_layer.name = options_.layer;
  walls_layer.color = 5;
  walls_layer.occluder = true;
  limit_layer.name = options_.layer + "-UNSEEN";
  limit_layer.color = 8;
  limit_layer.occluder = true;
  auto metres = [&](const cv::Point& c) {
    return Eigen::Vector2d(lo.x() + (c.x + 0.5) * cell, lo.y() + (c.y + 0.5) * cell);
  };
  // A side of an outline is a wall when most of its cells are surface cells (or next to one); otherwise it
  // is where the frames' sight ended at their side (past a door jamb, round a corner): the limit of what
  // the path saw, kept so the free space stays closed, on a layer of its own.
  cv::Mat near_surface;
  cv::dilate(surfaces, near_surface, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
  auto on_surface = [&](const cv::Point& a, const cv::Point& b) {
    cv::LineIterator line(near_surface, a, b, 8);
    int hits = 0;
    for (int i = 0; i < line.count; ++i, ++line) hits += **line != 0;
    return 2 * hits >= line.count;
  };
  // Two rooms either side of a wall without thickness trace the same surface cells: each side once.
  std::set<std::tuple<int, int, int, int>> drawn;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    const std::vector<cv::Point>& contour = contours[i];
    const cv::Rect box = cv::boundingRect(contour);
    const bool hole = hierarchy[i][3] >= 0;
    const bool border = box.x == 0 || box.y == 0 || box.x + box.width == cols || box.y + box.height == rows;
    if (!hole && border) continue;  // the unseen world round the free space
    if (std::max(box.width, box.height) * cell < options_.min_outline_m) continue;
    std::vector<cv::Point> simple;
    cv::approxPolyDP(contour, simple, options_.simplify_m / cell, true);
    if (simple.size() < 2) continue;
    PlanOutline outline;
    outline.layer = walls_layer.name;
    outline.closed = true;
    for (const cv::Point& c : simple) outline.points.push_back(metres(c));
    for (std::size_t k = 0; k < simple.size(); ++k) {
      const cv::Point a = simple[k], b = simple[(k + 1) % simple.size()];
      if (a == b) continue;
      const auto key = a.x < b.x || (a.x == b.x && a.y < b.y) ? std::make_tuple(a.x, a.y, b.x, b.y)
                                                              : std::make_tuple(b.x, b.y, a.x, a.y);
      if (!drawn.insert(key).second) continue;
      PlanSegment segment;
      segment.a = metres(a);
      segment.b = metres(b);
      segment.layer = on_surface(a, b) ? walls_layer.name : limit_layer.name;
      segment.occluder = true;
      (segment.layer == walls_layer.name ? walls_layer : limit_layer).entity_count++;
      plan.segments.push_back(segment);
    }
    plan.outlines.push_back(std::move(outline));
  }
  if (walls_layer.entity_count == 0)
    throw Error("section from depth: the frames' depth bounds no space at eye level (nothing was hit?)");
  plan.layers.push_back(walls_layer);
  plan.layers.push_back(limit_layer);
  progress.report(1.0);
  return section;
}

DepthSection plan_from_depth_section(const CameraPath& path,
                                     const std::function<cv::Mat(int index)>& read_depth,
                                     const DepthSectionOptions& options, Progress& progress) {
  DepthSectionBuilder builder(options);
  for (std::size_t i = 0; i < path.size(); ++i) {
    progress.checkpoint(0.8 * i / path.size(),
                        "section: frame " + std::to_string(i + 1) + " of " + std::to_string(path.size()));
    builder.add(read_depth(path.frames[i].index), path.frames[i]);
  }
  SubProgress finishing(progress, 0.8, 1.0);
  return builder.finish(finishing);
}

}  // namespace plenopath
