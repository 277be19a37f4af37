// Closing the openings of a building's outer walls. A disc of diameter max_opening_m rolled in from far
// outside (on a raster of the walls) covers the outside and cannot pass the openings; a candidate segment
// between two wall endpoints closes an opening when one side of it starts in covered space and the other
// reaches space the disc never covered. Reflex corners of the outline (covered on both sides) and gaps
// between a pillar and a wall inside a room (uncovered on both sides) are left alone.
#include "processing/plan/exterior_openings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>
#include <unordered_map>

#include "model/error.h"
#include "processing/plan/grid_key.h"

namespace plenopath {

void ExteriorOpeningOptions::check() const {
  auto fail = [](const std::string& what) { throw Error("exterior opening options: " + what); };
  if (!(max_opening_m >= 0.0 && max_opening_m <= 50.0)) fail("max_opening_m must be in [0, 50] m");
  if (!(cell_m > 0.0 && cell_m <= 1.0)) fail("cell_m must be in (0, 1] m");
}

namespace {

// kShallow: uncovered, but too thin to be a room: the body of a wall drawn as an outline, or the bit of a
// concave corner of the outside that a disc cannot fill.
enum CellKind : std::uint8_t { kWall = 0, kCovered = 1, kUncovered = 2, kShallow = 3 };

struct OpeningRaster {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell = 0.05;
  cv::Mat kind;  // CV_8U CellKind
  int kind_at(const Eigen::Vector2d& p) const {
    const int c = static_cast<int>(std::floor((p.x() - origin.x()) / cell));
    const int r = static_cast<int>(std::floor((p.y() - origin.y()) / cell));
    if (c < 0 || r < 0 || c >= kind.cols || r >= kind.rows) return kCovered;  // beyond the raster: outside
    return kind.at<std::uint8_t>(r, c);
  }
};

OpeningRaster rasterize(const std::vector<Segment2>& walls, const ExteriorOpeningOptions& options) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (const Segment2& s : walls) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  const double radius = 0.5 * options.max_opening_m;
  OpeningRaster out;
  // At most 2000 cells a side (4 M cells): a 100 m plan runs at 5 cm, larger ones coarser.
  const double margin = options.max_opening_m + 0.5;
  const double extent = (hi - lo).maxCoeff() + 2 * margin;
  out.cell = std::max(options.cell_m, extent / 2000.0);
  out.origin = lo - Eigen::Vector2d::Constant(margin);
  const int cols = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * margin) / out.cell)) + 1;
  const int rows = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * margin) / out.cell)) + 1;
  cv::Mat wall(rows, cols, CV_8U, cv::Scalar(0));
  auto pixel = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::floor((p.x() - out.origin.x()) / out.cell)),
                     static_cast<int>(std::floor((p.y() - out.origin.y()) / out.cell)));
  };
  for (const Segment2& s : walls) cv::line(wall, pixel(s.a), pixel(s.b), cv::Scalar(255), 1, cv::LINE_8);

  // Where the disc's centre can be: farther than the radius from every wall, and joined to the border.
  cv::Mat distance;
  cv::distanceTransform(wall == 0, distance, cv::DIST_L2, cv::DIST_MASK_5);
  cv::Mat centre_ok = distance * out.cell >= radius;
  cv::Mat labels;
  const int count = cv::connectedComponents(centre_ok, labels, 4, CV_32S);
  std::vector<char> on_border(static_cast<std::size_t>(count), 0);
  for (int c = 0; c < cols; ++c) {
    on_border[labels.at<int>(0, c)] = on_border[labels.at<int>(rows - 1, c)] = 1;
  }
  for (int r = 0; r < rows; ++r) {
    on_border[labels.at<int>(r, 0)] = on_border[labels.at<int>(r, cols - 1)] = 1;
  }
  cv::Mat not_centre(rows, cols, CV_8U, cv::Scalar(255));
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (centre_ok.at<std::uint8_t>(r, c) && on_border[labels.at<int>(r, c)])
        not_centre.at<std::uint8_t>(r, c) = 0;
  // Covered: within the radius of a reachable centre (half a cell of slack for the raster).
  cv::Mat to_centre;
  cv::distanceTransform(not_centre, to_centre, cv::DIST_L2, cv::DIST_MASK_5);
  out.kind.create(rows, cols, CV_8U);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      std::uint8_t k = kUncovered;
      if (wall.at<std::uint8_t>(r, c))
        k = kWall;
      else if ((to_centre.at<float>(r, c) + 0.5) * out.cell <= radius)
        k = kCovered;
      out.kind.at<std::uint8_t>(r, c) = k;
    }
  // A room holds a point deeper than a 90-degree corner's uncovered bit (r (1 - 1/sqrt 2) from the walls)
  // and deeper than half a thick wall (a 1 m closet counts, a 0.6 m wall body does not).
  const double room_depth = std::max(0.35, radius * (1.0 - std::sqrt(0.5))) + 2 * out.cell;
  cv::Mat uncovered = out.kind == kUncovered;
  const int pieces = cv::connectedComponents(uncovered, labels, 4, CV_32S);
  std::vector<float> deepest(static_cast<std::size_t>(pieces), 0.0f);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      float& d = deepest[static_cast<std::size_t>(labels.at<int>(r, c))];
      if (uncovered.at<std::uint8_t>(r, c)) d = std::max(d, distance.at<float>(r, c));
    }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (uncovered.at<std::uint8_t>(r, c) &&
          deepest[static_cast<std::size_t>(labels.at<int>(r, c))] * out.cell < room_depth)
        out.kind.at<std::uint8_t>(r, c) = kShallow;
  return out;
}

// Walking from `from` along `direction` (unit) for at most `length`: the kind of the first non-wall cell
// (after any wall cells the walk starts in), and whether uncovered space is met before the next wall.
struct SideWalk {
  int first = kWall;
  bool meets_uncovered = false;
};
SideWalk walk_side(const OpeningRaster& raster, const Eigen::Vector2d& from, const Eigen::Vector2d& direction,
                   double length) {
  SideWalk out;
  const double step = 0.5 * raster.cell;
  bool left_wall = false;
  for (double t = step; t <= length; t += step) {
    const int k = raster.kind_at(from + t * direction);
    if (k == kWall) {
      if (left_wall) break;
      continue;
    }
    if (!left_wall) out.first = k;
    left_wall = true;
    if (k == kUncovered) {
      out.meets_uncovered = true;
      break;
    }
  }
  return out;
}

bool properly_crosses(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Segment2& s) {
  double t = 0, u = 0;
  if (!intersect_segments(a, b, s.a, s.b, &t, &u)) return false;
  const double eps = 1e-9;
  return t > eps && t < 1 - eps;  // touching at the candidate's own endpoints is fine
}

}  // namespace

std::vector<Segment2> exterior_openings(const std::vector<Segment2>& input,
                                        const ExteriorOpeningOptions& options) {
  options.check();
  std::vector<Segment2> out;
  if (options.max_opening_m <= 0) return out;
  // A drawing's stray NaN or zero-length segment would spoil the raster's extent: left out.
  std::vector<Segment2> walls;
  for (const Segment2& s : input)
    if (s.a.allFinite() && s.b.allFinite() && s.a != s.b) walls.push_back(s);
  if (walls.empty()) return out;
  const OpeningRaster raster = rasterize(walls, options);
  const SegmentGrid grid(walls);

  // The wall endpoints next to covered space (an opening's corners are), without duplicates.
  std::vector<Eigen::Vector2d> corners;
  std::unordered_map<std::int64_t, std::vector<int>> corner_cells;
  const double bucket = options.max_opening_m;
  auto bucket_of = [&](const Eigen::Vector2d& p) {
    return std::make_pair(static_cast<std::int64_t>(std::floor(p.x() / bucket)),
                          static_cast<std::int64_t>(std::floor(p.y() / bucket)));
  };
  // Within half an opening of covered space: an opening's inner corners lie a wall's thickness in.
  cv::Mat to_covered;
  cv::distanceTransform(raster.kind != kCovered, to_covered, cv::DIST_L2, cv::DIST_MASK_5);
  auto near_covered = [&](const Eigen::Vector2d& p) {
    const int c = static_cast<int>(std::floor((p.x() - raster.origin.x()) / raster.cell));
    const int r = static_cast<int>(std::floor((p.y() - raster.origin.y()) / raster.cell));
    if (c < 0 || r < 0 || c >= to_covered.cols || r >= to_covered.rows) return true;
    return to_covered.at<float>(r, c) * raster.cell <= 0.5 * options.max_opening_m + raster.cell;
  };
  for (const Segment2& s : walls)
    for (const Eigen::Vector2d& p : {s.a, s.b}) {
      if (!near_covered(p)) continue;
      const auto [bx, by] = bucket_of(p);
      bool seen = false;
      for (int i : corner_cells[grid_cell_key(bx, by)])
        if ((corners[static_cast<std::size_t>(i)] - p).norm() < 1e-9) seen = true;
      if (seen) continue;
      corner_cells[grid_cell_key(bx, by)].push_back(static_cast<int>(corners.size()));
      corners.push_back(p);
    }

  struct Candidate {
    double length;
    int a, b;
  };
  // Each corner pairs with its nearest corners only: an opening's far corner is among them, and a drawing
  // of densely tessellated curves does not make the pairs grow as the square of its corners.
  constexpr std::size_t kPairsPerCorner = 24;
  const auto by_length = [](const Candidate& x, const Candidate& y) {
    return x.length < y.length || (x.length == y.length && (x.a < y.a || (x.a == y.a && x.b < y.b)));
  };
  std::vector<Candidate> candidates, nearest;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    nearest.clear();
    const auto [bx, by] = bucket_of(corners[i]);
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        auto it = corner_cells.find(grid_cell_key(bx + dx, by + dy));
        if (it == corner_cells.end()) continue;
        for (int j : it->second) {
          if (static_cast<std::size_t>(j) == i) continue;
          const double length = (corners[static_cast<std::size_t>(j)] - corners[i]).norm();
          if (length <= options.max_opening_m)
            nearest.push_back({length, std::min(static_cast<int>(i), j), std::max(static_cast<int>(i), j)});
        }
      }
    if (nearest.size() > kPairsPerCorner) {
      std::nth_element(nearest.begin(), nearest.begin() + kPairsPerCorner, nearest.end(), by_length);
      nearest.resize(kPairsPerCorner);
    }
    candidates.insert(candidates.end(), nearest.begin(), nearest.end());
  }
  std::sort(candidates.begin(), candidates.end(), by_length);
  candidates.erase(
      std::unique(candidates.begin(), candidates.end(),
                  [](const Candidate& x, const Candidate& y) { return x.a == y.a && x.b == y.b; }),
      candidates.end());

  std::vector<char> closed(corners.size(), 0);                       // a corner some accepted closing ends at
  std::unordered_map<std::int64_t, std::vector<int>> closing_cells;  // accepted closings by their middle
  for (const Candidate& c : candidates) {
    // Both ends on closings already (the diagonal of an opening whose inner and outer lines are taken).
    if (closed[static_cast<std::size_t>(c.a)] && closed[static_cast<std::size_t>(c.b)]) continue;
    const Eigen::Vector2d a = corners[static_cast<std::size_t>(c.a)],
                          b = corners[static_cast<std::size_t>(c.b)];
    const Eigen::Vector2d mid = 0.5 * (a + b);
    // On a wall already (an outline's own edge, or collinear with one): nothing to close.
    if (grid.distance_within(mid, 1e-6) < 1e-9) continue;
    const Eigen::Vector2d d = (b - a) / c.length, normal(-d.y(), d.x());
    const SideWalk left = walk_side(raster, mid, normal, options.max_opening_m);
    const SideWalk right = walk_side(raster, mid, -normal, options.max_opening_m);
    const bool separates = (left.first == kCovered && right.meets_uncovered) ||
                           (right.first == kCovered && left.meets_uncovered);
    if (!separates) continue;
    bool crosses = false;
    for (int k : grid.along(a, b))
      if (properly_crosses(a, b, grid.segments()[static_cast<std::size_t>(k)])) crosses = true;
    // An X with a closing already taken (the two diagonals of one opening): keep the shorter. Closings
    // are at most max_opening_m long, so one that crosses has its middle within that of this one's.
    const auto [mx, my] = bucket_of(mid);
    for (std::int64_t dy = -1; dy <= 1 && !crosses; ++dy)
      for (std::int64_t dx = -1; dx <= 1 && !crosses; ++dx) {
        auto it = closing_cells.find(grid_cell_key(mx + dx, my + dy));
        if (it == closing_cells.end()) continue;
        for (int k : it->second) {
          const Segment2& s = out[static_cast<std::size_t>(k)];
          if (properly_crosses(a, b, s) && properly_crosses(s.a, s.b, {a, b})) crosses = true;
        }
      }
    if (crosses) continue;
    closing_cells[grid_cell_key(mx, my)].push_back(static_cast<int>(out.size()));
    out.push_back({a, b});
    closed[static_cast<std::size_t>(c.a)] = closed[static_cast<std::size_t>(c.b)] = 1;
  }
  return out;
}

}  // namespace plenopath
