#pragma once
// The fast path of VisibilityIndex's envelope areas: triangular expansion in doubles over a constrained
// triangulation of the walls. The triangulation is built exactly (CGAL, visibility_cgal.cpp) once per
// index and handed over in doubles; this file has no CGAL. The exact CGAL classes stay the fallback.
//
// From a point p strictly inside a triangle the expansion walks across the edges that are not walls,
// narrowing an angular window as it goes; where a window meets a wall, the wedge (p, hit of its right ray,
// hit of its left ray) is visible. The envelope is the union of those wedges, so its area is the sum of
// theirs. Every wedge's two rays pass through triangulation vertices, and neighbouring wedges share them.
// Inside one visibility cell those vertices and walls do not change (a change is a visibility event), so
// the same wedges give the envelope area in closed form at any other point of the cell: that is how the
// cells' mean areas are integrated from one expansion per cell.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace plenopath {

struct WallTriangulation {
  std::vector<Eigen::Vector2d> points;
  std::vector<std::array<int, 3>> corners;     // point indices, counter-clockwise
  std::vector<std::array<int, 3>> neighbours;  // triangle across the edge opposite corner i; -1 = none
  std::vector<std::array<bool, 3>> walls;      // the edge opposite corner i is a wall

  // Builds the lookup grid; call once after filling the arrays above.
  void finish();
  // The triangle holding p at least 1e-9 m inside each of its edges' lines (*on_edge = -1); else one
  // holding p within 1e-9 m of the line of its edge *on_edge (opposite that corner) and at least 1e-9 m
  // inside the other two; else -1 (p near a vertex or outside the triangulation).
  int locate(const Eigen::Vector2d& p, int* on_edge) const;

 private:
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_size_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<int>> cells_;  // triangles whose bounding box overlaps each grid cell
};

// One visible piece of a wall: seen from the query point between the rays through `right` and `left`
// (point indices; clockwise to counter-clockwise), on the wall from point `wall_a` to `wall_b`.
struct EnvelopeWedge {
  int wall_a = 0, wall_b = 0;
  int right = 0, left = 0;
};

// The wedges of p's envelope, counter-clockwise, one per visible piece of wall, and its area. False (and
// the caller falls back to the exact computation) when p is not safely inside a triangle or on the inside
// of an edge that is not a wall, the expansion
// exceeds max_steps window steps, or the result fails the checks of wedges_area at p (including that the
// rays turn exactly once around p).
bool expand_envelope(const WallTriangulation& triangulation, const Eigen::Vector2d& p, long max_steps,
                     std::vector<EnvelopeWedge>* wedges, double* area);

// The envelope area at q from wedges found at a point of the same visibility cell. False when they no
// longer describe q's envelope: a ray that misses its wall or meets it before its vertex, or a wedge turned
// inside out (each wedge spans less than a half turn, so while none turns inside out along a path inside
// the cell, the rays keep turning once around q; check_turn checks that too, with one atan2 per wedge).
bool wedges_area(const WallTriangulation& triangulation, const std::vector<EnvelopeWedge>& wedges,
                 const Eigen::Vector2d& q, bool check_turn, double* area);

}  // namespace plenopath
