#pragma once
// Poses of still panoramas shot from a tripod metres apart (issue 20), where the video tracker
// (processing/egomotion), which follows features from frame to frame, finds nothing to follow:
//   1. sphere features on each still (sphere_features.h);
//   2. every pair matched (mutual nearest RootSIFT neighbours passing Lowe's ratio) and verified by planar
//      two-view geometry (planar_two_point.h); a pair with enough verified matches is an edge of the view
//      graph, with its turn, its direction of travel and, when the pair sees enough of the floor, its
//      metric length from the camera height (floor_scale.h);
//   3. per connected group of the graph: headings by circular averaging, positions from the directions and
//      lengths (view_graph.h), then one Ceres refinement of poses and points (stills_refinement.h);
//   4. metric scale from the camera height: the floor among the refined points lies at -camera height;
//   5. the result as a path in pieces (ARCHITECTURE.md): pieces follow capture order, so each group comes as
//      its runs of consecutive stills. The largest group's runs are placed (one frame: its first still at
//      the origin, heading 0); every other run is unplaced, in coordinates of its own, and its
//      break_reason says which group it belongs to. A still that connects to nothing is a run of one and
//      is listed in `unconnected`, as the tracker reports pieces.
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/path_points.h"
#include "processing/stills/planar_two_point.h"
#include "processing/stills/sphere_features.h"
#include "processing/stills/stills_refinement.h"
#include "processing/stills/view_graph.h"
#include "processing/util/progress.h"

namespace plenopath {

struct StillsOptions {
  SphereFeatureOptions features;
  double match_ratio = 0.8;  // Lowe's ratio test on RootSIFT distances
  PlanarRansacOptions two_view;
  int min_pair_inliers = 40;  // verified matches that make a pair an edge of the view graph
  // ... and the azimuth they must cover in both views (36 bins of 10 deg). Identical furniture in two rooms
  // (the same desk model) matches as a copy displaced by the distance between the copies, consistently
  // enough to pass the two-view check, but over the copy's small part of the view; two stills that truly
  // see the same room share much more of the horizon. 120 deg was chosen on the POV-Ray stills scene
  // (wrong edges there covered 40-130 deg, right ones 70-230 deg): a trade, not a proof.
  double min_pair_coverage_deg = 120.0;
  // Stills next to each other in capture order (the author carried the tripod from one to the other) need
  // less: a corridor's plain walls give few matches over a narrow view, and the false match the coverage
  // test is there for (the same furniture in two rooms) seldom falls between two consecutive shots. Such a
  // pair needs its direction (parallax) and its length from the floor it sees.
  int consecutive_min_inliers = 30;
  double consecutive_min_coverage_deg = 30.0;
  // Below this median parallax of its verified matches a pair's direction of travel is not trusted (the
  // stills are nearly on the same spot); the pair still gives its turn.
  double min_direction_parallax_deg = 2.0;
  HeadingAveragingOptions headings;
  // Edges that disagree with the solved positions (solve_positions_robust): a direction this far off is
  // dropped, a length this far off (relative) loses its length.
  double max_direction_residual_deg = 3.0;
  double max_length_residual = 0.1;
  StillsRefinementOptions refinement;
  // Height of the tripod's nodal point above the floor, metres: the metric scale. The author gives it (the
  // command line's --camera-height); 1.6 m is a usual tripod for real-estate tours.
  double camera_height_m = 1.6;
  int min_floor_points = 15;  // floor points needed for a scale (per pair, and for the refined group)
  std::uint32_t seed = 1;
  void check() const;  // throws Error naming the bad field
};

struct StillsPair {
  int a = 0, b = 0;  // a < b
  int matches = 0;   // descriptor matches before verification
  int inliers = 0;   // verified by the planar two-view pose (0: not verified)
  double turn_deg = 0.0, direction_deg = 0.0, rms_error_deg = 0.0, median_parallax_deg = 0.0;
  double length_m = 0.0;  // from the floor seen by the pair, 0 when not measured
  int floor_points = 0;
  double coverage_deg = 0.0;  // azimuth the verified matches cover (10 deg bins occupied, the lesser view)
  bool edge = false;          // verified well enough to be an edge of the view graph
  bool kept = false;          // an edge that the heading averaging and the positions kept
};

struct StillsResult {
  CameraPath path;  // one frame per still, index = position in the input, in pieces (see above)
  std::vector<std::vector<int>> groups;  // connected groups, largest first (singletons included)
  std::vector<int> unconnected;          // stills that connect to no other still
  std::vector<StillsPair> pairs;         // every pair that had matches
  std::vector<int> features;             // per still
  std::vector<PathPoint> points;         // refined points, in their piece's frame (the path's pieces)
  StillsRefinementReport refinement;     // summed over the groups
  std::string scale_source;              // the largest group's: "camera_height" or "relative"
  double scale_factor = 1.0;             // the largest group's metres per unit applied after refinement
  int floor_points = 0;                  // the largest group's points on the floor level
  double seconds = 0.0;
};

// Progress stages: "features", "matching", "graph", "refinement". A cancel ends the run with Cancelled.
// read(i) returns still i (BGR or grey equirectangular); a still that cannot be read throws Error naming it.
StillsResult solve_stills(int count, const std::function<cv::Mat(int)>& read, const StillsOptions& options,
                          Progress& progress = null_progress());

}  // namespace plenopath
