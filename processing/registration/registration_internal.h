#pragma once
// The steps of register_on_plan() (registration.h), shared through this internal header: plan_raster.cpp
// (the plan's rasters), global_search.cpp (rotations x FFT correlation), icp.cpp (robust refinement and
// the final score). Not part of the public API.
#include <Eigen/Core>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "model/floor_plan.h"
#include "processing/egomotion/path_evaluation.h"
#include "processing/plan/segment_grid.h"
#include "processing/registration/registration.h"
#include "processing/util/progress.h"

namespace plenopath::registration_detail {

// v turned by `angle` radians (counter-clockwise).
inline Eigen::Vector2d rotate(const Eigen::Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// The plan at the fine cell: column = floor((x - origin.x) / cell), row = floor((y - origin.y) / cell).
struct PlanRaster {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell = 0.05;
  int cols = 0, rows = 0;
  std::vector<Segment2> walls;  // the occluder segments
  cv::Mat distance;             // CV_32F, metres to the nearest wall cell
  cv::Mat nearest;              // CV_32S, index into walls of the nearest wall cell's segment
  cv::Mat free;                 // CV_8U, 1 = free space (a room), 0 = wall, outside, pillar
  bool cell_of(const Eigen::Vector2d& p, int* col, int* row) const;  // false outside the raster
  bool is_free(const Eigen::Vector2d& p) const;
};

// The ceiling above the floor (metres): options.ceiling_height_m, or estimated from the points (the densest
// 10 cm band above the camera when it stands out), or camera height + 1 m.
double estimate_ceiling(const std::vector<const PathPoint*>& points, const RegistrationOptions& options);

// A wall point: measured by min_observations keyframes or more, between floor + floor_margin_m and
// ceiling - ceiling_margin_m (heights from the camera: the floor at -camera_height_m).
bool in_wall_band(const PathPoint& p, const RegistrationOptions& options, double ceiling_m);

// Throws Error when the plan has no occluder segments. `margin` metres of outside around the walls.
PlanRaster build_plan_raster(const FloorPlan& plan, double cell, double margin);

// The coarse rasters of the global search: an integer factor of the fine cell.
struct CoarseRaster {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell = 0.2;
  cv::Mat wall_proximity;  // CV_32F, max(0, 1 - d / radius) with d the block's nearest wall distance
  cv::Mat not_free;        // CV_32F, share of the block's fine cells off free space
};
CoarseRaster coarsen(const PlanRaster& fine, double coarse_cell, int max_cells);

// Dominant wall directions, radians in [0, pi/2): of the plan's segments (length-weighted histogram, the
// peaks above half the highest) and of a point cloud (the direction whose projections are most peaked).
std::vector<double> plan_directions(const std::vector<Segment2>& walls);
double points_direction(const std::vector<Eigen::Vector2d>& points);

struct Placement {
  Similarity2 transform;
  double score = 0.0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // where the points' centre lands
};
// Suppression: a placement within distinct_* of a better one is dropped. Sorted best first, at most `keep`.
std::vector<Placement> distinct_placements(std::vector<Placement> all, const RegistrationOptions& options,
                                           int keep);

// Global search on the coarse raster. `wall_points`, `frames`: the piece's, in its own frame.
std::vector<Placement> global_search(const std::vector<Eigen::Vector2d>& wall_points,
                                     const std::vector<Eigen::Vector2d>& frames, const CoarseRaster& coarse,
                                     const std::vector<double>& plan_dirs, const RegistrationOptions& options,
                                     Progress& progress);

// Local search (local_search.cpp): max(0, 1 - (d / tolerance_m)^2) of each fine cell's wall distance d; and
// the rotation (within +-options.local_search_deg at local_search_step_deg, about where the points' mean
// lands) and shift (within +-local_search_m at the fine cell) of `start` whose points sum most of it.
cv::Mat soft_wall_raster(const PlanRaster& plan, double tolerance_m);
Similarity2 local_search(const std::vector<Eigen::Vector2d>& points, const cv::Mat& soft,
                         const PlanRaster& plan, const Similarity2& start,
                         const RegistrationOptions& options);

// Robust point-to-segment ICP from `start`.
Similarity2 refine_icp(const std::vector<Eigen::Vector2d>& wall_points, const PlanRaster& plan,
                       const Similarity2& start, double start_truncation_m,
                       const RegistrationOptions& options);

// The final score of a placement (registration.h). `observers[i]`: where wall_points[i] was measured from
// (the piece's frame; not finite = not known, no sight-line test), empty = none known.
RegistrationCandidate score_placement(const std::vector<Eigen::Vector2d>& wall_points,
                                      const std::vector<Eigen::Vector2d>& observers,
                                      const std::vector<Eigen::Vector2d>& frames, const PlanRaster& plan,
                                      const SegmentGrid& grid, const Similarity2& transform,
                                      const RegistrationOptions& options);

// Whether the sight line from `camera` to `q` crosses a wall that q is not within `margin` of, more than
// max(margin, depth_margin * |q - camera|) before q.
bool seen_through_wall(const Eigen::Vector2d& camera, const Eigen::Vector2d& q, const SegmentGrid& grid,
                       double margin, double depth_margin);

// Plan refinement (plan_refinement.cpp, drift_fit.cpp). The wall a point `q` seen from `camera` is on: the
// first wall the ray from the camera meets on its way to q (and `within` beyond), when q lies within
// `within` of its line; a point on it and its unit normal.
bool wall_of(const Eigen::Vector2d& q, const Eigen::Vector2d& camera, const SegmentGrid& grid, double within,
             Eigen::Vector2d* on_wall, Eigen::Vector2d* normal);

// A wall point tied to a frame of the piece: its offset in that frame's axes, as placed by registration.
struct DriftTie {
  std::size_t point = 0;  // index into the caller's points
  std::size_t pose = 0;   // index into the piece's frames
  Eigen::Vector2d local = Eigen::Vector2d::Zero();
};

// The drift model of a stiff path: every step scaled by `scale` and turned by `turn - k * bias` (k: the
// step's first frame), headings likewise; the first frame shifted by `shift`. The same model as the pose
// graph's steps with their drift block (processing/anchors/pose_graph_costs.h) at zero step residual.
struct DriftModel {
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  double turn = 0.0, scale = 1.0, bias = 0.0;
};
// Poses (x, y, heading) of `start` under the model.
std::vector<Eigen::Vector3d> apply_drift_model(const std::vector<Eigen::Vector3d>& start,
                                               const DriftModel& m);

struct DriftFitOptions {
  std::vector<double> within_m = {0.5, 0.3, 0.2, 0.12};  // association distance per round
  double loss_fraction = 0.3, min_loss_m = 0.03;         // Cauchy scale: max(min, fraction * within)
  double wall_sigma_m = 0.03;
  double shift_sigma_m = 1.0, turn_sigma_rad = 0.2, scale_sigma = 0.2, bias_sigma_rad = 0.01;  // priors
  int iterations = 10;  // Gauss-Newton steps per round
};
// The model that puts `ties` (poses: indices into `start`) on the plan's walls. Progress per iteration;
// a cancel ends it with Cancelled.
DriftModel fit_drift_model(const std::vector<Eigen::Vector3d>& start, const std::vector<DriftTie>& ties,
                           const SegmentGrid& grid, const DriftFitOptions& options, Progress& progress);

}  // namespace plenopath::registration_detail
