// The office sample: 25 m x 15 m, seven rooms off a corridor, doorways with swing arcs, square and round
// pillars, furniture as blocks, room labels. Authored as CAD primitives (rig/plan_drawing.h).
#include <cmath>
#include <utility>

#include "rig/plan_drawing.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

using V = Eigen::Vector2d;

DrawingPolyline rectangle(double x0, double y0, double x1, double y1, const std::string& layer) {
  return {{V(x0, y0), V(x1, y0), V(x1, y1), V(x0, y1)}, true, layer};
}

// A wall along x at height y from x0 to x1, with gaps [g0, g1) sorted by g0.
void horizontal_wall(PlanDrawing& d, double y, double x0, double x1,
                     const std::vector<std::pair<double, double>>& gaps) {
  double x = x0;
  for (const auto& g : gaps) {
    d.lines.push_back({V(x, y), V(g.first, y), "WALLS"});
    x = g.second;
  }
  d.lines.push_back({V(x, y), V(x1, y), "WALLS"});
}
void vertical_wall(PlanDrawing& d, double x, double y0, double y1,
                   const std::vector<std::pair<double, double>>& gaps) {
  double y = y0;
  for (const auto& g : gaps) {
    d.lines.push_back({V(x, y), V(x, g.first), "WALLS"});
    y = g.second;
  }
  d.lines.push_back({V(x, y), V(x, y1), "WALLS"});
}

// A door hinged at `hinge`, its leaf drawn open along `open_deg` and its swing arc from the closed position.
void door(PlanDrawing& d, const V& hinge, double width, double closed_deg, double open_deg) {
  const double r = open_deg * M_PI / 180.0;
  d.lines.push_back({hinge, hinge + width * V(std::cos(r), std::sin(r)), "DOORS"});
  // The arc runs counter-clockwise between the two leaf positions.
  double start = closed_deg, end = open_deg;
  if (std::remainder(open_deg - closed_deg, 360.0) < 0) std::swap(start, end);
  d.arcs.push_back({hinge, width, start, end, "DOORS"});
}

void furniture(PlanDrawing& d, const std::string& block, double x, double y, double rotation_deg = 0.0) {
  d.inserts.push_back({block, V(x, y), rotation_deg, "FURNITURE"});
}

}  // namespace

PlanDrawing make_office_sample_drawing() {
  PlanDrawing d;
  d.layers = {{"WALLS", 7}, {"COLUMNS", 8}, {"DOORS", 3}, {"FURNITURE", 5}, {"TEXT", 2}};

  // Exterior: a 25 cm thick wall drawn as two closed outlines.
  d.polylines.push_back(rectangle(-0.25, -0.25, 25.25, 15.25, "WALLS"));
  d.polylines.push_back(rectangle(0.0, 0.0, 25.0, 15.0, "WALLS"));
  // The corridor (y 6.5 .. 8.5) and its doorways.
  horizontal_wall(d, 8.5, 0.0, 25.0, {{3.0, 4.8}, {10.5, 11.4}, {16.2, 17.1}, {21.5, 22.4}});
  horizontal_wall(d, 6.5, 0.0, 25.0, {{4.0, 4.9}, {11.0, 14.0}, {19.5, 20.4}});
  // Room dividers: north side (Open Office | Meeting Room | Kitchen | Director), south (Lab | Lobby |
  // Library).
  vertical_wall(d, 8.0, 8.5, 15.0, {});
  vertical_wall(d, 14.0, 8.5, 15.0, {{12.0, 12.9}});
  vertical_wall(d, 19.5, 8.5, 15.0, {});
  vertical_wall(d, 9.0, 0.0, 6.5, {});
  vertical_wall(d, 16.0, 0.0, 6.5, {});

  // Doors: leaves open into the rooms.
  door(d, V(10.5, 8.5), 0.9, 0.0, 90.0);
  door(d, V(16.2, 8.5), 0.9, 0.0, 90.0);
  door(d, V(21.5, 8.5), 0.9, 0.0, 90.0);
  door(d, V(4.0, 6.5), 0.9, 0.0, -90.0);
  door(d, V(19.5, 6.5), 0.9, 0.0, -90.0);
  door(d, V(14.0, 12.0), 0.9, 90.0, 0.0);

  // Pillars: square ones as closed outlines, round ones as circles.
  d.polylines.push_back(rectangle(3.8, 11.55, 4.2, 11.95, "COLUMNS"));
  d.polylines.push_back(rectangle(20.3, 3.05, 20.7, 3.45, "COLUMNS"));
  d.circles.push_back({V(11.0, 3.25), 0.25, "COLUMNS"});
  d.circles.push_back({V(14.0, 3.25), 0.25, "COLUMNS"});

  // Furniture blocks (base point at the centre; entities on layer 0 take the insert's layer).
  auto block = [&d](const std::string& name, double w, double h) {
    d.blocks.push_back({name, {rectangle(-w / 2, -h / 2, w / 2, h / 2, "0")}});
  };
  block("DESK", 1.6, 0.8);
  block("TABLE", 2.4, 1.2);
  block("CABINET", 0.5, 2.0);
  block("COUNTER", 3.0, 0.6);
  block("SHELF", 2.0, 0.4);
  furniture(d, "DESK", 1.3, 10.5, 90);  // Open Office
  furniture(d, "DESK", 6.7, 10.5, 90);
  furniture(d, "DESK", 2.2, 14.2);
  furniture(d, "DESK", 5.8, 14.2);
  furniture(d, "TABLE", 11.0, 12.5);     // Meeting Room
  furniture(d, "COUNTER", 16.75, 14.6);  // Kitchen
  furniture(d, "DESK", 17.0, 11.5);
  furniture(d, "DESK", 22.5, 13.0);  // Director
  furniture(d, "CABINET", 24.6, 11.0);
  furniture(d, "TABLE", 2.5, 2.5);  // Lab
  furniture(d, "TABLE", 6.5, 2.5);
  furniture(d, "DESK", 12.5, 1.0);       // Lobby
  furniture(d, "TABLE", 18.0, 3.0, 90);  // Library
  furniture(d, "SHELF", 22.5, 3.0, 90);
  furniture(d, "SHELF", 24.0, 3.0, 90);

  const std::pair<const char*, V> rooms[] = {{"Open Office", V(4.0, 12.8)}, {"Meeting Room", V(11.0, 10.0)},
                                             {"Kitchen", V(16.75, 10.0)},   {"Director", V(22.25, 10.0)},
                                             {"Lab", V(4.5, 5.0)},          {"Lobby", V(12.5, 5.0)},
                                             {"Library", V(20.5, 5.0)},     {"Corridor", V(12.5, 7.5)}};
  for (const auto& r : rooms) d.texts.push_back({r.second, 0.35, r.first, "TEXT"});
  return d;
}

FloorPlan make_office_sample_plan() {
  FloorPlan plan = flatten_drawing(make_office_sample_drawing());
  plan.source_file = "office-sample (built in code)";
  return plan;
}

}  // namespace plenopath
