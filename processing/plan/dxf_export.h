#pragma once
// Writes plans as ASCII DXF (AutoCAD 2000, via dxflib's writer): layers with colours, LINE, LWPOLYLINE,
// CIRCLE, ARC, TEXT, and blocks with INSERTs. Coordinates are converted from metres to the chosen units and
// $INSUNITS says which, so processing/plan/dxf_import.h reads the file back in metres.
#include <string>

#include "model/floor_plan.h"
#include "rig/plan_drawing.h"

namespace plenopath {

struct DxfExportOptions {
  std::string units = "mm";  // "mm", "cm" or "m": the file's drawing units ($INSUNITS 4, 5 or 6)
  void check() const;        // throws Error naming the bad field
};

// Throws Error naming the file when it cannot be written or the drawing refers to an unknown block.
void write_dxf(const PlanDrawing& drawing, const std::string& file, const DxfExportOptions& options = {});

// A plan as a drawing: its outlines as polylines, segments not on any outline as lines, labels as texts.
PlanDrawing drawing_from_plan(const FloorPlan& plan);

}  // namespace plenopath
