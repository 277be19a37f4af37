#pragma once
// The floor plan as the studio uses it: line geometry in metres in the plan frame (X right, Y up).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace plenopath {

struct PlanSegment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  std::string layer;
  bool occluder = false;  // copied from the layer when the author toggles it; walls block sight
  double length() const { return (b - a).norm(); }
};
bool operator==(const PlanSegment& l, const PlanSegment& r);

// A closed or open polyline kept whole (rooms, pillars, furniture footprints). Its edges also appear in
// FloorPlan::segments, so visibility only ever looks at segments.
struct PlanOutline {
  std::vector<Eigen::Vector2d> points;
  std::string layer;
  bool closed = true;
};
bool operator==(const PlanOutline& l, const PlanOutline& r);

struct PlanLabel {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  std::string text;
  double height = 0.0;  // metres
  std::string layer;
};
bool operator==(const PlanLabel& l, const PlanLabel& r);

struct PlanLayer {
  std::string name;
  int color = 7;  // AutoCAD colour index
  bool visible = true;
  bool occluder = false;
  int entity_count = 0;
};
bool operator==(const PlanLayer& l, const PlanLayer& r);

struct PlanExtents {
  Eigen::Vector2d min = Eigen::Vector2d::Zero();
  Eigen::Vector2d max = Eigen::Vector2d::Zero();
  bool valid = false;
  Eigen::Vector2d size() const { return max - min; }
};

struct FloorPlan {
  std::string source_file;  // absolute in memory; relative to the project file on disk
  std::string units = "m";  // the source file's units, as read or overridden
  double metres_per_unit = 1.0;
  // plan = dxf * metres_per_unit - dxf_origin_m: far-from-origin (georeferenced) drawings are re-centred for
  // computation; this keeps where the plan's origin lies in the source file's frame, in metres.
  Eigen::Vector2d dxf_origin_m = Eigen::Vector2d::Zero();
  std::vector<PlanLayer> layers;
  std::vector<PlanSegment> segments;
  std::vector<PlanOutline> outlines;
  std::vector<PlanLabel> labels;

  bool empty() const { return segments.empty() && outlines.empty(); }
  PlanExtents extents() const;
  const PlanLayer* find_layer(const std::string& name) const;
  PlanLayer* find_layer(const std::string& name);
  // Sets each layer's occluder flag and copies it to the layer's segments.
  void set_layer_occluder(const std::string& layer, bool occluder);
  std::vector<PlanSegment> occluder_segments() const;
};
bool operator==(const FloorPlan& l, const FloorPlan& r);

// Default guess of which layers block sight: the name votes +1 in occluder_vote_from_name()
// (model/layer_names.h): walls, columns, structure in the usual conventions and languages, unless the name
// also says doors, windows, furniture, text, dimensions or hatch.
bool guess_layer_is_occluder(const std::string& layer_name);

}  // namespace plenopath
