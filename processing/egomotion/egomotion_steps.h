#pragma once
// The steps of EgomotionTracker::finish() (egomotion.h), one file each, shared through this internal header:
// frame_turns.cpp (1b), capture_pieces.cpp (where the images stop connecting), piece_solver.cpp (2-5 for
// one piece). Not part of the public API.
#include <Eigen/Core>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/path_points.h"
#include "processing/egomotion/descriptor_store.h"
#include "processing/egomotion/egomotion.h"
#include "processing/egomotion/klt_tracks.h"
#include "processing/egomotion/loop_closure.h"
#include "processing/egomotion/path_refinement.h"

namespace plenopath::egomotion_steps {

Eigen::Vector3d rotate_z(const Eigen::Vector3d& v, double angle);
void add_flag(PathFrame& f, FrameFlag flag, const std::string& why);
// Angle between a world ray and the direction from a centre to a point.
double ray_error(const Eigen::Vector3d& pose, const Eigen::Vector3d& point, const Eigen::Vector3d& bearing);
// Pose-only Gauss-Newton (x, y, heading) on angular residuals with a Huber weight. Returns the inlier count.
int resect_pose(Eigen::Vector3d* pose, const std::vector<Eigen::Vector3d>& points,
                const std::vector<Eigen::Vector3d>& bearings, double huber, double inlier_threshold);
// The same for a camera that may be tilted: (x, y, heading) and tilt = (pitch, roll) (bearing_cost.h), the
// tilt held near level by residuals tilt_weight * tilt (as the refinement's prior). Returns the inlier count.
int resect_tilted_pose(Eigen::Vector3d* pose, Eigen::Vector2d* tilt,
                       const std::vector<Eigen::Vector3d>& points,
                       const std::vector<Eigen::Vector3d>& bearings, double huber, double inlier_threshold,
                       double tilt_weight);
// Step 2's check of a keyframe step against the points triangulated so far (`points`, seen from keyframe b
// along `bearings`, b's camera frame): b resected against them from `predicted` (where the last speed would
// carry it), at b's heading, explains how many of them, against b placed at `measured` (the two-view step).
// The step is replaced by the resected one when the two directions from `a` differ by more than
// `min_turn` radians and the resected position explains at least `min_points` and `factor` times as many.
struct StepCheck {
  bool replaced = false;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // b's: the resected one when replaced, else measured
  int explained_measured = 0, explained_resected = 0;
};
StepCheck check_step_against_points(const Eigen::Vector2d& a, const Eigen::Vector2d& measured,
                                    const Eigen::Vector2d& predicted, double heading_b,
                                    const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<Eigen::Vector3d>& bearings, double huber,
                                    double inlier_threshold, double factor, int min_points, double min_turn);
// Merges the points of each verified pair of tracks (union-find; the earlier point stays), rewrites the
// observations and the track-to-point map. Returns how many points were merged away.
int merge_loop_points(const std::vector<LoopMatch>& loops, BundleProblem* problem,
                      std::vector<int>* point_of_track);

// The KLT tracks seen per frame, and their observations and bearings. The per-frame lists are one array
// (4 bytes an observation), not a vector per frame.
struct TrackView {
  struct Tracks {  // the tracks observed in one frame, in increasing order
    const int* first = nullptr;
    const int* last = nullptr;
    const int* begin() const { return first; }
    const int* end() const { return last; }
    std::size_t size() const { return static_cast<std::size_t>(last - first); }
    bool empty() const { return first == last; }
  };
  const KltTracker* klt = nullptr;

  explicit TrackView(const KltTracker& tracker, int frame_count);
  int frame_count() const { return static_cast<int>(frame_begin_.size()) - 1; }
  Tracks frame_tracks(int frame) const {
    return {track_ids_.data() + frame_begin_[static_cast<std::size_t>(frame)],
            track_ids_.data() + frame_begin_[static_cast<std::size_t>(frame) + 1]};
  }
  int track_count() const { return klt->track_count(); }
  bool seen(int track, int frame) const { return klt->seen(track, frame); }
  Eigen::Vector3d bearing(int track, int frame) const;  // camera frame, unit; requires seen(track, frame)

 private:
  std::vector<std::size_t>
      frame_begin_;  // frame f's tracks: track_ids_[frame_begin_[f], frame_begin_[f + 1])
  std::vector<int> track_ids_;
};

// Everything finish() has measured before the geometry, for all frames.
struct TrackerMeasurements {
  const EgomotionOptions* options = nullptr;
  const TrackView* view = nullptr;
  const DescriptorStore* described = nullptr;
  std::vector<double> heading;       // chained frame-to-frame turns (radians), the heading guide
  std::vector<double> moving_share;  // per frame, -1 when unknown (egomotion.cpp explains)
  std::vector<bool> textureless;
  // Angular tolerances scaled to the working width (egomotion.cpp explains).
  double coarseness = 1.0;
  double pixel_angle = 0.0;
  PlanarTwoViewOptions two_view;
  RefinementOptions refinement;
};

// Step 1b: frame-to-frame turns from the KLT tracks (median azimuth change, refined by planar two-view),
// the rings' turn where tracks are too few; and per frame the share of tracks moving against the scene.
void measure_frame_turns(const std::vector<double>& ring_headings, std::mt19937& rng, TrackerMeasurements* m);

// Where the images connect. A join ties the two sides of a stretch without tracks by descriptor matches.
struct CaptureJoin {
  int frame_a = 0, frame_b = 0;  // last frame before the stretch, first frame after it
  double turn = 0.0;             // heading of b minus a, verified (radians)
  double direction = 0.0;        // b seen from a in a's frame; NaN when not observable
  std::vector<std::pair<int, int>> track_pairs;
};
struct PiecePlan {
  int first = 0, last = 0;   // frames (inclusive)
  std::string break_reason;  // why the piece before ended (empty for the first)
};
struct CapturePieces {
  std::vector<PiecePlan> pieces;
  std::vector<CaptureJoin> joins;  // inside pieces
};
CapturePieces find_capture_pieces(const std::vector<FrameTrackStats>& stats, const TrackerMeasurements& m,
                                  std::mt19937& rng);

// Steps 2-5 for the frames [plan.first, plan.last] of one piece: keyframes, chaining, refinement with loop
// closures (and the piece's joins), every frame against the refined points, metric scale, jumps.
struct PieceSolution {
  std::vector<Eigen::Vector3d> poses;   // (x, y, heading) per frame of the piece, metric, own gauge
  std::vector<Eigen::Vector3d> coarse;  // step 2's, same scale and gauge
  std::vector<int> keyframes;           // capture frames
  // The refined points (each with at least one observation left), same scale and gauge as the poses.
  std::vector<PathPoint> tracked_points;
  int points = 0, observations = 0, merged_points = 0, floor_points = 0;
  int steps_from_points = 0;  // keyframe steps the points contradicted, taken from them instead
  int steps_on_floor = 0;     // keyframe steps measured on the floor
  RefinementReport refinement;
  std::vector<std::pair<int, int>> loop_frames;
  std::string scale_source = "relative";
  double scale_factor = 1.0;
};

// Flags and confidences go to `frames` (all frames of the capture). Reports the stages "chaining",
// "refinement" and "resection" over this piece's [0, 1]; a cancel ends it with Cancelled.
PieceSolution solve_piece(const PiecePlan& plan, const std::vector<CaptureJoin>& joins,
                          const TrackerMeasurements& m, std::vector<PathFrame>* frames, std::mt19937& rng,
                          Progress& progress);

}  // namespace plenopath::egomotion_steps
