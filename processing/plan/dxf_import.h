#pragma once
// DXF floor plans (ASCII DXF, read with dxflib) to a FloorPlan in metres.
//
// Entities: LINE, LWPOLYLINE and old-style POLYLINE (bulges become arcs), ARC, CIRCLE, ELLIPSE, SPLINE
// (tessellated to a chord tolerance), INSERT (nested blocks, negative/mirrored scale, rotation, column/row
// arrays, layer-0 inheritance), TEXT/MTEXT as labels. Entities with extrusion (0,0,-1) are mirrored back.
// Units: $INSUNITS (or the override) to metres. Clean-up of the segments: snap endpoints, drop zero-length
// and duplicate segments, merge collinear overlaps, split at intersections.
#include <string>
#include <vector>

#include "model/floor_plan.h"

namespace plenopath {

struct DxfImportOptions {
  // Units of the file's coordinates: "mm", "cm", "m", "in", "ft", "yd", "km", "mi", "dm", "um".
  // Empty = use the header's $INSUNITS (unitless or missing = metres, with a warning).
  std::string units_override;
  // Layers whose segments block sight. Empty = guess each layer with guess_layer_is_occluder().
  std::vector<std::string> occluder_layers;
  // Layers to import at all. Empty = all layers.
  std::vector<std::string> layers;
  // Endpoints closer than this (metres) are merged into one vertex; also the grid of the final snap.
  double snap_tolerance_m = 0.001;
  // Largest distance (metres) between an arc/ellipse/spline and the chords that replace it.
  double chord_tolerance_m = 0.005;
  // Thickness (metres) given to single-line walls when visibility needs a closed obstacle (see
  // processing/visibility.h); kept here so one options struct describes how a plan was read.
  double single_line_wall_thickness_m = 0.01;
  // Coordinates (after unit conversion) beyond this magnitude (metres) are rejected as absurd.
  double max_coordinate_m = 1.0e6;
  // Upper bound on segments after tessellation and block expansion (protects against block bombs).
  std::size_t max_segments = 2000000;

  // Throws plenopath::Error saying which field is wrong.
  void check() const;
};

struct DxfImportReport {
  std::string units;              // units used ("mm", ...), after the override
  bool units_from_header = false; // $INSUNITS was present and known
  int entities_read = 0;          // entities in the model space (INSERTs count once)
  int entities_skipped = 0;       // unsupported entity kinds (HATCH, DIMENSION, ...) or filtered layers
  int blocks_expanded = 0;        // block references expanded (all nesting levels, all array cells)
  int arcs_tessellated = 0;       // arcs, circles, ellipses, splines and bulges turned into chords
  int snapped_endpoints = 0;      // endpoints moved onto a neighbour within the snap tolerance
  int zero_length_dropped = 0;
  int duplicates_dropped = 0;
  int collinear_merged = 0;       // overlapping collinear segments merged
  int intersections_split = 0;    // segments split where they cross or touch another
  std::vector<std::string> warnings;
};

// Reads `file`. Geometry in metres in the plan frame. Throws plenopath::Error naming the file (and the line
// or group code when known) for unreadable, binary, truncated or malformed files, files without usable
// geometry and absurd coordinates.
FloorPlan import_dxf(const std::string& file, const DxfImportOptions& options = {},
                     DxfImportReport* report = nullptr);

// Same, from the file's bytes in memory (the fuzz target uses this); `name` names the source in errors.
FloorPlan import_dxf_from_memory(const std::string& bytes, const std::string& name,
                                 const DxfImportOptions& options = {}, DxfImportReport* report = nullptr);

// Metres per unit for a unit name ("mm", "cm", "m", "in", "ft", ...); throws plenopath::Error if unknown.
double metres_per_unit(const std::string& units);
// Unit name for a DXF $INSUNITS code, or "" for unitless/unknown codes.
std::string units_of_insunits(int insunits);

}  // namespace plenopath
