#include "model/floor_plan.h"

#include <algorithm>
#include <tuple>

#include "model/layer_names.h"

namespace plenopath {

bool operator==(const PlanSegment& l, const PlanSegment& r) {
  return std::tie(l.a, l.b, l.layer, l.occluder) == std::tie(r.a, r.b, r.layer, r.occluder);
}
bool operator==(const PlanOutline& l, const PlanOutline& r) {
  return std::tie(l.points, l.layer, l.closed) == std::tie(r.points, r.layer, r.closed);
}
bool operator==(const PlanLabel& l, const PlanLabel& r) {
  return std::tie(l.position, l.text, l.height, l.layer) == std::tie(r.position, r.text, r.height, r.layer);
}
bool operator==(const PlanLayer& l, const PlanLayer& r) {
  return std::tie(l.name, l.color, l.visible, l.occluder, l.entity_count) ==
         std::tie(r.name, r.color, r.visible, r.occluder, r.entity_count);
}
bool operator==(const FloorPlan& l, const FloorPlan& r) {
  return std::tie(l.source_file, l.units, l.metres_per_unit, l.dxf_origin_m, l.layers, l.segments, l.outlines,
                  l.labels) == std::tie(r.source_file, r.units, r.metres_per_unit, r.dxf_origin_m, r.layers,
                                        r.segments, r.outlines, r.labels);
}

PlanExtents FloorPlan::extents() const {
  PlanExtents e;
  auto add = [&e](const Eigen::Vector2d& p) {
    if (!e.valid) {
      e.min = e.max = p;
      e.valid = true;
    } else {
      e.min = e.min.cwiseMin(p);
      e.max = e.max.cwiseMax(p);
    }
  };
  for (const auto& s : segments) {
    add(s.a);
    add(s.b);
  }
  for (const auto& o : outlines)
    for (const auto& p : o.points) add(p);
  return e;
}

const PlanLayer* FloorPlan::find_layer(const std::string& name) const {
  auto it = std::find_if(layers.begin(), layers.end(), [&](const PlanLayer& l) { return l.name == name; });
  return it == layers.end() ? nullptr : &*it;
}

PlanLayer* FloorPlan::find_layer(const std::string& name) {
  auto it = std::find_if(layers.begin(), layers.end(), [&](const PlanLayer& l) { return l.name == name; });
  return it == layers.end() ? nullptr : &*it;
}

void FloorPlan::set_layer_occluder(const std::string& layer, bool occluder) {
  if (PlanLayer* l = find_layer(layer)) l->occluder = occluder;
  for (auto& s : segments)
    if (s.layer == layer) s.occluder = occluder;
}

std::vector<PlanSegment> FloorPlan::occluder_segments() const {
  std::vector<PlanSegment> out;
  std::copy_if(segments.begin(), segments.end(), std::back_inserter(out),
               [](const PlanSegment& s) { return s.occluder; });
  return out;
}

bool guess_layer_is_occluder(const std::string& layer_name) {
  return occluder_vote_from_name(layer_name) > 0;
}

}  // namespace plenopath
