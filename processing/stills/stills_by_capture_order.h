#pragma once
// Stills placed on the plan next to the still shot before or after them (issue 20). A tripod is carried a
// few metres between two shots: a still that matched no other (a plain room seen through a door, a room
// furnished like the one next door, so its matches point there) lies within walking reach of its
// neighbours in capture order. Every spot reachable from a placed neighbour (from both, when both are
// placed) is tried with every heading by what the still sees of the plan's walls (still_on_plan.h); the
// best is taken only when it fits well and no spot farther than ambiguity_gap_m fits nearly as well.
// The still's pairs with placed stills give its heading: their turn is right even when a look-alike room
// makes their direction wrong. The strongest sets the headings tried (within turn_tolerance_deg), and most
// of them must agree with the heading found, or the still is left. A still with no such pair is left for
// the author: the capture order says where to look, not that the still was shot there, and one still's
// walls alone are fooled by look-alike spots (a lab shot amid open-office stills fitted a corner of the
// open office at 1.4 px, as well as right placements fit).
// Repeated until no more stills can be placed, so a run of stills is placed one from the next.
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

struct CaptureOrderPlacementOptions {
  StillOnPlanOptions fit;  // camera height, resolution and truncation of the final fit
  // How far (walking, round the walls) a tripod is carried between two consecutive shots. Tour
  // photographers shoot every 1-4 m.
  double reach_m = 6.0;
  double coarse_step_m = 0.1;  // spots tried on this grid ...
  int coarse_width = 720;      // ... with the still compared at this width; the best refined at fit's
  double max_fit_px = 3.25;    // a worse fit is not taken (see CandidateFitOptions::max_fit_px)
  // The best spot farther than ambiguity_gap_m from the chosen one must fit this much worse (both refined
  // at fit's width), or the still is left for the author: corridors and repeated rooms look alike.
  double ambiguity_gap_m = 1.0;
  double min_ambiguity_ratio = 1.2;
  int min_inliers = 30;             // pairs with fewer verified matches do not vote on the heading
  double turn_tolerance_deg = 5.0;  // a pair agrees when its turn is this near the placement's
  void check() const;               // throws Error naming the bad field
};

struct CaptureOrderPlacement {
  int frame = -1;                 // the still placed (capture index)
  std::vector<int> from_frames;   // its placed neighbours in capture order
  StillPlacement pose;            // at fit's width
  double elsewhere_fit_px = 0.0;  // the best fit farther than ambiguity_gap_m (fit's width; inf: none)
  int pairs_agreeing = 0, pairs_voting = 0;  // pairs with placed stills whose turn agrees, and all of them
};

// A still tried and left for the author, and why ("fit 2.9 px", "a spot 3.1 m away fits 1.04x as well",
// "1 of 3 pairs agree on the heading").
struct CaptureOrderRejection {
  int frame = -1;
  std::string reason;
};

struct CaptureOrderReport {
  std::vector<CaptureOrderPlacement> placed;
  std::vector<CaptureOrderRejection> rejected;  // each try, in order (a still may be tried again)
};

// Spots on a `step` grid within `reach` metres of `from` by an 8-connected walk that crosses none of the
// plan's sight-blocking segments.
std::vector<Eigen::Vector2d> spots_within_walking_reach(const FloorPlan& plan, const Eigen::Vector2d& from,
                                                        double reach, double step);

// `path` as the stills pipeline and registration left it. Unplaced pieces of one still, or of several with
// a metric scale, are moved (rigidly, path_with_still_placed), with their `points` when given. read(i)
// gives still i. `pairs`: StillsResult::pairs (capture indices).
CameraPath place_stills_by_capture_order(const CameraPath& path, const std::vector<StillsPair>& pairs,
                                         const std::function<cv::Mat(int)>& read, const FloorPlan& plan,
                                         std::vector<PathPoint>* points,
                                         const CaptureOrderPlacementOptions& options = {},
                                         CaptureOrderReport* report = nullptr,
                                         Progress& progress = null_progress());

}  // namespace plenopath
