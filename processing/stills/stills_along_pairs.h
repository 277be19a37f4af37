#pragma once
// Stills the view graph could not place, placed on the plan through the pairs they do have (issue 20). A
// pair of stills that matched well enough to give its turn and its direction but not its length (a
// corridor's plain walls, a floor too repetitive to measure) cannot join a group: nothing says how far
// apart the two are. The plan can: from a placed still, the other lies somewhere along the pair's
// direction, turned by the pair's turn, and what it sees of the walls (still_on_plan.h) says where along
// it. Repeated until no more stills can be placed, so a corridor of such pairs is placed one by one.
// Along one pair a row of look-alike bays fits nearly as well every few metres; the still's other pairs
// with placed stills say where along it: only the spots every one of them sees are tried, so pairs that
// cross (from stills off the row) leave one short stretch, and the plan picks the spot within it. (The
// POV-Ray gallery stills: two stills each with 3-4 right pairs, none with a length, were left for the
// author because their strongest pair alone met a look-alike bay 1.3 and 4 m away.)
//
// A group of stills whose scale is not metric (its floor was not measured) knows its directions but not
// its distances: it is split into stills of their own first, and its pairs place them one by one like any
// other. (The office stills scene: N1's two stills, 754 matches between them, were left off the plan as a
// group without scale.)
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "model/path_points.h"
#include "processing/stills/still_on_plan.h"
#include "processing/stills/stills.h"
#include "processing/util/progress.h"

namespace plenopath {

struct PairPlacementOptions {
  StillOnPlanOptions fit;       // camera height, resolution, truncation; the fine grid around each spot
  double min_distance_m = 0.5;  // how far along the pair's direction the other still is looked for
  double max_distance_m = 10.0;
  double step_m = 0.1;
  double lateral_m = 0.1;           // and this far either side (the direction's own error)
  double heading_spread_deg = 3.0;  // the heading within this of the pair's turn
  int min_inliers = 30;             // a pair's verified matches
  double max_fit_px = 3.25;         // a worse fit is not taken (see CandidateFitOptions::max_fit_px)
  // Along a corridor the walls look alike every few metres: the best spot farther than ambiguity_gap_m from
  // the chosen one must fit this much worse, or the still is left for the author.
  double ambiguity_gap_m = 1.0;
  double min_ambiguity_ratio = 1.15;
  // Only spots the placed still has a clear line to (the tripod was carried from one to the other, through
  // a door if need be): a pair whose direction is wrong would otherwise find rooms beyond a wall.
  bool require_line_of_sight = true;
  void check() const;  // throws Error naming the bad field
};

struct PairPlacement {
  int frame = -1;       // the still placed (capture index)
  int from_frame = -1;  // through its pair with this placed still
  StillPlacement pose;
  double runner_up_fit_px = 0.0;  // the best fit farther than ambiguity_gap_m among the spots tried
  int other_pairs = 0;            // the still's other pairs with placed stills (every one sees the spot)
  int crossing_pairs = 0;         // ... of them, those whose direction crosses from_frame's by >= 15 deg
};

struct PairPlacementReport {
  std::vector<PairPlacement> placed;
  std::vector<int> rejected;  // stills tried whose best fit was too poor or ambiguous
};

// `path` as the stills pipeline and registration left it (placed pieces on the plan); pairs from
// StillsResult::pairs (a, b are capture indices). Unplaced pieces without metric scale are split into
// stills of their own (split_unscaled_groups); then unplaced pieces of one still, or of several with a
// metric scale, are moved (rigidly, path_with_still_placed). read(i) gives still i. `points` (when given:
// the path's points, PathPoint::piece naming its pieces) are renumbered and moved with their pieces.
CameraPath place_stills_along_pairs(const CameraPath& path, const std::vector<StillsPair>& pairs,
                                    const std::function<cv::Mat(int)>& read, const FloorPlan& plan,
                                    std::vector<PathPoint>* points, const PairPlacementOptions& options = {},
                                    PairPlacementReport* report = nullptr,
                                    Progress& progress = null_progress());

// Whether `pair` (one of its stills placed at placed_position, placed_heading; placed_frame its capture
// index) sees its other still at `spot`: the pair's direction from the placed still passes within
// heading_spread_deg, or within 2 lateral_m, of it. A still placed along one pair is checked against its
// other pairs with placed stills this way, and left for the author when one disagrees.
bool pair_sees_spot(const StillsPair& pair, int placed_frame, const Eigen::Vector2d& placed_position,
                    double placed_heading, const Eigen::Vector2d& spot, const PairPlacementOptions& options);

// The plan bearing (radians) in which `pair`'s other still lies seen from its still `placed_frame`, whose
// heading is placed_heading.
double pair_bearing_from(const StillsPair& pair, int placed_frame, double placed_heading);

// Every unplaced piece of more than one still whose scale is not metric (scale_source other than
// "camera_height") becomes pieces of one still each, in their place in capture order; the pieces after
// them are renumbered. `points` (when given) follow: a point goes to the piece of the still it is tied to
// (PathPoint::frame), or of the group's first still. Returns how many pieces were split.
int split_unscaled_groups(CameraPath* path, std::vector<PathPoint>* points = nullptr);

}  // namespace plenopath
