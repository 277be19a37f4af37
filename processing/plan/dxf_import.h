#pragma once
// DXF floor plans to a FloorPlan in metres, as CAD programs really write them: R12 to R2018, ASCII or
// binary (processing/plan/dxf_tags.h), any code page (processing/plan/dxf_text.h).
//
// Entities: LINE, LWPOLYLINE and old-style POLYLINE (bulges become arcs), ARC, CIRCLE, ELLIPSE, SPLINE
// (tessellated to a chord tolerance), INSERT (nested blocks, negative/mirrored scale, rotation, column/row
// arrays, layer-0 inheritance; attributes ignored), HATCH and SOLID/TRACE (their boundaries become closed
// outlines: solid-filled walls and columns), MLINE (one polyline per element), TEXT/MTEXT as labels. Every
// entity's object coordinate system (extrusion) is mapped to the world and flattened onto the XY plane.
// Skipped and counted: 3-D-only entities, DIMENSION, paper space, viewports, images and anything unknown.
//
// Validation is per entity: a bad entity is skipped and reported with its line and why, never the whole
// file. Header and OBJECTS values never stop an import. The file is refused only when nothing in it can be
// read as a drawing (not DXF at all, or no geometry).
//
// Units: the override, else $INSUNITS when the drawing agrees with it, else inferred from the drawing
// (processing/plan/units_inference.h); the report says which and why. Far-from-origin drawings are
// re-centred (FloorPlan::dxf_origin_m keeps the offset); entities far from the drawing's bulk are reported
// as stray and left out of the plan unless asked for. Clean-up of the segments: snap endpoints, drop
// zero-length and duplicate segments, merge collinear overlaps, split at intersections.
#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "model/floor_plan.h"

namespace plenopath {

struct DxfImportOptions {
  // Units of the file's coordinates: "mm", "cm", "m", "in", "ft", "yd", "km", "mi", "dm", "um".
  // Empty = $INSUNITS when the drawing agrees with it, otherwise inferred from the drawing.
  std::string units_override;
  // Layers whose segments block sight. Empty = the proposal of propose_occluder_layers().
  std::vector<std::string> occluder_layers;
  // Layers to import at all. Empty = all layers.
  std::vector<std::string> layers;
  // Endpoints closer than this (metres) are merged into one vertex; also the grid of the final snap.
  double snap_tolerance_m = 0.001;
  // Largest distance (metres) between an arc/ellipse/spline and the chords that replace it.
  double chord_tolerance_m = 0.005;
  // Thickness (metres) given to single-line walls when visibility needs a closed obstacle (see
  // processing/visibility/visibility.h); kept here so one options struct describes how a plan was read.
  double single_line_wall_thickness_m = 0.01;
  // Re-centre the plan when the drawing's bulk lies further than this (metres) from the DXF origin.
  double recentre_beyond_m = 10000.0;
  // Keep entities that lie far from the drawing's bulk (title blocks, stray points at 1e20). Off = they
  // are reported as stray and left out, so the plan's extents are the building's.
  bool keep_stray = false;
  // Upper bound on segments after tessellation and block expansion (protects against block bombs).
  std::size_t max_segments = 2000000;

  // Throws plenopath::Error saying which field is wrong.
  void check() const;
};

// One entity the importer left out, and why.
struct DxfSkippedEntity {
  std::size_t line = 0;  // line of its "0" tag in an ASCII file; byte offset in a binary one
  std::string kind;      // "CIRCLE", "DIMENSION", ...
  std::string layer;
  std::string why;  // "radius 0", "paper space", "3-D only", "far from the drawing (stray)", ...
};

struct DxfImportReport {
  std::string version;             // $ACADVER ("AC1009" = R12, "AC1032" = R2018), "" when the header has none
  bool binary = false;             // binary DXF
  std::string codepage;            // $DWGCODEPAGE as written ("ANSI_1252"), "" when absent
  std::string units;               // units used ("mm", ...)
  std::string units_source;        // "override", "header", "inferred" or "assumed"
  std::string units_reason;        // one sentence: why these units (inference evidence, header contradiction)
  bool units_from_header = false;  // the header's $INSUNITS was used
  int entities_read = 0;           // model-space entities turned into geometry or labels (INSERTs count once)
  int entities_skipped = 0;        // model-space entities left out (unsupported, invalid, filtered, stray)
  std::map<std::string, int> skipped_by_kind;  // kind -> count, all reasons together
  std::vector<DxfSkippedEntity> skipped;       // the first max_listed_skips, with line and reason
  static constexpr std::size_t max_listed_skips = 500;
  // Model-space entities read, per layer and kind (an INSERT counts once, on the INSERT's layer).
  std::map<std::string, std::map<std::string, int>> entities_by_layer;
  // Bounding box of the imported geometry in drawing units, before unit conversion and re-centring
  // (what another DXF reader reports for the same entities).
  PlanExtents drawing_extents;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // = FloorPlan::dxf_origin_m
  int stray_entities = 0;     // left out (or kept, with keep_stray) as far from the drawing's bulk
  int blocks_expanded = 0;    // block references expanded (all nesting levels, all array cells)
  int arcs_tessellated = 0;   // arcs, circles, ellipses, splines and bulges turned into chords
  int hatch_outlines = 0;     // closed boundaries taken from HATCH, SOLID and TRACE
  int snapped_endpoints = 0;  // endpoints moved onto a neighbour within the snap tolerance
  int zero_length_dropped = 0;
  int duplicates_dropped = 0;
  int collinear_merged = 0;                             // overlapping collinear segments merged
  int intersections_split = 0;                          // segments split where they cross or touch another
  std::map<std::string, std::string> occluder_reasons;  // layer -> why it was proposed as blocking sight
  std::vector<std::string> warnings;
};

// Reads `file`. Geometry in metres in the plan frame. Throws plenopath::Error naming the file (and the line
// when known) only when nothing in it can be read as a drawing: not a DXF file, no geometry at all.
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
