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
// Thread-safety: a VisibilityIndex is immutable after construction and its const methods may be called
// from several threads at once: each calling thread gets its own CGAL visibility object (CGAL's
// Triangular_expansion_visibility_2 keeps mutable state and must never be shared between threads).
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "model/visibility_cells.h"

namespace plenopath {

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

struct VisibilityOptions {
  VisibilityAlgorithm algorithm = VisibilityAlgorithm::triangular_expansion;
  // Endpoints closer than this (metres) are merged before the arrangement is built.
  double snap_tolerance_m = 0.001;
  // Width (metres) of the thin rectangle that replaces a dangling wall.
  double dangling_wall_thickness_m = 0.01;
  // Events closer than this along the path (metres) are merged into one.
  double event_merge_distance_m = 1.0e-6;
  // At most this many critical lines are kept for display (the events use all of them).
  std::size_t max_critical_lines = 20000;
  // Threads used for the per-vertex visibility polygons of cells_along_path (0 = hardware concurrency).
  int threads = 0;
  // area_mean by Simpson's rule over each cell (one extra envelope per event); false = area_mid. Off by
  // default: query points exactly on critical lines are near-degenerate and push the exact kernel onto
  // its slow exact path (the benchmark measured about 3x the cost of the middle queries).
  bool area_mean_simpson = false;
  // Compute the cells' envelope areas at all. They dominate cells_along_path's cost on open plans (an
  // envelope seen through many doors costs ~2 ms); false leaves area_mid/area_mean at 0 for a caller
  // that fills them later (e.g. only for the cells it samples).
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
  // Just the envelope's area (0 unless p is in free space), from the unregularized visibility class:
  // cheaper than envelope() where the polygon is not needed.
  double envelope_area(const Eigen::Vector2d& p) const;

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
  // The envelope is computed once per cell (its middle; also once per event if area_mean_simpson), never
  // per frame; those queries run on `threads` threads.
  // `progress` (optional) is called with the fraction done, from worker threads too; it may throw to cancel
  // (the exception reaches the caller once the workers have stopped, within a few envelope queries).
  VisibilityCells cells_along_path(const CameraPath& path,
                                   const std::function<void(double fraction)>& progress = {}) const;

  // The segments CGAL sees after snapping and thickening (for display and for independent test oracles).
  std::vector<PlanSegment> effective_segments() const;
  // The arrangement's vertices (the plan vertices that events refer to).
  std::vector<Eigen::Vector2d> vertices() const;

 private:
  // Windows of every plan vertex's visibility polygon: the critical lines the events come from.
  std::vector<CriticalLine> vertex_windows(const std::function<void(double fraction)>& progress = {}) const;
  const VisibilityOptions& options() const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace plenopath
