#pragma once
// The steps of register_on_plan() (registration.h), shared through this internal header: plan_raster.cpp
// (the plan's rasters), global_search.cpp (rotations x FFT correlation), icp.cpp (robust refinement and
// the final score). Not part of the public API.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "model/floor_plan.h"
#include "processing/egomotion/path_evaluation.h"
#include "processing/plan/segment_grid.h"
#include "processing/registration/registration.h"
#include "processing/util/progress.h"

namespace plenopath::registration_detail {

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

// Robust point-to-segment ICP from `start`.
Similarity2 refine_icp(const std::vector<Eigen::Vector2d>& wall_points, const PlanRaster& plan,
                       const Similarity2& start, double start_truncation_m,
                       const RegistrationOptions& options);

// The final score of a placement (registration.h).
RegistrationCandidate score_placement(const std::vector<Eigen::Vector2d>& wall_points,
                                      const std::vector<Eigen::Vector2d>& frames, const PlanRaster& plan,
                                      const SegmentGrid& grid, const Similarity2& transform,
                                      const RegistrationOptions& options);

}  // namespace plenopath::registration_detail
