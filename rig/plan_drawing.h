#pragma once
// A floor plan as CAD primitives (lines, polylines, circles, arcs, texts, blocks and their inserts), in
// metres. The sample plan is authored this way so that one description yields both the DXF file the project
// ships (processing/plan/dxf_export.h) and the FloorPlan tests use without the DXF importer
// (flatten_drawing).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/floor_plan.h"

namespace plenopath {

struct DrawingLayer {
  std::string name;
  int color = 7;  // AutoCAD colour index
};
struct DrawingLine {
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  std::string layer;
};
struct DrawingPolyline {
  std::vector<Eigen::Vector2d> points;
  bool closed = false;
  std::string layer;  // "0" inside a block = take the insert's layer
};
struct DrawingCircle {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
  std::string layer;
};
struct DrawingArc {  // counter-clockwise from start to end
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double start_deg = 0.0, end_deg = 90.0;
  std::string layer;
};
struct DrawingText {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // centre of the text
  double height = 0.3;
  std::string text;
  std::string layer;
};
struct DrawingBlock {  // geometry relative to the block's base point (0, 0)
  std::string name;
  std::vector<DrawingPolyline> polylines;
};
struct DrawingInsert {
  std::string block;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double rotation_deg = 0.0;
  std::string layer;
};

struct PlanDrawing {
  std::vector<DrawingLayer> layers;
  std::vector<DrawingLine> lines;
  std::vector<DrawingPolyline> polylines;
  std::vector<DrawingCircle> circles;
  std::vector<DrawingArc> arcs;
  std::vector<DrawingText> texts;
  std::vector<DrawingBlock> blocks;
  std::vector<DrawingInsert> inserts;

  const DrawingBlock* find_block(const std::string& name) const;
};

struct FlattenOptions {
  int circle_segments = 32;  // chords per full circle (arcs get a proportional share, at least 2)
};

// The drawing as the studio sees a plan: lines and polyline edges become segments, polylines, circles,
// arcs and expanded inserts become outlines (circles closed, arcs open), texts become labels; a layer's
// occluder flag is guessed from its name (guess_layer_is_occluder). Throws Error for an unknown block.
FloorPlan flatten_drawing(const PlanDrawing& drawing, const FlattenOptions& options = {});

// The points of an insert's polyline in plan coordinates.
std::vector<Eigen::Vector2d> insert_points(const DrawingInsert& insert,
                                           const std::vector<Eigen::Vector2d>& points);

// The office sample as CAD primitives (metres). Layers WALLS, COLUMNS, DOORS, FURNITURE, TEXT.
PlanDrawing make_office_sample_drawing();

}  // namespace plenopath
