// Triangular expansion in doubles (see visibility_expansion.h). Nothing here can crash or loop on bad
// floating-point luck: every walk is capped, and a result that fails its checks is refused, so the
// caller answers with the exact CGAL computation instead.
#include "processing/visibility/visibility_expansion.h"

#include <algorithm>
#include <cmath>

namespace plenopath {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Where the ray from q through vertex v meets the wall [A, B] (v itself when v is one of its ends).
// False if the ray misses the wall, is parallel to it, or meets it before reaching v.
bool ray_hit(const WallTriangulation& tri, const Eigen::Vector2d& q, int v, const EnvelopeWedge& w,
             Eigen::Vector2d* hit) {
  if (v == w.wall_a) return *hit = tri.points[w.wall_a], true;
  if (v == w.wall_b) return *hit = tri.points[w.wall_b], true;
  const Eigen::Vector2d& a = tri.points[w.wall_a];
  const Eigen::Vector2d d = tri.points[v] - q, e = tri.points[w.wall_b] - a, aq = a - q;
  const double denom = cross(d, e);
  if (!(std::abs(denom) > 1e-14 * d.norm() * e.norm())) return false;
  const double t = cross(aq, e) / denom;  // along the ray; 1 at v
  const double u = cross(aq, d) / denom;  // along the wall
  constexpr double kSlack = 1e-9;
  if (!(t >= 1.0 - kSlack && u >= -kSlack && u <= 1.0 + kSlack)) return false;
  *hit = q + t * d;
  return true;
}

}  // namespace

void WallTriangulation::finish() {
  cells_.clear();
  nx_ = ny_ = 0;
  if (points.empty() || corners.empty()) return;
  Eigen::Vector2d lo = points.front(), hi = points.front();
  for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector2d size = (hi - lo).cwiseMax(1e-9);
  // About two triangles per cell, at most 1 000 cells along a side.
  cell_size_ = std::sqrt(size.x() * size.y() / std::max<std::size_t>(1, corners.size() / 2));
  cell_size_ = std::max({cell_size_, size.x() / 1000.0, size.y() / 1000.0});
  origin_ = lo;
  nx_ = std::max(1, static_cast<int>(std::ceil(size.x() / cell_size_)));
  ny_ = std::max(1, static_cast<int>(std::ceil(size.y() / cell_size_)));
  cells_.assign(static_cast<std::size_t>(nx_) * ny_, {});
  auto clamp_x = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - origin_.x()) / cell_size_)), 0, nx_ - 1);
  };
  auto clamp_y = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - origin_.y()) / cell_size_)), 0, ny_ - 1);
  };
  for (std::size_t t = 0; t < corners.size(); ++t) {
    Eigen::Vector2d tlo = points[corners[t][0]], thi = tlo;
    for (int k = 1; k < 3; ++k)
      tlo = tlo.cwiseMin(points[corners[t][k]]), thi = thi.cwiseMax(points[corners[t][k]]);
    for (int y = clamp_y(tlo.y()); y <= clamp_y(thi.y()); ++y)
      for (int x = clamp_x(tlo.x()); x <= clamp_x(thi.x()); ++x)
        cells_[static_cast<std::size_t>(y) * nx_ + x].push_back(static_cast<int>(t));
  }
}

int WallTriangulation::locate(const Eigen::Vector2d& p, int* on_edge) const {
  *on_edge = -1;
  if (cells_.empty() || !p.allFinite()) return -1;
  const double fx = std::floor((p.x() - origin_.x()) / cell_size_),
               fy = std::floor((p.y() - origin_.y()) / cell_size_);
  if (fx < 0 || fy < 0 || fx >= nx_ || fy >= ny_) return -1;
  constexpr double kMargin = 1e-9;  // metres
  int edge_triangle = -1, edge = -1;
  for (int t : cells_[static_cast<std::size_t>(fy) * nx_ + static_cast<std::size_t>(fx)]) {
    int inside = 0, near = -1;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d& a = points[corners[t][(k + 1) % 3]];
      const Eigen::Vector2d& b = points[corners[t][(k + 2) % 3]];
      const double length = (b - a).norm();
      if (!(length > 0.0)) break;
      const double distance = cross(b - a, p - a) / length;  // positive inside
      if (distance > kMargin)
        ++inside;
      else if (distance >= -kMargin)
        near = k;
    }
    if (inside == 3) return t;
    if (inside == 2 && near >= 0) edge_triangle = t, edge = near;
  }
  *on_edge = edge;
  return edge_triangle;
}

bool expand_envelope(const WallTriangulation& tri, const Eigen::Vector2d& p, long max_steps,
                     std::vector<EnvelopeWedge>* wedges, double* area) {
  wedges->clear();
  int on_edge = -1;
  const int start = tri.locate(p, &on_edge);
  if (start < 0) return false;
  // A window: seen from p through the edge opposite corner `edge` of triangle `triangle`, between the rays
  // through points `right` and `left`.
  struct Window {
    int triangle, edge, right, left;
  };
  std::vector<Window> stack;
  // Depth first, right before left, so the wedges come out counter-clockwise and each shares its left
  // ray with the next one's right ray.
  const auto& sc = tri.corners[start];
  if (on_edge < 0) {
    for (int k = 2; k >= 0; --k) stack.push_back({start, k, sc[(k + 1) % 3], sc[(k + 2) % 3]});
  } else {
    // p on the edge A -> B opposite corner k: the two other edges of this triangle, then the two of the
    // neighbour (B, A, C) beyond, each seen across less than a half turn.
    const int k = on_edge, a = sc[(k + 1) % 3], b = sc[(k + 2) % 3];
    const int other = tri.neighbours[start][k];
    if (tri.walls[start][k] || other < 0) return false;  // on a wall
    const auto& oc = tri.corners[other];
    int j = 0;
    while (j < 3 && (oc[j] == a || oc[j] == b)) ++j;
    if (j == 3 || oc[(j + 2) % 3] != a || oc[(j + 1) % 3] != b) return false;
    stack.push_back({other, (j + 2) % 3, oc[j], b});  // C -> B
    stack.push_back({other, (j + 1) % 3, a, oc[j]});  // A -> C
    stack.push_back({start, (k + 2) % 3, sc[k], a});  // corner k -> A
    stack.push_back({start, (k + 1) % 3, b, sc[k]});  // B -> corner k
  }
  long steps = 0;
  while (!stack.empty()) {
    if (++steps > max_steps) return false;
    const Window w = stack.back();
    stack.pop_back();
    if (w.right == w.left) continue;  // no width
    const auto& corners = tri.corners[w.triangle];
    const int a = corners[(w.edge + 1) % 3], b = corners[(w.edge + 2) % 3];
    const int next = tri.neighbours[w.triangle][w.edge];
    if (tri.walls[w.triangle][w.edge]) {
      // A vertex that only splits the window (not an end of this wall) leaves the wall's piece whole.
      if (!wedges->empty() && wedges->back().wall_a == a && wedges->back().wall_b == b &&
          wedges->back().left == w.right)
        wedges->back().left = w.left;
      else
        wedges->push_back({a, b, w.right, w.left});
      continue;
    }
    if (next < 0) return false;  // the triangulation's hull without a wall: p is not in a closed room
    // The neighbour holds the edge as b -> a; c is its third corner.
    const auto& nc = tri.corners[next];
    int j = 0;
    while (j < 3 && (nc[j] == a || nc[j] == b)) ++j;
    if (j == 3 || nc[(j + 2) % 3] != a || nc[(j + 1) % 3] != b) return false;  // inconsistent
    const int c = nc[j];
    const Eigen::Vector2d dr = tri.points[w.right] - p, dl = tri.points[w.left] - p, dc = tri.points[c] - p;
    const double right_of_c = cross(dr, dc), c_of_left = cross(dc, dl);
    const int edge_ac = (j + 1) % 3, edge_cb = (j + 2) % 3;
    if (right_of_c > 0.0 && c_of_left > 0.0) {  // c splits the window
      stack.push_back({next, edge_cb, c, w.left});
      stack.push_back({next, edge_ac, w.right, c});
    } else if (right_of_c <= 0.0) {  // c on or right of the window: it all passes through c -> b
      stack.push_back({next, edge_cb, w.right, w.left});
    } else {
      stack.push_back({next, edge_ac, w.right, w.left});
    }
  }
  // The last wedge may continue the first one's wall piece.
  if (wedges->size() > 1 && wedges->back().wall_a == wedges->front().wall_a &&
      wedges->back().wall_b == wedges->front().wall_b && wedges->back().left == wedges->front().right) {
    wedges->front().right = wedges->back().right;
    wedges->pop_back();
  }
  return wedges_area(tri, *wedges, p, true, area);
}

bool wedges_area(const WallTriangulation& tri, const std::vector<EnvelopeWedge>& wedges,
                 const Eigen::Vector2d& q, bool check_turn, double* area) {
  if (wedges.empty()) return false;
  double twice = 0.0, turn = 0.0;
  for (std::size_t i = 0; i < wedges.size(); ++i) {
    const EnvelopeWedge& w = wedges[i];
    if (w.left != wedges[(i + 1) % wedges.size()].right) return false;
    Eigen::Vector2d hit_right, hit_left;
    if (!ray_hit(tri, q, w.right, w, &hit_right) || !ray_hit(tri, q, w.left, w, &hit_left)) return false;
    const Eigen::Vector2d hr = hit_right - q, hl = hit_left - q;
    const double c = cross(hr, hl);
    if (c < -1e-9 * hr.norm() * hl.norm()) return false;  // turned inside out
    twice += c;
    if (!check_turn) continue;
    const Eigen::Vector2d dr = tri.points[w.right] - q, dl = tri.points[w.left] - q;
    turn += std::atan2(cross(dr, dl), dr.dot(dl));
  }
  if ((check_turn && !(std::abs(turn - 2.0 * M_PI) < 1e-6)) || !std::isfinite(twice)) return false;
  *area = 0.5 * twice;
  return true;
}

}  // namespace plenopath
