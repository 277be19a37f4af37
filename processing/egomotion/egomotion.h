#pragma once
// The camera path from the panoramas alone (seed paper §4, issue 5), COLMAP-controller style: options with
// defaults and check(), a streaming add_frame() (ring image + KLT per frame, so frames are read once) and
// finish() that runs the geometric steps, reporting to a Progress (processing/util/progress.h):
//   1. coarse headings from ring images (ring_heading.h);
//   1b. frame-to-frame turns from the KLT tracks (median azimuth change refined by planar two-view),
//      chained: the heading guide of the later steps (the rings bridge frames without tracks);
//   2. keyframes ("chunks": cut when the scene has moved enough or the heading has turned), the direction
//      of each step by planar two-view RANSAC on bearings, its length by bearing-only resection against the
//      points triangulated so far, chained into (x, y);
//   3. Ceres refinement of keyframe poses and points (path_refinement.h): windows, then loop closures
//      (loop_closure.h) tie revisited places together, then one global pass; every other frame is resected
//      against the refined points;
//   4. metric scale from the camera height (floor points lie at -h) or a known distance, else relative;
//   5. frames that cannot be trusted are flagged with a reason (model/camera_path.h FrameFlag).
// Where the images stop connecting (capture_pieces.cpp), steps 2-5 run on each piece on its own: a broken
// capture comes back in pieces (CameraPath::pieces), each with its own scale and gauge, never bridged by a
// guess. Piece 0 is placed (its first frame at the origin, heading 0); the others are unplaced.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "model/camera_path.h"
#include "model/path_points.h"
#include "processing/egomotion/klt_tracks.h"
#include "processing/egomotion/loop_closure.h"
#include "processing/egomotion/path_refinement.h"
#include "processing/egomotion/planar_two_view.h"
#include "processing/egomotion/ring_heading.h"
#include "processing/egomotion/static_mask.h"
#include "processing/util/progress.h"

namespace plenopath {

// When the frames stop connecting (see capture_pieces.cpp).
struct PieceOptions {
  int min_link_tracks = 20;  // fewer tracks continue from a frame into the next: not connected by tracks
  // A run of connected frames shorter than this (or with fewer textured frames) is no piece of its own: its
  // frames go with the piece before, bridged.
  int min_piece_frames = 10;
  int join_search_frames = 15;  // described frames this near either side of a stretch are matched to join it
  int join_max_pairs = 24;      // frame pairs tried per stretch, nearest first
  int join_min_inliers = 15;    // verified descriptor matches of a frame pair across the stretch
  // ... and two such pairs must agree on the turn across it (carried by the tracked turns on each side).
  double join_agreement_deg = 1.0;
  void check() const;  // throws Error naming the bad field
};

struct EgomotionOptions {
  RingOptions ring;
  KltOptions klt;
  PlanarTwoViewOptions two_view;
  RefinementOptions refinement;
  LoopClosureOptions loop;  // between the windowed and the global refinement
  PieceOptions pieces;
  double keyframe_parallax_deg = 2.0;  // median rotation-free parallax since the last keyframe that makes one
  double keyframe_max_turn_deg = 8.0;  // heading change since the last keyframe that cuts a chunk
  double keyframe_min_shared = 0.5;    // fraction of the last keyframe's tracks still seen; below it, cut
  // A two-view turn (consecutive frames, or keyframes) this far from the turn the tracks' azimuths suggest
  // is taken for a wrong solution.
  double max_step_turn_disagreement_deg = 3.0;
  // Frame-to-frame turns leave out the tracks that stay put in the image while the others turn (on the
  // trolley or the operator, where the static mask missed them): a scene point cannot stay put in a turn.
  bool turns_ignore_still_tracks = true;
  double max_step_ratio = 5.0;  // a keyframe step this many times above or below the recent median is bridged
  // ... unless 20 points or more measure it with a median relative deviation below this (a real jump: frames
  // dropped, video subsampled).
  double max_step_spread = 0.1;
  // A keyframe step is checked against the points triangulated so far: when resection against them (from
  // where the last speed would carry the camera) explains this many times as many of them as the step
  // measured by two-view geometry, and at least resection_min_points, the resected step is taken (0 = no
  // check). Only a gross disagreement switches: on the walks that track well the two agree.
  double step_map_check_factor = 2.0;
  double step_map_check_deg = 20.0;  // ... when the two directions differ by more than this
  // A keyframe step's two-view direction more than step_map_check_deg from the usual one (the median of
  // the last five measured steps', in the camera's frame) is replaced by the usual one when that explains
  // at least this share as many of the tracks that moved (0 = never): the camera is carried forward,
  // walkers cross in any direction.
  double step_direction_prior_share = 0.7;
  // With the floor prior (refinement.floor_sigma > 0: the camera rides at one height), the chaining measures
  // a keyframe step on the floor once the first keyframes have shown its level: from this many floor tracks
  // (0 = never), when they agree within this share of the step (median absolute deviation) and more
  // precisely (that deviation over the square root of the count) than the points known so far.
  int floor_step_min_points = 8;
  double floor_step_max_spread = 0.15;
  double min_triangulation_deg = 1.0;  // rays of a point must span at least this angle
  double max_initial_error_deg = 1.0;  // observations this far off after initialisation are dropped
  int min_point_keyframes = 3;         // a point enters the refinement when seen from this many keyframes
  int resection_min_points = 12;       // fewer points seen: the frame's pose is bridged (interpolated)
  // Metric scale, in order of preference: the camera's height above the floor, or a distance between two
  // frames the author knows. Neither: relative scale (first keyframe step = 1).
  double camera_height_m = 0.0;
  int scale_frame_a = -1, scale_frame_b = -1;
  double scale_distance_m = 0.0;
  // Flags.
  int textureless_corners = 60;     // fewer live corners than this: textureless
  double duplicate_flow_px = 0.08;  // median track motion below this (and no turn): duplicate / stopped
  double jump_factor = 6.0;         // a step this many times the local median step: jump
  // Above this share of a frame's tracks moving against the static scene (off the step's epipolar geometry):
  // moving objects. Clean renders stay below 0.003 at the 99th percentile (0.10 at worst, in 7 deg/frame
  // turns); 25 people walking about the office reach 0.09.
  double moving_outlier_fraction = 0.15;
  std::uint32_t seed = 1;
  // Pixels not to use, as the author drew them (CV_8U, any size, resized to the working size: 255 = usable,
  // 0 = the trolley, the operator, a logo). Empty = none. Combined with the automatic static-region mask.
  cv::Mat mask;
  // The automatic static-region mask (static_mask.h): the first frames are buffered until it is decided
  // (static_mask.frames = 0: no automatic mask, no buffering).
  StaticMaskOptions static_mask;
  void check() const;  // throws Error naming the bad field
};

struct EgomotionResult {
  // One pose per frame, headings radians; frame 0 at (0, 0), heading 0. In pieces (path.pieces) where the
  // images do not connect: each later piece unplaced, its first frame at (0, 0), heading 0.
  CameraPath path;
  int joins = 0;              // stretches without tracks whose two sides descriptor matches connected
  int steps_from_points = 0;  // keyframe steps taken from the points, not two-view (step_map_check_factor)
  int steps_on_floor = 0;     // keyframe steps measured on the floor (floor_step_min_points)
  std::vector<int> continued_tracks;          // per frame: KLT tracks continued into it from the frame before
  std::vector<double> ring_headings;          // step 1's headings per frame (radians, frame 0 = 0)
  std::vector<double> tracked_headings;       // frame-to-frame turns from the KLT tracks, chained (radians)
  std::vector<Eigen::Vector3d> coarse_poses;  // step 2's (x, y, heading) per frame, final scale
  std::vector<int> keyframes;                 // frame indices
  int points = 0;
  int observations = 0;
  // The refined points that kept an observation, each in its piece's frame (that of its poses: metric,
  // camera centres at z = 0, the floor at z = -camera height), with its piece and observation count. What
  // registration on the plan (processing/registration) fits to the walls.
  std::vector<PathPoint> tracked_points;
  RefinementReport refinement;
  int loop_closures = 0;                         // places recognised as revisited (frame pairs)
  std::vector<std::pair<int, int>> loop_frames;  // those pairs: (earlier frame, later frame)
  int merged_points = 0;                         // points tied to an earlier visit's by them
  std::string scale_source;                      // piece 0's: "camera_height", "distance", or "relative"
  double scale_factor = 1.0;                     // piece 0's metres per internal unit applied at the end
  int floor_points = 0;                          // points used for the camera-height scale
  int flagged_frames = 0;
  cv::Mat mask;  // the pixels used (255) and masked (0) at the working size; empty = all used
  double static_mask_fraction = 0.0;   // share of the image masked (author's and automatic)
  bool levelled = false;               // bearings levelled by per-frame tilt (KltOptions::auto_level)
  double tilt_spread_deg = 0.0;        // the first frames' tilt spread auto_level judged (0: not judged)
  double track_memory_mb = 0;          // the KLT track history kept for the geometry (MiB)
  double seconds_per_frame_stage = 0;  // ring + KLT (excluding decoding)
  double seconds_geometry = 0;         // everything in finish()
};

// Progress stages: "frames" (run() only), "headings", "chaining", "refinement", "resection". A cancel ends
// finish() or run() with Cancelled (processing/util/progress.h) and no result.

class EgomotionTracker {
 public:
  explicit EgomotionTracker(const EgomotionOptions& options);  // throws Error on bad options
  ~EgomotionTracker();
  void add_frame(const cv::Mat& bgr);  // frames in capture order
  int frame_count() const;
  EgomotionResult finish(Progress& progress = null_progress());

  // Convenience: reads frame_count frames through `read` (whose time is not counted), then finishes.
  static EgomotionResult run(int frame_count, const std::function<cv::Mat(int)>& read,
                             const EgomotionOptions& options, Progress& progress = null_progress());

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace plenopath
