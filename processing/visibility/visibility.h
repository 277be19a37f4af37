#pragma once
// Visibility in a floor plan: the envelope (visibility polygon) of a point, its radial function, and the
// visibility events and cells along a camera path. No CGAL here: the arrangement (exact kernel, Epeck) and
// the CGAL visibility classes live in visibility_cgal.cpp behind a pimpl.
//
// Free space: the occluder segments are snapped (~1 mm) and inserted with CGAL::insert (intersections and
// overlaps resolved exactly); dangling walls (ends that touch nothing) are thickened into thin rectangles so
// every wall bounds a face. Faces are classified by nesting: the unbounded face is outside; the faces of
// a wall component that sits in the outside are free (rooms); the faces of a component nested inside free
// space are obstacles (pillars); and so on alternating. A "room" that is only a thin ring (mean width under
// 60 cm) around other walls is the body of a wall drawn with two lines: what lies inside it is free again.
//
// Envelope areas (envelope_area(), the cells' areas) take a fast path by default: triangular expansion in
// doubles over a constrained Delaunay triangulation of the arrangement's edges, built exactly once per
// index (visibility_expansion.h), about 40x cheaper than the exact class on open plans; each answer is
// checked and the exact class answers whenever a check fails. envelope() and the events stay exact.
//
// Thread-safety: a VisibilityIndex is immutable after construction (apart from atomic counters) and its
// const methods may be called from several threads at once: each calling thread gets its own CGAL
// visibility object (CGAL's Triangular_expansion_visibility_2 keeps mutable state and must never be shared
// between threads).
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "model/visibility_cells.h"
#include "processing/util/progress.h"

namespace plenopath {

struct EnvelopeWedge;
struct WallTriangulation;

enum class EnvelopeStatus {
  ok,               // the point is in free space; polygon and area are valid
  on_wall,          // the point lies on a wall (within half the wall thickness): no envelope
  inside_obstacle,  // the point is inside a closed obstacle (pillar): no envelope
  outside,          // the point is outside the building (the unbounded face): no envelope
};
const char* to_string(EnvelopeStatus status);

struct Envelope {
  EnvelopeStatus status = EnvelopeStatus::outside;
  std::vector<Eigen::Vector2d> polygon;  // counter-clockwise, metres, plan frame; empty unless ok
  double area = 0.0;                     // m^2; 0 unless ok
};

// Which CGAL visibility class answers envelope queries (the benchmark compares them).
enum class VisibilityAlgorithm { triangular_expansion, rotational_sweep };

// How envelope areas (envelope_area() and the cells' areas) are computed.
enum class AreaMethod {
  // Triangular expansion in doubles over a constrained triangulation of the walls (built exactly, once),
  // checked, with the exact CGAL class as the fallback when a check fails
  // (processing/visibility/visibility_expansion.h).
  fast_with_exact_fallback,
  // Always CGAL's Triangular_expansion_visibility_2 on the exact kernel.
  exact,
};

// How many envelope areas each method answered since the index was built (benchmarks and tests).
struct EnvelopeAreaCounts {
  std::size_t fast = 0;         // by a fast expansion
  std::size_t closed_form = 0;  // from a cell's wedges at another point of the cell (no expansion)
  std::size_t exact = 0;        // by the exact CGAL class (area_method exact, or the fast path's fallback)
};

struct VisibilityOptions {
  VisibilityAlgorithm algorithm = VisibilityAlgorithm::triangular_expansion;
  // Endpoints closer than this (metres) are merged before the arrangement is built.
  double snap_tolerance_m = 0.001;
  // Gaps in the outer walls up to this wide (metres; windows drawn as gaps, an open entrance) are closed by
  // a segment that blocks sight, so the rooms behind them are inside the building (exterior_openings.h).
  // 0 = leave every gap open.
  double close_openings_up_to_m = 3.0;
  // Width (metres) of the thin rectangle that replaces a dangling wall.
  double dangling_wall_thickness_m = 0.01;
  // Events closer than this along the path (metres) are merged into one.
  double event_merge_distance_m = 1.0e-6;
  // At most this many critical lines are kept for display (the events use all of them).
  std::size_t max_critical_lines = 20000;
  // Threads used for the per-vertex visibility polygons and the cells' areas of cells_along_path
  // (0 = hardware concurrency).
  int threads = 0;
  // How envelope areas are computed. With the fast method a cell's area_mean is the mean of the envelope
  // area over the cell (adaptive Gauss-Legendre, ~1e-7), from the wedges of its one expansion.
  AreaMethod area_method = AreaMethod::fast_with_exact_fallback;
  // Cap on the fast expansion's window steps per query; over it, the exact fallback answers. 0 = automatic
  // (64 per triangle + 10 000). Tests set 1 to exercise the fallback.
  long fast_area_max_steps = 0;
  // With area_method exact only: area_mean by Simpson's rule over each cell (one extra envelope per event);
  // false = area_mid. Off by default: query points exactly on critical lines are near-degenerate and push
  // the exact kernel onto its slow exact path (the benchmark measured about 3x the cost of the middle).
  bool area_mean_simpson = false;
  // Compute the cells' envelope areas at all (with the exact method they dominate cells_along_path's cost
  // on open plans: an exact envelope seen through many doors costs ~2 ms, the fast one ~50 us); false
  // leaves area_mid/area_mean at 0 for a caller that fills them later.
  bool cell_areas = true;

  void check() const;  // throws plenopath::Error saying which field is wrong
};

class VisibilityIndex {
 public:
  // Builds the arrangement of the plan's occluder segments (FloorPlan::occluder_segments()). Throws
  // plenopath::Error if there are none.
  explicit VisibilityIndex(const FloorPlan& plan, const VisibilityOptions& options = {});
  ~VisibilityIndex();
  VisibilityIndex(VisibilityIndex&&) noexcept;
  VisibilityIndex& operator=(VisibilityIndex&&) noexcept;
  VisibilityIndex(const VisibilityIndex&) = delete;
  VisibilityIndex& operator=(const VisibilityIndex&) = delete;

  // The visibility polygon of p (Triangular_expansion_visibility_2, regularized).
  Envelope envelope(const Eigen::Vector2d& p) const;
  EnvelopeStatus classify(const Eigen::Vector2d& p) const;
  // Just the envelope's area (0 unless p is in free space): by options().area_method, i.e. by default the
  // fast expansion with the exact unregularized CGAL class as fallback. Much cheaper than envelope().
  double envelope_area(const Eigen::Vector2d& p) const;
  EnvelopeAreaCounts area_counts() const;

  // Distance from p to the first wall along the world angles k * 2*pi / samples, k = 0 .. samples-1,
  // counter-clockwise from +X (plan frame; NOT the panorama's azimuth, which grows clockwise: use
  // rig/spherical.h's world_angle_of_azimuth to convert). All zeros unless p is in free space.
  std::vector<double> radial_function(const Eigen::Vector2d& p, int samples) const;

  // Visibility events along the path polyline (where the set of visible plan vertices changes), the cells
  // between them, and the critical lines (windows of the vertices' visibility polygons) for display.
  // Event.frame is the position i in path.frames of the path segment [i, i+1] holding the event. The path
  // also has an event where it crosses a wall. A cell spans [s_begin, s_end] between consecutive events
  // (the first starts at 0, the last ends at the path's length); first_frame/last_frame are the positions
  // of the first and last frame inside it, or both the frame nearest its middle if no frame falls inside.
  // The envelope is computed once per cell (at its middle), never per frame: with the fast area method the
  // cell's mean area comes from that one expansion's wedges in closed form; with the exact method
  // area_mean is area_mid, or Simpson's rule with one more envelope per event (area_mean_simpson). The
  // cells run on `threads` threads; the result does not depend on their number or timing.
  // `progress` gets the fraction done, from worker threads too; a cancel ends it with Cancelled
  // (the exception reaches the caller once the workers have stopped, within a few envelope queries).
  VisibilityCells cells_along_path(const CameraPath& path, Progress& progress = null_progress()) const;

  // The segments CGAL sees after snapping and thickening (for display and for independent test oracles).
  std::vector<PlanSegment> effective_segments() const;
  // The segments that closed the outer walls' openings (part of effective_segments()).
  std::vector<PlanSegment> closed_openings() const;
  // The arrangement's vertices (the plan vertices that events refer to).
  std::vector<Eigen::Vector2d> vertices() const;

 private:
  // Windows of every plan vertex's visibility polygon: the critical lines the events come from.
  std::vector<CriticalLine> vertex_windows(Progress& progress = null_progress()) const;
  const VisibilityOptions& options() const;
  // The exact area by the unregularized CGAL class; -1 unless p is in free space.
  double exact_envelope_area(const Eigen::Vector2d& p) const;
  // p's envelope area by options().area_method (-1 unless p is in free space) and, when the fast path
  // answered, its wedges (else they are left empty).
  double area_and_wedges(const Eigen::Vector2d& p, std::vector<EnvelopeWedge>* wedges) const;
  // The cell's area at its middle and its mean area over [s_begin, s_end] of the path polyline.
  void areas_of_cell(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& s_at,
                     double s_begin, double s_end, double* area_mid, double* area_mean) const;
  const WallTriangulation& triangulation() const;
  void count_areas(std::size_t fast, std::size_t closed_form, std::size_t exact) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace plenopath
