// The plan's rasters for registration: walls with the nearest segment per cell (distance transform with
// labels), free space (components of the non-wall cells, the outer walls' openings closed, each classified
// once by the visibility index), and their coarse versions for the global search.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "processing/registration/registration_internal.h"
#include "processing/visibility/visibility.h"

namespace plenopath::registration_detail {

bool PlanRaster::cell_of(const Eigen::Vector2d& p, int* col, int* row) const {
  const double cx = std::floor((p.x() - origin.x()) / cell), cy = std::floor((p.y() - origin.y()) / cell);
  if (!(cx >= 0 && cy >= 0 && cx < cols && cy < rows)) return false;
  *col = static_cast<int>(cx);
  *row = static_cast<int>(cy);
  return true;
}

bool PlanRaster::is_free(const Eigen::Vector2d& p) const {
  int c = 0, r = 0;
  return cell_of(p, &c, &r) && free.at<std::uint8_t>(r, c) != 0;
}

PlanRaster build_plan_raster(const FloorPlan& plan, double cell, double margin) {
  PlanRaster out;
  out.cell = cell;
  Eigen::Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  for (const PlanSegment& s : plan.occluder_segments()) {
    if (!(s.length() > 0) || !s.a.allFinite() || !s.b.allFinite()) continue;
    out.walls.push_back({s.a, s.b});
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  const std::string who = plan.source_file.empty() ? std::string("plan") : plan.source_file;
  if (out.walls.empty())
    throw file_error(who,
                     "registration needs walls, but the plan has no sight-blocking segments (mark the "
                     "layers of walls and columns as occluders)");
  const Eigen::Vector2d size = hi - lo + Eigen::Vector2d::Constant(2 * margin);
  if (size.maxCoeff() / cell > 8000)
    throw file_error(who, "the plan's walls span " + std::to_string(int(size.maxCoeff())) +
                              " m: too large to register on at " + std::to_string(cell) + " m cells");
  out.origin = lo - Eigen::Vector2d::Constant(margin);
  out.cols = static_cast<int>(std::ceil(size.x() / cell)) + 1;
  out.rows = static_cast<int>(std::ceil(size.y() / cell)) + 1;

  // Walls: 8-connected lines of segment index + 1 (4-connected free space cannot cross them).
  cv::Mat ids(out.rows, out.cols, CV_32S, cv::Scalar(0));
  auto pixel = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::floor((p.x() - out.origin.x()) / cell)),
                     static_cast<int>(std::floor((p.y() - out.origin.y()) / cell)));
  };
  for (std::size_t i = 0; i < out.walls.size(); ++i)
    cv::line(ids, pixel(out.walls[i].a), pixel(out.walls[i].b), cv::Scalar(double(i + 1)), 1, cv::LINE_8);

  // Distance to the nearest wall cell, with that cell's label; labels mapped back to segments.
  cv::Mat not_wall = ids == 0;
  cv::Mat labels;
  cv::distanceTransform(not_wall, out.distance, labels, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  out.distance *= cell;
  std::vector<int> segment_of_label(static_cast<std::size_t>(out.rows) * out.cols + 2, 0);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      const int id = ids.at<int>(r, c);
      if (id > 0) segment_of_label[static_cast<std::size_t>(labels.at<int>(r, c))] = id - 1;
    }
  out.nearest.create(out.rows, out.cols, CV_32S);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c)
      out.nearest.at<int>(r, c) = segment_of_label[static_cast<std::size_t>(labels.at<int>(r, c))];

  // Free space: each 4-connected component of non-wall cells is free, outside or an obstacle as a whole;
  // the openings the visibility index closed (windows drawn as gaps) part rooms from the outside here too.
  std::unique_ptr<VisibilityIndex> index;
  try {
    index = std::make_unique<VisibilityIndex>(plan);
  } catch (const Error&) {
    index.reset();  // enclosed components count as free
  }
  cv::Mat open = not_wall.clone();
  if (index)
    for (const PlanSegment& s : index->closed_openings())
      cv::line(open, pixel(s.a), pixel(s.b), cv::Scalar(0), 1, cv::LINE_8);
  cv::Mat components;
  const int count = cv::connectedComponents(open, components, 4, CV_32S);
  std::vector<char> touches_border(count, 0);
  std::vector<float> deepest(count, -1.0f);
  std::vector<cv::Point> deepest_at(count);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      const int k = components.at<int>(r, c);
      if (!open.at<std::uint8_t>(r, c)) continue;
      if (r == 0 || c == 0 || r == out.rows - 1 || c == out.cols - 1) touches_border[k] = 1;
      const float d = out.distance.at<float>(r, c);
      if (d > deepest[k]) {
        deepest[k] = d;
        deepest_at[k] = {c, r};
      }
    }
  std::vector<char> is_free(count, 0);
  for (int k = 0; k < count; ++k) {
    if (touches_border[k] || deepest[k] < 0) continue;
    if (!index) {
      is_free[k] = 1;
      continue;
    }
    const Eigen::Vector2d p =
        out.origin + cell * Eigen::Vector2d(deepest_at[k].x + 0.5, deepest_at[k].y + 0.5);
    is_free[k] = index->classify(p) == EnvelopeStatus::ok;
  }
  out.free.create(out.rows, out.cols, CV_8U);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c)
      out.free.at<std::uint8_t>(r, c) =
          open.at<std::uint8_t>(r, c) && is_free[components.at<int>(r, c)] ? 1 : 0;
  return out;
}

CoarseRaster coarsen(const PlanRaster& fine, double coarse_cell, int max_cells) {
  int factor = std::max(1, static_cast<int>(std::lround(coarse_cell / fine.cell)));
  while (std::max(fine.cols, fine.rows) / factor > max_cells) ++factor;
  CoarseRaster out;
  out.cell = fine.cell * factor;
  out.origin = fine.origin;
  const int cols = (fine.cols + factor - 1) / factor, rows = (fine.rows + factor - 1) / factor;
  out.wall_proximity.create(rows, cols, CV_32F);
  out.not_free.create(rows, cols, CV_32F);
  // A point anywhere in a block scores by the block's nearest wall: proximity falls to 0 over two cells.
  const double radius = 2.0 * out.cell;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      float nearest = std::numeric_limits<float>::max();
      int n = 0, not_free = 0;
      for (int rr = r * factor; rr < std::min(fine.rows, (r + 1) * factor); ++rr)
        for (int cc = c * factor; cc < std::min(fine.cols, (c + 1) * factor); ++cc) {
          nearest = std::min(nearest, fine.distance.at<float>(rr, cc));
          not_free += fine.free.at<std::uint8_t>(rr, cc) == 0;
          ++n;
        }
      out.wall_proximity.at<float>(r, c) = static_cast<float>(std::max(0.0, 1.0 - nearest / radius));
      out.not_free.at<float>(r, c) = n ? float(not_free) / n : 1.0f;
    }
  return out;
}

std::vector<double> plan_directions(const std::vector<Segment2>& walls) {
  constexpr int bins = 180;  // half-degree bins over [0, 90)
  std::vector<double> h(bins, 0.0);
  for (const Segment2& s : walls) {
    const Eigen::Vector2d d = s.b - s.a;
    double a = std::atan2(d.y(), d.x());
    a = std::fmod(a, M_PI / 2);
    if (a < 0) a += M_PI / 2;
    h[static_cast<std::size_t>(std::min(bins - 1, int(a / (M_PI / 2) * bins)))] += d.norm();
  }
  std::vector<double> smooth(bins, 0.0);
  for (int i = 0; i < bins; ++i)
    for (int k = -2; k <= 2; ++k) smooth[i] += h[(i + k + bins) % bins] * (3 - std::abs(k));
  const double top = *std::max_element(smooth.begin(), smooth.end());
  std::vector<double> out;
  for (int i = 0; i < bins; ++i) {
    const double v = smooth[i];
    if (v <= 0 || v < 0.5 * top) continue;
    if (v < smooth[(i + 1) % bins] || v < smooth[(i + bins - 1) % bins]) continue;
    // Mean direction of the bin's neighbourhood (weighted), for a sub-bin estimate.
    double sum = 0, w = 0;
    for (int k = -2; k <= 2; ++k) {
      sum += h[(i + k + bins) % bins] * (i + k + 0.5);
      w += h[(i + k + bins) % bins];
    }
    double a = (w > 0 ? sum / w : i + 0.5) * (M_PI / 2) / bins;
    a = std::fmod(a + M_PI / 2, M_PI / 2);
    out.push_back(a);
    if (out.size() >= 3) break;
  }
  return out;
}

double points_direction(const std::vector<Eigen::Vector2d>& points) {
  // Points on walls along direction a project onto the normal to few bins: sum of squared bin counts over
  // the axes a and a + 90 deg, largest at the walls' direction (mod 90).
  double best = 0, best_a = 0;
  const double bin = 0.05;
  std::vector<int> counts;
  auto peakiness = [&](double a) {
    double total = 0;
    for (int axis = 0; axis < 2; ++axis) {
      const double t = a + axis * M_PI / 2;
      const Eigen::Vector2d n(std::cos(t), std::sin(t));
      double lo = std::numeric_limits<double>::max(), hi = -lo;
      for (const Eigen::Vector2d& p : points) {
        lo = std::min(lo, p.dot(n));
        hi = std::max(hi, p.dot(n));
      }
      counts.assign(static_cast<std::size_t>((hi - lo) / bin) + 2, 0);
      for (const Eigen::Vector2d& p : points) ++counts[static_cast<std::size_t>((p.dot(n) - lo) / bin)];
      for (int c : counts) total += double(c) * c;
    }
    return total;
  };
  for (double deg = 0; deg < 90; deg += 1.0) {
    const double v = peakiness(deg * M_PI / 180);
    if (v > best) {
      best = v;
      best_a = deg;
    }
  }
  for (double deg = best_a - 1; deg <= best_a + 1; deg += 0.1) {
    const double v = peakiness(deg * M_PI / 180);
    if (v > best) {
      best = v;
      best_a = deg;
    }
  }
  double a = std::fmod(best_a * M_PI / 180 + M_PI / 2, M_PI / 2);
  return a;
}

}  // namespace plenopath::registration_detail
