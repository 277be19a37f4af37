#pragma once
// A still panorama placed on the plan from one click of the author (issue 20): for a still that matched
// no other still (a textureless room, a shot through a door), the author clicks roughly where the tripod
// stood, and the pose is found by making the plan's walls, as seen from there, line up with the still:
//   - the floor-wall boundary: a wall at distance d along an azimuth meets the floor at elevation
//     -atan(camera height / d) in the still;
//   - the vertical edges: a corner or a door jamb of the plan seen from the spot is a vertical line in the
//     still at the corner's azimuth.
// Both are drawn into the still's edge map (Canny) as curves, and the score of a pose is the mean distance
// of the curves' pixels to the nearest edge running the same way (oriented chamfer matching), truncated
// (furniture hiding a wall costs at most the truncation). All headings and the positions within
// search_radius_m of the click are tried on a coarse grid, the best few refined on a fine one; the heading
// for every position is a shift of the plan's profile, so one ray cast per position serves all headings.
//
// A second click may give the direction the still's centre looks (heading_hint_deg): for a room whose
// walls look alike both ways round.
#include <Eigen/Core>
#include <limits>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "model/path_points.h"
#include "processing/util/progress.h"

namespace plenopath {

struct StillOnPlanOptions {
  double camera_height_m = 1.6;       // the tripod's nodal point above the floor
  double search_radius_m = 1.0;       // positions tried around the click
  double coarse_step_m = 0.1;         // grid of positions tried first ...
  double fine_step_m = 0.02;          // ... and around the best few
  int candidates = 3;                 // coarse poses refined
  int work_width = 1440;              // the still is compared at this width (0.25 deg a column)
  double min_wall_distance_m = 0.15;  // a tripod stands at least this far from a wall
  double truncation_px = 8.0;         // chamfer distances are truncated here (at work_width)
  double top_above_camera_m =
      0.4;  // vertical edges are drawn from the floor up to this height above the camera
  double nadir_limit_deg = -65.0;  // below this elevation (the tripod) nothing is compared
  // Each curve pixel compared with the still's edges that run its way only (oriented chamfer matching):
  // a tiled or patterned floor has edges every way, that fit a wall drawn anywhere over it.
  bool oriented_edges = true;
  std::optional<double> heading_hint_deg;  // the author's second click: the still's centre looks this way
  double heading_hint_spread_deg = 30.0;   // ... give or take this
  // > 0: the best fit this far or farther from the chosen spot is reported too (elsewhere_score_px), to
  // tell a placement from one of several look-alike spots (a corridor, repeated rooms).
  double elsewhere_gap_m = 0.0;
  void check() const;  // throws Error naming the bad field
};

struct StillPlacement {
  double x = 0.0, y = 0.0, heading_deg = 0.0;  // plan metres; heading as in ARCHITECTURE.md
  double score_px = 0.0;                       // mean truncated chamfer distance of the plan's curves
  // The best pose whose heading is more than 15 deg away: near-equal scores mean the room looks alike
  // both ways round (give a heading hint).
  double runner_up_heading_deg = 0.0;
  double runner_up_score_px = 0.0;
  // With StillOnPlanOptions::elsewhere_gap_m: the best poses found that far or farther from the chosen one
  // (x, y, heading in degrees, fit), best first, and the best of their fits (infinity when none).
  std::vector<Eigen::Vector4d> elsewhere;
  double elsewhere_score_px = std::numeric_limits<double>::infinity();
  int samples = 0;  // curve pixels compared at the chosen pose
  double seconds = 0.0;
  // One sentence for the author, e.g. "placed 0.18 m from the click, heading 32.4 deg; fit 1.9 px".
  std::string summary;
};

// Throws Error when the plan has no sight-blocking segments, the still is empty, or no position within
// the search radius is clear of the walls. Cancel through progress.
StillPlacement place_still_on_plan(const cv::Mat& still, const FloorPlan& plan, const Eigen::Vector2d& click,
                                   const StillOnPlanOptions& options = {},
                                   Progress& progress = null_progress());

// The same search among given spots (each refined on the fine grid around it), e.g. along the direction in
// which a still connected by a pair lies from a placed one. The summary's distance is from spots.front().
StillPlacement place_still_among(const cv::Mat& still, const FloorPlan& plan,
                                 const std::vector<Eigen::Vector2d>& spots,
                                 const StillOnPlanOptions& options = {},
                                 Progress& progress = null_progress());

// The fit (score_px as above, lower is better) of the still at each of `poses` (x, y in plan metres, heading
// in degrees), with no search: to tell which of several placements of a group of stills is right.
std::vector<double> still_fits_px(const cv::Mat& still, const FloorPlan& plan,
                                  const std::vector<Eigen::Vector3d>& poses,
                                  const StillOnPlanOptions& options = {});

// The still at work_width with the plan's curves at a pose drawn over it (red), and the edges they are
// compared with (green): what the author sees to judge a placement.
cv::Mat draw_plan_on_still(const cv::Mat& still, const FloorPlan& plan, double x, double y,
                           double heading_deg, const StillOnPlanOptions& options = {});

// The path with the piece holding frame `frame_index` (a capture index) moved rigidly so that frame lands
// on `placed`, and that piece marked placed: a still that connected to no other is a piece of one; a
// group of a few stills unconnected to the rest moves as a whole; `points` of that piece (when given) move
// with it. Throws Error when no frame has that index.
CameraPath path_with_still_placed(const CameraPath& path, int frame_index, const StillPlacement& placed,
                                  std::vector<PathPoint>* points = nullptr);

// Whether a still may be placed by moving its piece: it is in an unplaced piece of its own, or of several
// with a metric scale (a group without one must be split first: split_unscaled_groups).
bool still_can_be_moved(const CameraPath& path, int frame_index);

}  // namespace plenopath
