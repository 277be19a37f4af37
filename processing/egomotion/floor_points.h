#pragma once
// The points of the floor among a bundle's points, for the refinement's floor-level prior
// (RefinementOptions::floor_sigma): a trolley or tripod carries the camera at one height over a flat floor,
// so every floor point lies at one level below the camera centres (z = 0). Tied to that level, the points
// make the scale observable along the whole walk, and the chained steps cannot shrink or grow
// (monocular scale drift).
#include <Eigen/Core>
#include <vector>

#include "processing/egomotion/path_refinement.h"

namespace plenopath {

struct FloorPointOptions {
  double min_depression_deg = 20.0;   // the point's median observation looks down at least this steeply
  int neighbour_poses = 8;            // the level it is compared with: candidates first seen this near
  double max_level_deviation = 0.08;  // ... and it lies within this share of their floor level
  void check() const;                 // throws Error naming the bad field
};

// The floor's depth below the camera among the depths of points seen steeply downwards: the deepest level
// that holds at least a third as many of them as the most crowded level (bins of 4 % of the depth,
// smoothed over their neighbours). Not the most crowded level: in a small room with desks, more points lie
// on the desk tops (seen: the scale 43 % off). 0 when `depths` is empty.
double floor_depth(const std::vector<double>& depths);

// Per point of the problem, the angle (radians) its rays span in the plan frame: the widest angle between
// the ray of its first observation and any other. A point that rides with the camera (the trolley, the
// operator) spans almost none on a straight walk, whatever depth the bundle gave it. 0 for a point observed
// once or never.
std::vector<float> point_parallax(const BundleProblem& problem);

// The metric scale (metres per unit) from the camera's height over the floor: the floor is the level
// (floor_depth) of the points first seen more than 25 deg down whose rays span at least 3 deg (a floor
// point near the camera spans that within a few steps). Without that parallax, the rig's points crowd far
// below the floor (on the POV-Ray corridor at 26 cm steps: the scale 14x too small). 0 when fewer than 20
// points qualify; *floor_points (if given) counts those within 4 % of the level.
double scale_from_camera_height(const BundleProblem& problem, double camera_height_m, int* floor_points);

// Indices of problem.points judged to be on the floor. Scale-free: the depression is read from the bearings,
// and each candidate is compared with the level of candidates first seen near it (so a path whose scale has
// drifted is classified as well as one that has not). Tables, benches and reflections in a glossy floor
// are mostly left out; the prior's robust loss takes care of the rest.
std::vector<int> find_floor_points(const BundleProblem& problem, const FloorPointOptions& options = {});

// A step between two keyframes measured on the floor (the chaining's, piece_solver.cpp), with no point
// triangulated before: the camera rides at `level` above a flat floor, so a floor point seen at a depression
// e lies level / tan(e) away from either keyframe, and each track seen at least `min_depression` (radians)
// down from both gives the step's length along `direction` (unit, plan). Bearings are in each camera's frame
// (level cameras with the given headings, radians). Tracks whose bearing moves less than `min_motion`
// (radians) in the camera's frame stay with the camera (the trolley, the operator): they are skipped.
struct FloorStep {
  double length = 0.0;  // the median of the tracks' lengths (0: none)
  int points = 0;       // tracks that measured it
  double spread = 0.0;  // their median absolute deviation from it, a share of it (infinity when length <= 0)
};
struct FloorStepInput {
  const std::vector<Eigen::Vector3d>* bearings_a = nullptr;  // camera frame of keyframe a, unit
  const std::vector<Eigen::Vector3d>* bearings_b = nullptr;  // the same tracks from b
  double heading_a = 0.0, heading_b = 0.0;
  double level = 0.0;  // the floor's depth below the camera centres
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
};
FloorStep floor_step(const FloorStepInput& input, double min_depression, double min_motion);

}  // namespace plenopath
