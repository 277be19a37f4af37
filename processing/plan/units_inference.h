#pragma once
// The units a drawing must be in, judged from what it shows: door swings (arcs of about a quarter turn) are
// 0.6-1.1 m in radius, walls are 0.05-0.6 m thick (close parallel line pairs), a floor is 3-500 m across.
// Used when $INSUNITS is 0 or absent, and to catch a header that contradicts the drawing.
//
// Inputs: segments and arcs in drawing units, world coordinates (blocks expanded), strays included (the
// size is taken from the bulk). An arc's start_angle lets a door swing be confirmed by its leaf (a line
// from the centre to one end of the arc); leave it NaN when unknown, and then give the arc's true centre
// anyway (the radius alone counts then). Non-finite values are ignored.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace plenopath {
// rig/plan_drawing.h has its own DrawingArc (CAD primitives in metres): this namespace keeps the two apart
// at link time (no ODR clash); one translation unit cannot include both headers and use the bare names.
inline namespace units_evidence {

struct DrawingSegment {  // drawing units
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
};
struct DrawingArc {  // drawing units; sweep counter-clockwise, radians, in (0, 2 pi]
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double sweep = 0.0;
  // Where the sweep begins, radians counter-clockwise from +X; NaN = unknown (no leaf check).
  double start_angle = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace units_evidence

struct UnitsEvidence {
  // Radii of arcs sweeping 75-105 degrees, drawing units. When at least two of them (or a quarter of them)
  // are confirmed by a leaf line, only the confirmed ones.
  std::vector<double> door_swing_radii;
  int door_leaves = 0;            // door swings confirmed by a leaf line from the centre to an arc end
  std::vector<double> wall_gaps;  // drawing units, between close parallel line pairs
  double drawing_size = 0.0;      // drawing units, the larger side of the drawing's bulk (2nd-98th
                                  // percentile of endpoints)
};

// Near-linear in the number of segments (a grid, not all pairs).
UnitsEvidence collect_units_evidence(const std::vector<DrawingSegment>& segments,
                                     const std::vector<DrawingArc>& arcs);

struct UnitsInference {
  std::string units;        // "mm", "cm", "m", "in", "ft"; "" when the evidence says nothing
  double confidence = 0.0;  // 0..1; below 0.3 the guess rests on weak evidence (the size alone, a near tie)
  std::string reason;       // one sentence for the import report ("12 door swings of median radius 900
                            // units: millimetres")
};

UnitsInference infer_units(const UnitsEvidence& evidence);

// Whether the drawing looks right in `units` (any name metres_per_unit() knows: mm, cm, dm, m, km, um, in,
// ft, yd, mi); `why` gets the contradiction when it does not ("door swings
// of median radius 36 in would be 0.91 m: ok" / "doors 0.9 units wide would be 2.3 cm in inches").
bool units_plausible(const std::string& units, const UnitsEvidence& evidence, std::string* why = nullptr);

}  // namespace plenopath
