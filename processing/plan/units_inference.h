#pragma once
// The units a drawing must be in, judged from what it shows: door swings (arcs of about a quarter turn) are
// 0.6-1.1 m in radius, walls are 0.05-0.6 m thick (close parallel line pairs), a floor is 3-500 m across.
// Used when $INSUNITS is 0 or absent, and to catch a header that contradicts the drawing.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace plenopath {

struct DrawingSegment {  // drawing units
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
};
struct DrawingArc {  // drawing units; sweep counter-clockwise, radians, in (0, 2 pi]
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double sweep = 0.0;
};

struct UnitsEvidence {
  std::vector<double> door_swing_radii;  // drawing units
  std::vector<double> wall_gaps;         // drawing units, between close parallel line pairs
  double drawing_size = 0.0;             // drawing units, the larger side of the drawing's bulk
};

// Near-linear in the number of segments (a grid, not all pairs).
UnitsEvidence collect_units_evidence(const std::vector<DrawingSegment>& segments,
                                     const std::vector<DrawingArc>& arcs);

struct UnitsInference {
  std::string units;        // "mm", "cm", "m", "in", "ft"; "" when the evidence says nothing
  double confidence = 0.0;  // 0..1
  std::string reason;       // one sentence for the import report ("12 door swings of median radius 900
                            // units: millimetres")
};

UnitsInference infer_units(const UnitsEvidence& evidence);

// Whether the drawing looks right in `units`; `why` gets the contradiction when it does not ("door swings
// of median radius 36 in would be 0.91 m: ok" / "doors 0.9 units wide would be 2.3 cm in inches").
bool units_plausible(const std::string& units, const UnitsEvidence& evidence, std::string* why = nullptr);

}  // namespace plenopath
