#pragma once
// Plan-aware refinement (issue 19): after registration, the walls of the plan correct the path's drift
// without anchors, for each placed piece:
//   - walls: each wall point (PathPoint with a frame, in the registration's height band) moves rigidly with
//     the pose of the frame it is tied to (its offset scaled by the drift scale) and is pulled onto the first
//     wall the ray from that frame meets (projective association: what the camera saw there; the nearest
//     wall would let desks and door frames pull), point-to-line residual with a Cauchy loss, when it lies
//     within the round's association distance of that wall;
//   - stiff rounds (drift_fit.cpp): the path keeps its tracked shape but for the drift model {scale, turn
//     bias per step} and its placement, five unknowns fitted by Gauss-Newton while the association distance
//     shrinks (0.5 to 0.1 m by default), so a drift of a few decimetres is taken in at once;
//   - flexible rounds: a pose graph (Ceres) whose steps keep every step's tracked motion with the drift
//     block, as in the anchor refinement (processing/anchors/pose_graph_costs.h), so single stretches may
//     bend; a weak prior on the first frame's pose holds what the walls do not fix (a corridor's length).
// Safeguard: the refined piece is kept only when its wall fit (the share of wall points within
// inlier_tolerance_m of a wall) does not get worse and its frames stay in free space; otherwise the piece
// stays as registered and the report says why. Anchors are not used here: the anchor refinement that runs
// after it has the last word where the author placed anchors.
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "model/path_points.h"
#include "processing/registration/registration.h"
#include "processing/util/progress.h"

namespace plenopath {

struct PlanRefinementOptions {
  RegistrationOptions registration;  // the wall band (camera height, margins), raster cell, inlier tolerance
  double association_start_m = 0.5;  // first round: a point this near a wall is tied to it ...
  double association_end_m = 0.1;    // ... shrinking to this
  double wall_sigma_m = 0.03;        // std. dev. of a wall point off its wall (triangulation noise)
  // Robust loss of the wall residual (Cauchy): its scale is loss_fraction times the round's association
  // distance, but at least wall_loss_m.
  double wall_loss_m = 0.03;
  double loss_fraction = 0.3;
  int max_wall_points = 8000;  // evenly subsampled beyond this many per piece (speed)
  // The flexible rounds' step sigmas: a tracker's steps are good to about 1 % (measured on the renders:
  // 5 % let the no-drift walks bend by 5 mm under 1 % depth noise, 1 % by 2 mm).
  double step_sigma_fraction = 0.01;     // std. dev. of a step's tracked translation, fraction of its length
  double step_sigma_min_m = 0.001;       // ... but at least this
  double turn_sigma_rad = 0.001;         // std. dev. of a step's tracked heading change
  double drift_scale_sigma = 0.2;        // prior on the piece's scale error (1 = none)
  double drift_bias_sigma_rad = 0.01;    // prior on the heading bias per step
  double start_sigma_m = 1.0;            // weak prior on the first frame's registered position ...
  double start_heading_sigma_rad = 0.2;  // ... and heading
  // Rounds: stiff_rounds hold the path's shape (only the drift model and the placement move) while the
  // association distance shrinks from association_start_m to association_end_m; then flexible_rounds at
  // association_end_m let every step bend by its own sigmas.
  int stiff_rounds = 4;
  int flexible_rounds = 2;
  int max_iterations = 30;  // per round
  // Safeguard: the refined piece is dropped when its share of frames in free space falls by more than this.
  double max_free_share_loss = 0.02;
  // ... and not kept unless this share of the wall points ends on walls (a path that does not fit the plan
  // is not made to by bending it).
  double min_wall_share = 0.5;
  void check() const;  // throws Error naming the bad field
};

struct PieceRefinement {
  int piece = 0;
  bool refined = false;  // the refinement ran on this piece
  bool kept = false;     // ... and its result was kept (the safeguard passed)
  int wall_points = 0;   // points tied to walls in the last round
  double wall_share_before = 0.0, wall_share_after = 0.0;  // band points within inlier_tolerance_m
  double rms_before_m = 0.0, rms_after_m = 0.0;            // RMS distance of those inliers to their walls
  double free_share_before = 0.0, free_share_after = 0.0;
  double drift_scale = 1.0;                    // the piece's scale correction (refined over tracked)
  double drift_bias_deg_per_100_frames = 0.0;  // the heading bias it took out
  double max_shift_m = 0.0;                    // the largest move of a frame
  int iterations = 0;
  std::string message;  // why not refined or not kept; empty when kept
};

struct PlanRefinementReport {
  std::vector<PieceRefinement> pieces;  // one per piece of the path
  double seconds = 0.0;
  bool any_kept() const;
};

// Refines each placed piece of `path` (in plan coordinates, as apply_registration leaves it) with
// `points` (moved alike) on `plan`'s sight-blocking segments. Returns the path; `points`, when given, are
// moved with their frames (each with its frame's pose), so that they stay consistent with the path. Pieces
// not placed, without enough wall points tied to frames, or failing the safeguard stay as they were.
// Throws Error when the plan has no sight-blocking segments or a point names a piece the path lacks.
// Progress: "piece k: round r"; a cancel ends it with Cancelled, path and points untouched.
CameraPath refine_on_plan(const CameraPath& path, std::vector<PathPoint>* points, const FloorPlan& plan,
                          const PlanRefinementOptions& options = {}, PlanRefinementReport* report = nullptr,
                          Progress& progress = null_progress());

// One line per piece for the console: "piece 1: refined on the walls: 94 % -> 99 % of wall points on walls,
// scale x1.048, bias 1.9 deg / 100 frames, largest move 0.41 m" or why not.
std::string describe(const PieceRefinement& piece);

}  // namespace plenopath
