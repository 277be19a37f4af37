#include "processing/plan/occluder_proposal.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>
#include <unordered_map>

#include "model/layer_names.h"
#include "processing/plan/grid_key.h"
#include "processing/plan/parallel_pairs.h"
#include "processing/plan/segment_grid.h"

namespace plenopath {
namespace {

// What walls and columns look like on a plan, in metres.
constexpr double kMinWallGap = 0.05, kMaxWallGap = 0.6;
constexpr double kMinColumn = 0.1, kMaxColumn = 1.5;
constexpr double kSmallOutline =
    2.0;  // closed outlines up to this size are items (columns, furniture), not walls
constexpr double kOnOutline =
    0.002;  // a segment within this of a small outline's boundary is one of its edges

std::string fixed(double v, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}
std::string count_of(int n, const std::string& thing) {
  return std::to_string(n) + " " + thing + (n == 1 ? "" : "s");
}
std::string range_text(double lo, double hi, const char* unit) {
  const int d = hi < 1.0 ? 2 : 1;
  return fixed(lo, d) == fixed(hi, d) ? fixed(lo, d) + " " + unit
                                      : fixed(lo, d) + "-" + fixed(hi, d) + " " + unit;
}

struct OutlineShape {
  const PlanOutline* outline = nullptr;
  Eigen::Vector2d min, max;
  double extent = 0.0, short_side = 0.0, area = 0.0, perimeter = 0.0;
  bool column_like() const {
    return extent >= kMinColumn && extent <= kMaxColumn && short_side >= 0.5 * extent;
  }
  double thickness() const { return perimeter > 0.0 ? 2.0 * area / perimeter : 0.0; }  // of a thin polygon
  bool wall_like() const {
    return !column_like() && thickness() >= kMinWallGap && thickness() <= kMaxWallGap && perimeter >= 1.0;
  }
};

OutlineShape shape_of(const PlanOutline& o) {
  OutlineShape s;
  s.outline = &o;
  s.min = s.max = o.points.front();
  double twice_area = 0.0;
  for (std::size_t i = 0; i < o.points.size(); ++i) {
    const Eigen::Vector2d& p = o.points[i];
    const Eigen::Vector2d& q = o.points[(i + 1) % o.points.size()];
    s.min = s.min.cwiseMin(p);
    s.max = s.max.cwiseMax(p);
    twice_area += p.x() * q.y() - q.x() * p.y();
    s.perimeter += (q - p).norm();
  }
  s.area = 0.5 * std::abs(twice_area);
  const Eigen::Vector2d size = s.max - s.min;
  s.extent = size.maxCoeff();
  s.short_side = size.minCoeff();
  return s;
}

struct LayerGeometry {
  std::vector<int> segments;  // indices into plan.segments
  std::vector<OutlineShape> closed;
  int labels = 0;
};

// What the geometry of one layer says.
struct GeometryVerdict {
  int pairs = 0;
  double paired_length = 0.0, total_length = 0.0;
  double gap_lo = 0.0, gap_hi = 0.0;
  bool hatch_like = false;  // lines evenly spaced with partners on both sides: a hatch pattern
  int sandwiched = 0, paired_segments = 0;
  int closed = 0, columns = 0, column_group = 0;
  double all_length = 0.0;  // every line of the layer, items' edges included
  double column_lo = 0.0, column_hi = 0.0, column_perimeter = 0.0;
  int fills = 0, fill_walls = 0, fill_columns = 0;
  double fill_thick_lo = 0.0, fill_thick_hi = 0.0;

  bool walls() const {
    return pairs >= 3 && paired_length >= 2.0 && total_length > 0.0 &&
           2.0 * paired_length >= 0.3 * total_length && !hatch_like;
  }
  bool column_layer() const {
    return columns >= 2 && 2 * columns >= closed && column_group >= std::max(2.0, 0.4 * columns) &&
           column_perimeter >= 0.5 * all_length;
  }
  bool solid_fill() const { return fills >= 2 && fill_walls + fill_columns >= std::max(2.0, 0.5 * fills); }
};

// Whether segment s is an edge of one of the layer's small closed outlines (they arrive split and snapped,
// so the test is geometric: inside the outline's box and on its boundary).
class SmallOutlineIndex {
 public:
  explicit SmallOutlineIndex(const std::vector<OutlineShape>& closed) {
    for (const OutlineShape& o : closed)
      if (o.extent <= kSmallOutline) {
        const int index = static_cast<int>(shapes_.size());
        shapes_.push_back(&o);
        for (std::int64_t cx = cell(o.min.x()); cx <= cell(o.max.x()); ++cx)
          for (std::int64_t cy = cell(o.min.y()); cy <= cell(o.max.y()); ++cy)
            cells_[key(cx, cy)].push_back(index);
      }
  }
  bool holds(const PlanSegment& s) const {
    const Eigen::Vector2d mid = 0.5 * (s.a + s.b);
    if (!mid.allFinite() || mid.cwiseAbs().maxCoeff() > 1e9) return false;
    auto it = cells_.find(key(cell(mid.x()), cell(mid.y())));
    if (it == cells_.end()) return false;
    for (int index : it->second) {
      const OutlineShape& o = *shapes_[index];
      const Eigen::Vector2d lo = o.min.array() - kOnOutline, hi = o.max.array() + kOnOutline;
      if ((s.a.array() < lo.array()).any() || (s.a.array() > hi.array()).any() ||
          (s.b.array() < lo.array()).any() || (s.b.array() > hi.array()).any())
        continue;
      const auto& pts = o.outline->points;
      for (std::size_t i = 0; i < pts.size(); ++i)
        if (distance_point_segment(mid, pts[i], pts[(i + 1) % pts.size()]) <= kOnOutline) return true;
    }
    return false;
  }

 private:
  static std::int64_t cell(double v) { return static_cast<std::int64_t>(std::floor(v / kSmallOutline)); }
  static std::int64_t key(std::int64_t cx, std::int64_t cy) { return grid_cell_key(cx, cy); }
  std::vector<const OutlineShape*> shapes_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

GeometryVerdict judge_geometry(const FloorPlan& plan, const LayerGeometry& g, int solid_fills) {
  GeometryVerdict v;
  const SmallOutlineIndex small(g.closed);

  // Walls as two lines: pairs among the segments that are not edges of small items.
  std::vector<Segment2> lines;
  for (int i : g.segments) {
    const PlanSegment& s = plan.segments[static_cast<std::size_t>(i)];
    if (!s.a.allFinite() || !s.b.allFinite()) continue;
    v.all_length += s.length();
    if (small.holds(s)) continue;
    lines.push_back({s.a, s.b});
    v.total_length += s.length();
  }
  ParallelPairOptions o;
  o.min_gap = 0.9 * kMinWallGap;  // a plaster line 1-2 cm off a wall face is not its other side
  o.max_gap = kMaxWallGap;
  const ParallelPairs pairs = find_parallel_pairs(lines, o);
  v.gap_lo = kMaxWallGap;
  for (const ParallelPair& p : pairs.pairs) {
    if (p.gap < kMinWallGap) continue;
    ++v.pairs;
    v.paired_length += p.overlap;
    v.gap_lo = std::min(v.gap_lo, p.gap);
    v.gap_hi = std::max(v.gap_hi, p.gap);
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int l = pairs.left[i], r = pairs.right[i];
    if (l < 0 && r < 0) continue;
    ++v.paired_segments;
    if (l >= 0 && r >= 0) {
      const double a = pairs.pairs[l].gap, b = pairs.pairs[r].gap;
      if (std::abs(a - b) <= 0.25 * std::max(a, b)) ++v.sandwiched;
    }
  }
  v.hatch_like = v.paired_segments >= 6 && v.sandwiched * 2 >= v.paired_segments;

  // Columns: small, roughly square or round closed outlines, most of them the same size.
  v.closed = static_cast<int>(g.closed.size());
  std::vector<const OutlineShape*> columns;
  for (const OutlineShape& s : g.closed)
    if (s.column_like()) columns.push_back(&s);
  v.columns = static_cast<int>(columns.size());
  if (!columns.empty()) {
    // Sizes in bins of 10 % (log scale); the biggest group counts itself and its neighbouring bins.
    std::unordered_map<std::int64_t, int> bins;
    auto bin = [](double v) { return static_cast<std::int64_t>(std::lround(std::log(v) / std::log(1.1))); };
    v.column_lo = v.column_hi = columns.front()->extent;
    for (const OutlineShape* c : columns) {
      v.column_lo = std::min(v.column_lo, c->extent);
      v.column_hi = std::max(v.column_hi, c->extent);
      v.column_perimeter += c->perimeter;
      ++bins[grid_cell_key(bin(c->extent), bin(c->short_side))];
    }
    for (const OutlineShape* c : columns) {
      int same = 0;
      for (int de = -1; de <= 1; ++de)
        for (int ds = -1; ds <= 1; ++ds) {
          auto it = bins.find(grid_cell_key(bin(c->extent) + de, bin(c->short_side) + ds));
          if (it != bins.end()) same += it->second;
        }
      v.column_group = std::max(v.column_group, same);
    }
  }

  // Solid fills: their outlines are the walls (thin polygons) and columns (small squares and discs).
  v.fills = std::min(solid_fills, static_cast<int>(g.closed.size()));
  if (v.fills > 0) {
    v.fill_thick_lo = kMaxWallGap;
    for (const OutlineShape& s : g.closed) {
      if (s.column_like()) {
        ++v.fill_columns;
      } else if (s.wall_like()) {
        ++v.fill_walls;
        v.fill_thick_lo = std::min(v.fill_thick_lo, s.thickness());
        v.fill_thick_hi = std::max(v.fill_thick_hi, s.thickness());
      }
    }
  }
  return v;
}

std::string geometry_reason(const GeometryVerdict& v) {
  std::vector<std::string> parts;
  if (v.walls())
    parts.push_back(count_of(v.pairs, "parallel line pair") + " " + range_text(v.gap_lo, v.gap_hi, "m") +
                    " apart over " + fixed(v.paired_length, 1) + " m (walls drawn as two lines)");
  if (v.column_layer())
    parts.push_back(std::to_string(v.columns) + " small closed outlines " +
                    range_text(v.column_lo, v.column_hi, "m") + " across (columns)");
  if (v.solid_fill()) {
    std::string s = std::to_string(v.fills) + " solid-filled outlines:";
    if (v.fill_walls > 0)
      s += " " + std::to_string(v.fill_walls) + " wall-like " +
           range_text(v.fill_thick_lo, v.fill_thick_hi, "m") + " thick";
    if (v.fill_columns > 0)
      s += std::string(v.fill_walls > 0 ? "," : "") + " " + std::to_string(v.fill_columns) + " column-like";
    parts.push_back(s);
  }
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
  return out;
}

// Why a layer was not taken, in words.
std::string rejection_reason(const GeometryVerdict& v, const LayerGeometry& g, bool annotation) {
  if (g.segments.empty()) return g.labels > 0 ? "text only" : "no lines";
  if (v.hatch_like)
    return "lines evenly spaced with partners on both sides (" + std::to_string(v.sandwiched) + " of " +
           std::to_string(v.paired_segments) + "): a hatch pattern";
  if (annotation && v.walls())
    return std::to_string(g.labels) + " labels for " + std::to_string(v.pairs) + " line pairs: annotation";
  std::string s = count_of(v.pairs, "parallel line pair") + " 0.05-0.6 m apart";
  if (v.pairs > 0)
    s += " over " + fixed(v.paired_length, 1) + " m of " + fixed(v.total_length, 1) + " m of lines";
  if (v.columns > 0) s += ", " + std::to_string(v.columns) + " small closed outlines of varied sizes";
  return s + ": no walls or columns";
}

}  // namespace

std::vector<OccluderProposal> propose_occluder_layers(const FloorPlan& plan,
                                                      const std::map<std::string, int>& solid_fill_outlines) {
  std::vector<OccluderProposal> out;
  std::vector<int> votes;
  std::vector<std::string> name_reasons;
  bool any_name_says_wall = false;
  for (const PlanLayer& l : plan.layers) {
    std::string why;
    votes.push_back(occluder_vote_from_name(l.name, &why));
    name_reasons.push_back(why);
    any_name_says_wall |= votes.back() > 0;
  }
  std::string wall_layers;
  for (std::size_t i = 0; i < plan.layers.size(); ++i)
    if (votes[i] > 0) wall_layers += (wall_layers.empty() ? "" : ", ") + plan.layers[i].name;

  std::unordered_map<std::string, LayerGeometry> geometry;
  for (std::size_t i = 0; i < plan.segments.size(); ++i)
    geometry[plan.segments[i].layer].segments.push_back(static_cast<int>(i));
  for (const PlanOutline& o : plan.outlines)
    if (o.closed && o.points.size() >= 3) geometry[o.layer].closed.push_back(shape_of(o));
  for (const PlanLabel& l : plan.labels) ++geometry[l.layer].labels;
  auto fills_of = [&solid_fill_outlines](const std::string& layer) {
    auto it = solid_fill_outlines.find(layer);
    return it == solid_fill_outlines.end() ? 0 : it->second;
  };
  // A wall pattern layer ("A-WALL-PATT") votes no by name, but when its solid fills are wall- or
  // column-shaped they are the walls themselves (plans that draw walls only as poche).
  auto solid_walls_under_pattern = [&](std::size_t i, std::string* why) {
    const std::string& name = plan.layers[i].name;
    if (votes[i] >= 0 || fills_of(name) == 0 || !name_mentions_occluder(name)) return false;
    const GeometryVerdict v = judge_geometry(plan, geometry[name], fills_of(name));
    if (!v.solid_fill()) return false;
    GeometryVerdict fills_only;
    fills_only.fills = v.fills;
    fills_only.fill_walls = v.fill_walls;
    fills_only.fill_columns = v.fill_columns;
    fills_only.fill_thick_lo = v.fill_thick_lo;
    fills_only.fill_thick_hi = v.fill_thick_hi;
    *why = geometry_reason(fills_only) + " on a wall pattern layer (" + name_reasons[i] + ")";
    return true;
  };

  if (any_name_says_wall) {
    for (std::size_t i = 0; i < plan.layers.size(); ++i) {
      OccluderProposal p{plan.layers[i].name, votes[i] > 0, name_reasons[i]};
      if (votes[i] == 0) p.reason = "the name says nothing, and " + wall_layers + " name the walls";
      if (solid_walls_under_pattern(i, &p.reason)) p.occluder = true;
      out.push_back(p);
    }
    return out;
  }

  // No name says "wall": the geometry of each layer whose name does not rule it out.

  std::vector<GeometryVerdict> verdicts(plan.layers.size());
  double most_paired = 0.0;
  for (std::size_t i = 0; i < plan.layers.size(); ++i) {
    if (votes[i] < 0) continue;
    verdicts[i] = judge_geometry(plan, geometry[plan.layers[i].name], fills_of(plan.layers[i].name));
    if (verdicts[i].walls()) most_paired = std::max(most_paired, verdicts[i].paired_length);
  }
  bool any = false;
  for (std::size_t i = 0; i < plan.layers.size(); ++i) {
    OccluderProposal p{plan.layers[i].name, false, ""};
    const GeometryVerdict& v = verdicts[i];
    const LayerGeometry& g = geometry[p.layer];
    if (votes[i] < 0) {
      p.reason = name_reasons[i];
      p.occluder = solid_walls_under_pattern(i, &p.reason);
    } else {
      const bool annotation = g.labels > std::max(3, v.pairs);
      const bool minor_walls = v.walls() && v.paired_length < 0.1 * most_paired;
      GeometryVerdict taken = v;
      if (minor_walls || annotation) taken.pairs = 0;  // keep columns and fills, drop the pairs
      p.occluder = taken.walls() || taken.column_layer() || taken.solid_fill();
      if (p.occluder) {
        p.reason = geometry_reason(taken);
      } else if (minor_walls) {
        p.reason = fixed(v.paired_length, 1) + " m of parallel line pairs, under a tenth of the walls' " +
                   fixed(most_paired, 1) + " m elsewhere: furniture or details";
      } else {
        p.reason = rejection_reason(v, g, annotation);
      }
    }
    any |= p.occluder;
    out.push_back(p);
  }
  if (any) return out;

  // Neither names nor geometry found walls (a plan drawn with single lines): propose the layer holding most
  // of the lines, if it holds most of them, so that something blocks sight; the author confirms.
  double total = 0.0, best = 0.0;
  int best_layer = -1;
  for (std::size_t i = 0; i < plan.layers.size(); ++i) {
    if (votes[i] < 0 || verdicts[i].hatch_like) continue;
    double length = 0.0;
    for (int s : geometry[plan.layers[i].name].segments)
      length += plan.segments[static_cast<std::size_t>(s)].length();
    if (geometry[plan.layers[i].name].labels > std::max(3, verdicts[i].pairs)) length = 0.0;
    total += length;
    if (length > best) {
      best = length;
      best_layer = static_cast<int>(i);
    }
  }
  if (best_layer >= 0 && best >= 0.5 * total && best > 0.0) {
    OccluderProposal& p = out[static_cast<std::size_t>(best_layer)];
    p.occluder = true;
    p.reason = "no wall by name or geometry; this layer holds most of the lines (" + fixed(best, 1) + " of " +
               fixed(total, 1) + " m): taken as walls drawn with single lines";
  }
  return out;
}

}  // namespace plenopath
