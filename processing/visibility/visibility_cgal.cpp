// The CGAL half of processing/visibility/visibility.h: the exact arrangement of the walls, face
// classification, the envelope queries and the per-vertex visibility polygons. Everything else (radial
// functions, events, cells) is plain double code in visibility.cpp.
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_landmarks_point_location.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Rotational_sweep_visibility_2.h>
#include <CGAL/Triangular_expansion_visibility_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <atomic>
#include <boost/variant/get.hpp>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>
#include <unordered_map>

#include "model/error.h"
#include "processing/plan/exterior_openings.h"
#include "processing/plan/segment_grid.h"
#include "processing/visibility/visibility.h"
#include "processing/visibility/visibility_expansion.h"

namespace plenopath {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Traits = CGAL::Arr_segment_traits_2<Kernel>;
using Point = Traits::Point_2;
using Curve = Traits::Curve_2;
// Face data: what the face is (see FaceKind).
using Dcel = CGAL::Arr_face_extended_dcel<Traits, int>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;
using OutputArrangement = CGAL::Arrangement_2<Traits>;
using Locator = CGAL::Arr_landmarks_point_location<Arrangement>;
// The regularization tag is spelled out: the 5.5.1 headers' default differs from the manual.
using TriangularVisibility = CGAL::Triangular_expansion_visibility_2<Arrangement, CGAL::Tag_true>;
using SweepVisibility = CGAL::Rotational_sweep_visibility_2<Arrangement, CGAL::Tag_true>;
// Unregularized: may leave needles in the output, which add no area; used where only the area counts.
using TriangularVisibilityRaw = CGAL::Triangular_expansion_visibility_2<Arrangement, CGAL::Tag_false>;

// The walls' constrained triangulation for the fast area path; vertex and face infos are indices. The
// arrangement's edges meet only at its vertices, so no constraint intersection is ever constructed.
using CdtVertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using CdtFaceBase =
    CGAL::Triangulation_face_base_with_info_2<int, Kernel,
                                              CGAL::Constrained_triangulation_face_base_2<Kernel>>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    Kernel, CGAL::Triangulation_data_structure_2<CdtVertexBase, CdtFaceBase>,
    CGAL::No_constraint_intersection_requiring_constructions_tag>;

enum FaceKind : int { kUnset = -1, kOutside = 0, kFree = 1, kObstacle = 2, kWallInterior = 3 };

Eigen::Vector2d to_eigen(const Point& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

// Endpoints within `tolerance` collapse onto the first one seen (grid hashing with neighbour lookup).
std::vector<Segment2> snap_segments(const std::vector<PlanSegment>& input, double tolerance) {
  std::unordered_map<long long, std::vector<Eigen::Vector2d>> cells;
  const double cell = std::max(tolerance, 1e-9);
  auto key = [](long long x, long long y) { return x * 73856093LL ^ y * 19349663LL; };
  auto snap = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d {
    const long long cx = static_cast<long long>(std::floor(p.x() / cell));
    const long long cy = static_cast<long long>(std::floor(p.y() / cell));
    for (long long dy = -1; dy <= 1; ++dy)
      for (long long dx = -1; dx <= 1; ++dx) {
        auto it = cells.find(key(cx + dx, cy + dy));
        if (it == cells.end()) continue;
        for (const auto& q : it->second)
          if ((q - p).norm() <= tolerance) return q;
      }
    cells[key(cx, cy)].push_back(p);
    return p;
  };
  std::vector<Segment2> out;
  out.reserve(input.size());
  for (const auto& s : input) {
    if (!s.a.allFinite() || !s.b.allFinite()) continue;
    Segment2 t{snap(s.a), snap(s.b)};
    if ((t.a - t.b).norm() > 0.0) out.push_back(t);
  }
  return out;
}

void insert_segments(Arrangement* arr, const std::vector<Segment2>& segments) {
  std::vector<Curve> curves;
  curves.reserve(segments.size());
  for (const auto& s : segments) curves.emplace_back(Point(s.a.x(), s.a.y()), Point(s.b.x(), s.b.y()));
  // CGAL::insert (never insert_non_intersecting_curves): walls ending on walls, overlaps and crossings.
  CGAL::insert(*arr, curves.begin(), curves.end());
}

// The four sides of a thin rectangle of width `width` around [a, b].
void add_rectangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width,
                   std::vector<Segment2>* out) {
  const Eigen::Vector2d d = (b - a).normalized();
  const Eigen::Vector2d n(-d.y() * width * 0.5, d.x() * width * 0.5);
  const Eigen::Vector2d p0 = a + n, p1 = b + n, p2 = b - n, p3 = a - n;
  out->push_back({p0, p1});
  out->push_back({p1, p2});
  out->push_back({p2, p3});
  out->push_back({p3, p0});
}

}  // namespace

struct VisibilityIndex::Impl {
  VisibilityOptions options;
  Arrangement arr;
  std::unique_ptr<Locator> locator;
  std::vector<Segment2> closings;           // the segments that close the outer walls' openings
  std::vector<Segment2> edges;              // the arrangement's edges in doubles
  std::unique_ptr<SegmentGrid> edge_grid;   // over `edges`
  std::unique_ptr<SegmentGrid> thick_grid;  // over the centre lines of thickened dangling walls
  double half_thickness = 0.005;
  WallTriangulation triangulation;  // the walls' constrained triangulation in doubles (fast area path)
  std::atomic<std::size_t> fast_areas{0}, closed_form_areas{0}, exact_areas{0};

  // One visibility object per thread: CGAL's keep mutable state. Created under the mutex because their
  // constructors attach observers to the (shared) arrangement.
  mutable std::mutex visibility_mutex;
  mutable std::map<std::thread::id, std::unique_ptr<TriangularVisibility>> triangular;
  mutable std::map<std::thread::id, std::unique_ptr<SweepVisibility>> sweep;
  mutable std::map<std::thread::id, std::unique_ptr<TriangularVisibilityRaw>> triangular_raw;

  template <typename V>
  V& visibility_for_this_thread(std::map<std::thread::id, std::unique_ptr<V>>* objects) const {
    std::lock_guard<std::mutex> lock(visibility_mutex);
    auto& slot = (*objects)[std::this_thread::get_id()];
    if (!slot) slot = std::make_unique<V>(arr);
    return *slot;
  }

  void build(const FloorPlan& plan);
  void classify_faces();
  void triangulate();
  // Status of p and, when ok, the face holding it.
  EnvelopeStatus locate(const Eigen::Vector2d& p, Arrangement::Face_const_handle* face) const;
  template <typename V, typename Q>
  std::vector<Eigen::Vector2d> visibility_polygon(V& vis, const Point& q, Q where) const {
    OutputArrangement out;
    auto f = vis.compute_visibility(q, where, out);
    std::vector<Eigen::Vector2d> polygon;
    if (f->is_unbounded() || !f->has_outer_ccb()) return polygon;
    auto first = f->outer_ccb(), curr = first;
    do {
      polygon.push_back(to_eigen(curr->source()->point()));
    } while (++curr != first);
    return polygon;
  }
};

void VisibilityIndex::Impl::build(const FloorPlan& plan) {
  std::vector<Segment2> walls = snap_segments(plan.occluder_segments(), options.snap_tolerance_m);
  if (walls.empty())
    throw Error(std::string("visibility: the plan") +
                (plan.source_file.empty() ? "" : " " + plan.source_file) +
                " has no occluding segments (choose the wall layers)");
  half_thickness = options.dangling_wall_thickness_m * 0.5;
  // Windows and entrances drawn as gaps would make the rooms behind them part of the outside.
  ExteriorOpeningOptions openings;
  openings.max_opening_m = options.close_openings_up_to_m;
  closings = exterior_openings(walls, openings);
  walls.insert(walls.end(), closings.begin(), closings.end());

  // Dangling walls (antennas: both sides of the edge are the same face) become thin rectangles, so every
  // edge CGAL's visibility sees bounds two different faces. Repeat in case thickening made new antennas.
  std::vector<Segment2> thick_centres;
  for (int round = 0; round < 3; ++round) {
    Arrangement trial;
    insert_segments(&trial, walls);
    std::vector<Segment2> kept, thickened;
    for (auto e = trial.edges_begin(); e != trial.edges_end(); ++e) {
      const Segment2 s{to_eigen(e->source()->point()), to_eigen(e->target()->point())};
      if (e->face() == e->twin()->face()) {
        thick_centres.push_back(s);
        add_rectangle(s.a, s.b, options.dangling_wall_thickness_m, &thickened);
      } else {
        kept.push_back(s);
      }
    }
    if (thickened.empty()) break;
    kept.insert(kept.end(), thickened.begin(), thickened.end());
    walls = std::move(kept);
  }
  insert_segments(&arr, walls);
  // Arr_segment_traits_2 computes a curve's supporting line on first use and caches it in mutable members:
  // two worker threads locating points at once would both write it (a data race that corrupted the heap
  // about one run in three). Fill every cache now, so concurrent queries only read the arrangement.
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) (void)e->curve().line();
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
    edges.push_back({to_eigen(e->source()->point()), to_eigen(e->target()->point())});
  edge_grid = std::make_unique<SegmentGrid>(edges);
  thick_grid = std::make_unique<SegmentGrid>(thick_centres);
  classify_faces();
  locator = std::make_unique<Locator>(arr);
  triangulate();
}

// The arrangement's vertices and edges as a constrained Delaunay triangulation (exact), then in doubles.
void VisibilityIndex::Impl::triangulate() {
  Cdt cdt;
  std::unordered_map<const void*, Cdt::Vertex_handle> vertex_of;
  for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) vertex_of[&*v] = cdt.insert(v->point());
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
    cdt.insert_constraint(vertex_of.at(&*e->source()), vertex_of.at(&*e->target()));
  WallTriangulation& t = triangulation;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    v->info() = static_cast<int>(t.points.size());
    t.points.push_back(to_eigen(v->point()));
  }
  int faces = 0;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) f->info() = faces++;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    std::array<int, 3> corners{}, neighbours{};
    std::array<bool, 3> walls{};
    for (int i = 0; i < 3; ++i) {
      corners[i] = f->vertex(i)->info();
      neighbours[i] = cdt.is_infinite(f->neighbor(i)) ? -1 : f->neighbor(i)->info();
      walls[i] = f->is_constrained(i);
    }
    t.corners.push_back(corners);
    t.neighbours.push_back(neighbours);
    t.walls.push_back(walls);
  }
  t.finish();
}

// Nesting: the unbounded face is outside; the faces of a wall component lying in an outside face are free
// (rooms), those of a component lying in a free face are obstacles (pillars), alternating. A "room" that is
// only a thin ring around other walls is the body of a double-line wall: what lies inside it is free again.
// Faces whose corners all lie within the thickness of a thickened dangling wall are that wall's inside.
namespace {

// Signed area and length of one boundary cycle of a face.
template <typename Circulator>
void cycle_area_and_length(Circulator first, double* area, double* length) {
  double a = 0, l = 0;
  auto curr = first;
  do {
    const Eigen::Vector2d p = to_eigen(curr->source()->point()), q = to_eigen(curr->target()->point());
    a += p.x() * q.y() - q.x() * p.y();
    l += (q - p).norm();
  } while (++curr != first);
  *area = 0.5 * a;
  *length = l;
}

// A face whose mean width (2 area / perimeter) is under a wall's thickness is the body of a wall, not a
// room: with holes, a wall drawn with two lines (an outer wall whose inner line is a loop of its own);
// without, a wall drawn as a closed outline, or the reveal between an opening's inner and outer closing.
bool is_wall_body(Arrangement::Face_const_handle f, double max_wall_thickness) {
  if (!f->has_outer_ccb()) return false;
  double area = 0, perimeter = 0, a = 0, l = 0;
  cycle_area_and_length(f->outer_ccb(), &a, &l);
  area += std::abs(a);
  perimeter += l;
  for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole) {
    cycle_area_and_length(*hole, &a, &l);
    area -= std::abs(a);
    perimeter += l;
  }
  return perimeter > 0 && 2.0 * area / perimeter < max_wall_thickness;
}

}  // namespace

void VisibilityIndex::Impl::classify_faces() {
  // Walls thicker than this are not drawn as two lines (60 cm: thick masonry).
  constexpr double kMaxWallThickness = 0.6;
  // A closed outline this thin (mean width) is a wall's body; a 1 m x 1 m closet (0.5) is still a room.
  constexpr double kMaxSolidWallThickness = 0.5;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) f->set_data(kUnset);
  std::vector<Arrangement::Face_handle> queue;
  auto top = arr.unbounded_face();
  top->set_data(kOutside);
  queue.push_back(top);
  for (std::size_t qi = 0; qi < queue.size(); ++qi) {
    auto g = queue[qi];
    const bool has_holes = g->inner_ccbs_begin() != g->inner_ccbs_end();
    if (g->data() == kFree && is_wall_body(g, has_holes ? kMaxWallThickness : kMaxSolidWallThickness))
      g->set_data(kWallInterior);
    // Inside a room: pillars; inside the outside or inside a wall's body: rooms.
    const int inner_kind = (g->data() == kFree) ? kObstacle : kFree;
    for (auto hole = g->inner_ccbs_begin(); hole != g->inner_ccbs_end(); ++hole) {
      // Flood the component behind this hole without crossing back into g.
      std::vector<Arrangement::Face_handle> component;
      auto first = *hole, curr = first;
      do {
        auto y = curr->twin()->face();
        if (y != g && y->data() == kUnset) {
          y->set_data(inner_kind);
          component.push_back(y);
        }
      } while (++curr != first);
      for (std::size_t ci = 0; ci < component.size(); ++ci) {
        auto x = component[ci];
        if (!x->has_outer_ccb()) continue;
        auto f0 = x->outer_ccb(), c = f0;
        do {
          auto z = c->twin()->face();
          if (z != g && z->data() == kUnset) {
            z->set_data(inner_kind);
            component.push_back(z);
          }
        } while (++c != f0);
      }
      queue.insert(queue.end(), component.begin(), component.end());
    }
  }
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->data() == kUnset) f->set_data(kObstacle);  // unreachable: be safe, never query it
    if (f->data() != kFree || thick_grid->segments().empty() || !f->has_outer_ccb()) continue;
    bool all_inside = true;
    auto first = f->outer_ccb(), curr = first;
    do {
      const Eigen::Vector2d v = to_eigen(curr->target()->point());
      if (thick_grid->distance_within(v, half_thickness * 2.0) > half_thickness * (1.0 + 1e-6) + 1e-9) {
        all_inside = false;
        break;
      }
    } while (++curr != first);
    if (all_inside) f->set_data(kWallInterior);
  }
}

EnvelopeStatus VisibilityIndex::Impl::locate(const Eigen::Vector2d& p,
                                             Arrangement::Face_const_handle* face) const {
  if (!p.allFinite()) return EnvelopeStatus::outside;
  if (edge_grid->distance_within(p, 1e-6) <= 1e-9) return EnvelopeStatus::on_wall;
  if (!thick_grid->segments().empty() &&
      thick_grid->distance_within(p, half_thickness * 2.0) <= half_thickness)
    return EnvelopeStatus::on_wall;
  const auto result = locator->locate(Point(p.x(), p.y()));
  const Arrangement::Face_const_handle* f = boost::get<Arrangement::Face_const_handle>(&result);
  if (!f) return EnvelopeStatus::on_wall;  // on a vertex or an edge
  switch ((*f)->data()) {
    case kOutside:
      return EnvelopeStatus::outside;
    case kObstacle:
      return EnvelopeStatus::inside_obstacle;
    case kWallInterior:
      return EnvelopeStatus::on_wall;
    default:
      break;
  }
  if (face) *face = *f;
  return EnvelopeStatus::ok;
}

VisibilityIndex::VisibilityIndex(const FloorPlan& plan, const VisibilityOptions& options)
    : impl_(std::make_unique<Impl>()) {
  options.check();
  impl_->options = options;
  impl_->build(plan);
}

VisibilityIndex::~VisibilityIndex() = default;
VisibilityIndex::VisibilityIndex(VisibilityIndex&&) noexcept = default;
VisibilityIndex& VisibilityIndex::operator=(VisibilityIndex&&) noexcept = default;

const VisibilityOptions& VisibilityIndex::options() const { return impl_->options; }

EnvelopeStatus VisibilityIndex::classify(const Eigen::Vector2d& p) const { return impl_->locate(p, nullptr); }

Envelope VisibilityIndex::envelope(const Eigen::Vector2d& p) const {
  Envelope e;
  Arrangement::Face_const_handle face;
  e.status = impl_->locate(p, &face);
  if (e.status != EnvelopeStatus::ok) return e;
  const Point q(p.x(), p.y());
  if (impl_->options.algorithm == VisibilityAlgorithm::rotational_sweep)
    e.polygon = impl_->visibility_polygon(impl_->visibility_for_this_thread(&impl_->sweep), q, face);
  else
    e.polygon = impl_->visibility_polygon(impl_->visibility_for_this_thread(&impl_->triangular), q, face);
  double twice = 0.0;
  for (std::size_t i = 0; i < e.polygon.size(); ++i) {
    const auto& a = e.polygon[i];
    const auto& b = e.polygon[(i + 1) % e.polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  e.area = 0.5 * twice;
  if (e.area < 0.0) {
    std::reverse(e.polygon.begin(), e.polygon.end());
    e.area = -e.area;
  }
  return e;
}

const WallTriangulation& VisibilityIndex::triangulation() const { return impl_->triangulation; }

void VisibilityIndex::count_areas(std::size_t fast, std::size_t closed_form, std::size_t exact) const {
  impl_->fast_areas += fast;
  impl_->closed_form_areas += closed_form;
  impl_->exact_areas += exact;
}

EnvelopeAreaCounts VisibilityIndex::area_counts() const {
  EnvelopeAreaCounts counts;
  counts.fast = impl_->fast_areas;
  counts.closed_form = impl_->closed_form_areas;
  counts.exact = impl_->exact_areas;
  return counts;
}

double VisibilityIndex::exact_envelope_area(const Eigen::Vector2d& p) const {
  Arrangement::Face_const_handle face;
  if (impl_->locate(p, &face) != EnvelopeStatus::ok) return -1.0;
  const auto polygon = impl_->visibility_polygon(impl_->visibility_for_this_thread(&impl_->triangular_raw),
                                                 Point(p.x(), p.y()), face);
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const auto& a = polygon[i];
    const auto& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * std::abs(twice);
}

namespace {

// Segments as sight-blocking plan segments (for display and test oracles).
std::vector<PlanSegment> as_occluders(const std::vector<Segment2>& segments) {
  std::vector<PlanSegment> out;
  out.reserve(segments.size());
  for (const auto& s : segments) {
    PlanSegment p;
    p.a = s.a;
    p.b = s.b;
    p.occluder = true;
    out.push_back(p);
  }
  return out;
}

}  // namespace

std::vector<PlanSegment> VisibilityIndex::closed_openings() const { return as_occluders(impl_->closings); }

std::vector<PlanSegment> VisibilityIndex::effective_segments() const { return as_occluders(impl_->edges); }

std::vector<Eigen::Vector2d> VisibilityIndex::vertices() const {
  std::vector<Eigen::Vector2d> out;
  for (auto v = impl_->arr.vertices_begin(); v != impl_->arr.vertices_end(); ++v)
    out.push_back(to_eigen(v->point()));
  return out;
}

// For every vertex and every wedge of free space around it, the visibility polygon from the vertex; its
// edges that lie on no wall are windows: crossing one changes whether the vertex is visible.
std::vector<CriticalLine> VisibilityIndex::vertex_windows(Progress& progress) const {
  const Impl& impl = *impl_;
  std::vector<Arrangement::Halfedge_const_handle> wedges;
  for (auto v = impl.arr.vertices_begin(); v != impl.arr.vertices_end(); ++v) {
    if (v->is_isolated()) continue;
    auto first = v->incident_halfedges(), curr = first;
    do {
      if (curr->face()->data() == kFree) wedges.push_back(curr);
    } while (++curr != first);
  }
  int threads = impl.options.threads > 0
                    ? impl.options.threads
                    : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::max(1, std::min<int>(threads, static_cast<int>(wedges.size() / 64) + 1));
  // One list per wedge, joined in wedge order: the result does not depend on the threads' timing.
  std::vector<std::vector<CriticalLine>> per_wedge(wedges.size());
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&]() {
    try {
      auto& vis = impl.visibility_for_this_thread(&impl.triangular);
      for (std::size_t i = next++; i < wedges.size(); i = next++) {
        if (i % 16 == 0) progress.checkpoint(static_cast<double>(i) / wedges.size());
        const auto he = wedges[i];
        const Eigen::Vector2d v = to_eigen(he->target()->point());
        const auto polygon = impl.visibility_polygon(vis, he->target()->point(), he);
        for (std::size_t k = 0; k < polygon.size(); ++k) {
          const Eigen::Vector2d& a = polygon[k];
          const Eigen::Vector2d& b = polygon[(k + 1) % polygon.size()];
          const double len = (b - a).norm();
          if (len < 1e-9) continue;
          // Windows lie on a ray from the vertex.
          const double cross = (a - v).x() * (b - v).y() - (a - v).y() * (b - v).x();
          if (std::abs(cross) > 1e-9 * std::max(1.0, (a - v).norm() + (b - v).norm()) * len) continue;
          if (impl.edge_grid->distance_within(0.5 * (a + b), 1e-6) <= 1e-7) continue;  // on a wall
          // Orient from the occluding vertex (nearer to v) outwards.
          CriticalLine line;
          const bool a_nearer = (a - v).squaredNorm() <= (b - v).squaredNorm();
          line.a = a_nearer ? a : b;
          line.b = a_nearer ? b : a;
          per_wedge[i].push_back(line);
        }
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next = wedges.size();
    }
  };
  if (threads == 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(work);
    for (auto& th : pool) th.join();
  }
  if (failure) std::rethrow_exception(failure);
  std::vector<CriticalLine> out;
  for (auto& lines : per_wedge) out.insert(out.end(), lines.begin(), lines.end());
  return out;
}

}  // namespace plenopath
