#include "rig/plan_drawing.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "model/error.h"

namespace plenopath {

const DrawingBlock* PlanDrawing::find_block(const std::string& name) const {
  for (const auto& b : blocks)
    if (b.name == name) return &b;
  return nullptr;
}

std::vector<Eigen::Vector2d> insert_points(const DrawingInsert& insert,
                                           const std::vector<Eigen::Vector2d>& points) {
  const double r = insert.rotation_deg * M_PI / 180.0;
  const double c = std::cos(r), s = std::sin(r);
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const auto& p : points)
    out.emplace_back(insert.position.x() + c * p.x() - s * p.y(),
                     insert.position.y() + s * p.x() + c * p.y());
  return out;
}

namespace {

class PlanBuilder {
 public:
  explicit PlanBuilder(const PlanDrawing& d) {
    for (const auto& l : d.layers) layer(l.name, l.color);
  }
  PlanLayer& layer(const std::string& name, int color = 7) {
    if (PlanLayer* l = plan.find_layer(name)) return *l;
    PlanLayer l;
    l.name = name;
    l.color = color;
    l.occluder = guess_layer_is_occluder(name);
    plan.layers.push_back(l);
    return plan.layers.back();
  }
  void segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::string& layer_name) {
    PlanSegment s;
    s.a = a;
    s.b = b;
    s.layer = layer_name;
    s.occluder = layer(layer_name).occluder;
    plan.segments.push_back(s);
  }
  void outline(const std::vector<Eigen::Vector2d>& points, bool closed, const std::string& layer_name) {
    layer(layer_name).entity_count++;
    for (std::size_t i = 0; i + 1 < points.size(); ++i) segment(points[i], points[i + 1], layer_name);
    if (closed && points.size() > 2) segment(points.back(), points.front(), layer_name);
    plan.outlines.push_back({points, layer_name, closed});
  }
  FloorPlan plan;
};

}  // namespace

FloorPlan flatten_drawing(const PlanDrawing& d, const FlattenOptions& options) {
  if (options.circle_segments < 3) throw Error("flatten_drawing: circle_segments must be >= 3");
  PlanBuilder b(d);
  for (const auto& l : d.lines) {
    b.layer(l.layer).entity_count++;
    b.segment(l.a, l.b, l.layer);
  }
  for (const auto& p : d.polylines) b.outline(p.points, p.closed, p.layer);
  for (const auto& c : d.circles) {
    std::vector<Eigen::Vector2d> pts;
    for (int i = 0; i < options.circle_segments; ++i) {
      const double t = 2.0 * M_PI * i / options.circle_segments;
      pts.emplace_back(c.centre.x() + c.radius * std::cos(t), c.centre.y() + c.radius * std::sin(t));
    }
    b.outline(pts, true, c.layer);
  }
  for (const auto& a : d.arcs) {
    double sweep = a.end_deg - a.start_deg;
    while (sweep <= 0) sweep += 360.0;
    const int n = std::max(2, static_cast<int>(std::ceil(options.circle_segments * sweep / 360.0)));
    std::vector<Eigen::Vector2d> pts;
    for (int i = 0; i <= n; ++i) {
      const double t = (a.start_deg + sweep * i / n) * M_PI / 180.0;
      pts.emplace_back(a.centre.x() + a.radius * std::cos(t), a.centre.y() + a.radius * std::sin(t));
    }
    b.outline(pts, false, a.layer);
  }
  for (const auto& ins : d.inserts) {
    const DrawingBlock* block = d.find_block(ins.block);
    if (!block) throw Error("flatten_drawing: insert of unknown block '" + ins.block + "'");
    for (const auto& p : block->polylines)
      b.outline(insert_points(ins, p.points), p.closed,
                p.layer == "0" || p.layer.empty() ? ins.layer : p.layer);
  }
  for (const auto& t : d.texts) {
    b.layer(t.layer).entity_count++;
    b.plan.labels.push_back({t.position, t.text, t.height, t.layer});
  }
  b.plan.units = "m";
  b.plan.metres_per_unit = 1.0;
  return b.plan;
}

}  // namespace plenopath
