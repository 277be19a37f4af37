#pragma once
// Registration of a tracked path on the floor plan (issue 19), no initial guess needed: each piece of the
// path (CameraPath::pieces) is placed on its own by the similarity (rotation, translation, scale near 1)
// that puts its triangulated wall points (EgomotionResult::tracked_points) on the plan's sight-blocking
// segments and its frames in free space.
//
//   1. Wall points: the points between floor + floor_margin_m and the ceiling - ceiling_margin_m (the
//      ceiling estimated from the points when not given), projected to the floor.
//   2. Rasters of the plan (plan_raster.cpp): the occluder segments at cell_m (distance transform with the
//      nearest segment per cell, for chamfer scores and ICP) and the free space (flood-filled wall
//      components, each classified once by the visibility index: rooms free, outside and pillars not).
//   3. Global search (global_search.cpp) on a coarse raster: every rotation_step_deg, plus the rotations
//      that put the points' dominant direction on the plan's (mod 90 deg), at scale 1;
//      for each, the translation by FFT cross-correlation of the point raster with a wall-proximity raster,
//      minus the share of the path's frames off free space; the best peaks, suppressed to distinct
//      placements.
//   3b. Local search (local_search.cpp) around each of the best few: every rotation within +-4 deg at 0.5
//      deg and shift within +-0.3 m at the fine cell, by the chamfer score of 2 000 of the points.
//   4. Refinement (icp.cpp) of the best few: robust point-to-segment ICP (Huber, then inliers only), the
//      scale with a prior at 1, from the start and from the start moved one coarse cell either way along
//      the plan's main directions (the best scoring kept); then the final score at the fine raster.
//      Candidates that end on the same placement are merged.
//
// Score of a candidate: the mean over wall points of max(0, 1 - (d / inlier_tolerance_m)^2) (d: distance to
// the nearest wall) less seen_through_weight times the share of wall points the placement says were seen
// through a wall, times the share of the piece's frames in free space. A point seen through a wall is a
// contradiction, not just a miss: it is what tells a room from its look-alike of another size. Scores of
// the candidates of one piece are comparable: two near-equal ones mean an ambiguous placement (a symmetric
// building).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/anchors.h"
#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "model/path_points.h"
#include "processing/egomotion/path_evaluation.h"
#include "processing/util/progress.h"

namespace plenopath {

struct RegistrationOptions {
  double camera_height_m = 1.6;  // the points' floor lies at z = -camera_height_m
  double floor_margin_m = 0.3;   // wall points start this far above the floor
  // Wall points end this far below the ceiling; the ceiling (above the floor) is estimated from the points
  // when ceiling_height_m is 0, and taken as camera_height_m + 1.0 when they show none.
  double ceiling_height_m = 0.0;
  double ceiling_margin_m = 0.3;
  int min_observations = 3;          // points measured by fewer keyframes are left out
  double cell_m = 0.04;              // fine raster (distance transform, free space, final scores)
  double coarse_cell_m = 0.2;        // global search raster (grown so that it stays below ~512 cells)
  double rotation_step_deg = 2.0;    // global search: every this many degrees ...
  bool dominant_directions = true;   // ... plus the rotations that align the dominant directions
  double scale_range = 0.03;         // scale searched and refined within 1 +- this
  double scale_prior_sigma = 0.01;   // ICP: Gaussian prior on the scale at 1 (relative)
  double inlier_tolerance_m = 0.10;  // a wall point this near a wall counts as on it
  double free_space_weight = 1.0;    // global search: penalty per share of frames off free space
  // Final score: what a wall point seen through a wall (its sight line from the keyframe that measured it
  // crosses a wall it is not within inlier_tolerance_m of) costs, against 1 for a point on a wall. 0 = off.
  // Without it the gap walk's first room (POV-Ray corpus) was placed turned round in the room beyond the
  // service wall, at 1.02 times the truth's score; with it, 9 % of that placement's points are seen through
  // walls and 1.3 % of the truth's.
  double seen_through_weight = 1.0;
  // ... when it lies beyond that wall by more than this share of its distance from the camera (triangulated
  // depth is that uncertain: at 0, 10 % of the gallery's points at the truth were beyond a far wall; 1 % at
  // 0.1) and by more than inlier_tolerance_m.
  double seen_through_depth_margin = 0.1;
  int refine_candidates = 8;            // distinct placements of the global search refined by ICP
  int max_candidates = 5;               // reported per piece
  double distinct_rotation_deg = 8.0;   // candidates closer than this in rotation ...
  double distinct_translation_m = 0.6;  // ... and this in position (of the points' centre) are one
  // Each start of the coarse search is first moved to the best chamfer score of an even sample of 2 000
  // wall points within +-local_search_deg (at local_search_step_deg) and +-local_search_m (at cell_m): the
  // coarse cells and rotation steps can leave a start both turned and shifted beyond ICP's reach. 0 = off.
  double local_search_deg = 4.0;
  double local_search_step_deg = 0.5;
  double local_search_m = 0.3;
  int icp_iterations = 30;
  // Each start is also refined from one coarse cell either way along the plan's two main directions; the
  // best scoring refinement is kept (a start a cell off along a corridor can settle a cell off).
  bool nudged_starts = true;
  // ICP robust loss scale. On the two-room render (second piece): 0.03 m gives 0.125 deg of rotation error,
  // 0.015 m 0.081 deg.
  double huber_m = 0.015;
  // Below this score (best candidate) no placement fits: register_on_plan reports the piece as failed.
  double min_score = 0.35;
  int min_wall_points = 30;  // fewer wall points in a piece: it cannot be registered
  // A piece longer than this that fits no placement as a whole is placed by its first this many metres
  // (points tied to those frames): drift bends a long path; the plan refinement straightens it. 0 = never.
  double window_length_m = 25.0;
  void check() const;  // throws Error naming the bad field
};

struct RegistrationCandidate {
  Similarity2 transform;       // plan = transform.apply(piece frame); headings + transform.rotation
  double score = 0.0;          // see the header comment; in [0, 1]
  double wall_share = 0.0;     // wall points within inlier_tolerance_m of a wall
  double free_share = 0.0;     // the piece's frames in free space (frames the tracker bridged left out)
  double through_share = 0.0;  // wall points seen through a wall from the keyframe that measured them
  double rms_m = 0.0;          // RMS distance of the inlier wall points to their walls
};

struct PieceRegistration {
  int piece = 0;
  int wall_points = 0;                            // points used
  double ceiling_m = 0.0;                         // ceiling height used (above the floor)
  std::vector<RegistrationCandidate> candidates;  // best first
  bool ok = false;                                // the best candidate fits (score >= min_score)
  bool by_window = false;  // placed by its first window_length_m (the whole did not fit: message says so)
  std::string message;     // why not, for the author ("no placement fits: ...")
  // Best score over second best (infinity with one candidate): near 1 means ambiguous.
  double ambiguity_ratio() const;
};

struct RegistrationResult {
  std::vector<PieceRegistration> pieces;  // one per piece of the path, in order
  double seconds = 0.0;
  bool all_ok() const;
};

// Registers each piece of `path` (in its own frame, as the tracker gives it: EgomotionResult::path) with
// the points of that piece. Throws Error when the plan has no sight-blocking segments, or the points name
// pieces the path does not have. A piece that cannot be placed is reported (ok false, message), not thrown.
// Progress: "rasters", "piece k: search", "piece k: refinement"; a cancel ends it with Cancelled.
RegistrationResult register_on_plan(const CameraPath& path, const std::vector<PathPoint>& points,
                                    const FloorPlan& plan, const RegistrationOptions& options = {},
                                    Progress& progress = null_progress());

// The path with each piece placed by its chosen candidate (choice[k], default 0 for every ok piece; -1 or
// a failed piece: left as it was): positions, headings and placed flags; and `points` (when given) moved
// alike. Throws Error on a choice out of range.
CameraPath apply_registration(const CameraPath& path, const RegistrationResult& result,
                              const std::vector<int>& choice = {}, std::vector<PathPoint>* points = nullptr);

// The candidate of `piece` that puts the anchored frames (of that piece) nearest their anchors, or -1 when
// no anchor falls on the piece. `path` is the unregistered one.
int candidate_for_anchors(const CameraPath& path, const PieceRegistration& piece, const Anchors& anchors);

// "no placement fits: best candidate has 12 % of wall points on walls" and the like, for one line of output.
std::string describe(const PieceRegistration& piece);

}  // namespace plenopath
