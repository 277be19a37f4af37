#pragma once
// Step 2's raw material: KLT feature tracks across an equirectangular sequence. Corners are found with
// goodFeaturesToTrack and followed with pyramidal Lucas-Kanade on the panorama padded across the seam
// (BORDER_WRAP), so a feature walking over azimuth +-180 keeps its track. Frames are tracked at a working
// width (resized) and observations are kept as working-image pixels; bearing() turns them into unit
// bearings in the camera frame (rig/spherical.h).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <deque>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "processing/egomotion/affine_patch.h"
#include "processing/egomotion/vertical_tilt.h"

namespace plenopath {

struct KltOptions {
  int work_width = 1024;         // frames are resized to this width for tracking (0 = keep the frame's)
  int max_features = 700;        // corners kept alive at most
  int min_features = 450;        // below this many live tracks, new corners are detected
  double quality_level = 0.003;  // goodFeaturesToTrack quality (relative to the best corner)
  int min_distance_px = 10;      // between corners, working pixels
  int window_px = 21;            // Lucas-Kanade window
  // Auto-exposure jumps undone before tracking: a frame whose brightness (median ratio of 64x32 blocks)
  // changes by more than exposure_jump (relative) against the frame before is scaled back (gain within
  // 1/3..3, kept for the frames after). On the POV-Ray corridor walk (x1.2 on frames 60-95, x0.7 on
  // 210-240) the capture otherwise breaks in three pieces at the jumps.
  bool normalise_exposure = true;
  double exposure_jump = 0.06;
  int pyramid_levels = 3;
  // When the predicted turn (add_frame's, from the rings) continues fewer than this share of the live tracks,
  // the previous frame's turn is tried as well and the guess that continues more tracks wins: the rings miss
  // fast turns where the walls are plain or the rig fills their band, and a turn lasts several frames
  // (bench_nuisances corridor_like, 26 cm steps turning up to 42 deg a frame). 0 = never.
  double retry_share = 0.6;
  double max_abs_elevation_deg = 72.0;  // corners nearer the poles are not used (stretched, few)
  double forward_backward_px = 0.7;     // forward-backward check tolerance; <= 0 disables the check
  // A track longer than this many frames is cut and continued as a new track (a new 3-D point): what drift
  // is left after the affine refinement (a few hundredths of a pixel at each template refresh) stays below
  // the refinement's noise. Each track is cut after between half and all of this many frames of camera
  // motion (staggered, so tracks born together do not end together; a turn on the spot does not count); the
  // continuation shares the cut track's last observation. 0 = never cut. On the 400-frame office walk
  // (1024 wide): 24 -> heading RMS 0.056 deg, ATE 0.015 %; 48 -> 0.035 deg, 0.010 %; never -> 0.059 deg.
  int max_track_frames = 48;
  // Frames count towards max_track_frames only when the camera moved: the median flow left after removing
  // the median sideways flow (a turn) exceeds this (working pixels).
  double min_parallax_flow_px = 0.15;
  // Each observation after the first is refined by aligning the feature's first patch under an affine warp
  // (affine_patch.h): translation-only Lucas-Kanade slides about 0.1 px per frame as the patch deforms.
  // A refinement that fails, or moves the point farther than max_affine_correction_px from where
  // Lucas-Kanade put it, ends the track (a new one starts there). A patch deformed by more than
  // affine_refresh_deformation (relative change of a length, or rotation in radians) is cut anew where it
  // was aligned: floor points passing the camera shrink to half their width within a few frames.
  bool affine_refinement = true;
  AffinePatchOptions affine;
  double max_affine_correction_px = 1.5;
  double affine_refresh_deformation = 0.15;
  // Pitch and roll per frame from its vertical edges (vertical_tilt.h), and bearing() levelled by them: for a
  // camera that rocks on an uneven floor. Off by default: on a level camera the estimate's own noise
  // (0.08 deg RMS at 1024 wide, 0.2 deg at 512 on the office renders) costs more than it gains.
  bool level_bearings = false;
  // Unless level_bearings forces it: the tilt of the first auto_level_frames frames is estimated, and when
  // it varies by more than auto_level_spread_deg (pitch and roll together, each as 1.4826 x its median
  // absolute deviation; at 1024 wide, scaled with the working width like the estimate's noise) the camera
  // rocks: every frame's bearings are levelled. Otherwise no more tilt is estimated. A trolley whose tilt
  // changes within a few frames otherwise scatters the chained step directions (bench_nuisances
  // steps_26cm_fast_tilt: heading 0.336 deg unlevelled, 0.016 levelled). Captures shorter than
  // auto_level_frames stay unlevelled.
  bool auto_level = true;
  int auto_level_frames = 40;
  double auto_level_spread_deg = 0.3;
  TiltOptions tilt;
  void check() const;  // throws Error naming the bad field
};

struct TrackObservation {
  int frame = 0;
  float x = 0.f, y = 0.f;  // working-image pixel coordinates (x in [0, width))
};

struct FeatureTrack {
  std::vector<TrackObservation> observations;  // consecutive frames
};

// Bytes the tracker keeps for its track history: about 4 per observation, 16 per track.
struct TrackMemory {
  std::size_t observations = 0, tracks = 0, bytes = 0;
};

struct FrameTrackStats {
  int tracked = 0;            // tracks continued into this frame
  int lost = 0;               // tracks that ended at the previous frame
  int detected = 0;           // new corners started in this frame
  int corners_available = 0;  // corners the detector found (after masking), a texture measure
  double median_flow_px = 0;  // median displacement of continued tracks, working pixels
};

class KltTracker {
 public:
  explicit KltTracker(const KltOptions& options);
  // Tracks into the next frame (BGR or gray, any size; equirectangular 2:1). predicted_shift_px: expected
  // horizontal motion of every feature in working pixels (a turn, e.g. from the ring images), used as
  // the search's starting point so fast turns stay within the pyramid's reach.
  FrameTrackStats add_frame(const cv::Mat& frame, double predicted_shift_px = 0.0);

  // The track history. Observations are kept packed (16-bit fixed point: 1/64 px at 1024 wide, far below
  // what Lucas-Kanade resolves), so that a 100 000-frame walk's 60 million observations take 240 MB, not
  // the 1.4 GB of one vector per track; the live tracks are followed at full precision.
  int track_count() const { return static_cast<int>(stored_.size()); }
  int first_frame(int track) const { return stored_[static_cast<std::size_t>(track)].first_frame; }
  int last_frame(int track) const {
    const StoredTrack& s = stored_[static_cast<std::size_t>(track)];
    return s.first_frame + s.length - 1;
  }
  bool seen(int track, int frame) const { return frame >= first_frame(track) && frame <= last_frame(track); }
  TrackObservation observation(int track, int frame) const;  // requires seen(track, frame)
  TrackObservation last_observation(int track) const;
  std::vector<FeatureTrack> tracks() const;  // every track, unpacked (tests and small captures)
  TrackMemory memory() const;
  int frame_count() const { return frame_count_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // Unit bearing in the camera frame, levelled by the frame's estimated tilt when levelling() is on.
  Eigen::Vector3d bearing(const TrackObservation& o) const;
  // Whether bearings are levelled (level_bearings, or auto_level found the camera rocking), and the spread
  // of the first frames' tilt estimates that auto_level judged (degrees; 0 before it judged).
  bool levelling() const { return levelling_ == Levelling::kOn; }
  double tilt_spread_deg() const { return tilt_spread_deg_; }
  // Pixels not to use (CV_8U, any size, 255 = usable, 0 = masked: the trolley, the operator): no corners are
  // detected there and a track entering it ends. Empty = use everything. Applies from the next frame.
  void set_mask(const cv::Mat& mask);
  const cv::Mat& mask() const { return mask_; }  // at the working size once a frame was added
  const std::vector<TiltEstimate>& tilts() const { return tilts_; }  // per frame estimated
  const std::vector<int>& live_tracks() const { return live_; }      // tracks observed in the last frame
  const std::vector<cv::Point2f>& live_positions() const { return live_positions_; }  // ... and where
  int affine_failures() const { return affine_failures_; }  // refinements refused so far (tracks cut there)
  // The median sideways flow of the tracks continued into the last frame (working pixels): its turn.
  double last_turn_px() const { return last_turn_px_; }

 private:
  cv::Mat prepare(const cv::Mat& frame);
  // add_frame's stages, in order.
  struct LiveFlow;
  void measure_tilt(const cv::Mat& gray);
  LiveFlow follow_live_tracks(const std::vector<cv::Mat>& pyramid, double predicted_shift_px, double y_min,
                              double y_max) const;
  void refine_affine(const cv::Mat& padded, LiveFlow* flow) const;
  void carry_live_tracks(const cv::Mat& padded, LiveFlow& flow, int frame_index, FrameTrackStats* stats);
  void detect_new_tracks(const cv::Mat& gray, const cv::Mat& padded, int frame_index, double y_min,
                         double y_max, FrameTrackStats* stats);
  bool unmasked(double x, double y) const;      // working-image coordinates; true without a mask
  using Packed = std::array<std::uint16_t, 2>;  // x, y in units of quantum_ pixels
  struct StoredTrack {
    int first_frame = 0;
    int length = 0;
    std::int64_t offset = -1;  // into closed_ once the track has ended
    int open = -1;             // its slot in open_ while it is live
  };
  int start_track(int frame, float x, float y);  // a new track (live), returns its index
  void extend_track(int track, float x, float y);
  void close_track(int track);  // the track has ended: its observations move to closed_
  Packed pack(float x, float y) const;
  KltOptions options_;
  int width_ = 0, height_ = 0, pad_ = 0;
  int frame_count_ = 0;
  double quantum_ = 1.0 / 64.0;  // pixels per packed unit: width / 65536
  cv::Mat previous_blocks_;      // the last frame at 64x32, as read (normalise_exposure)
  double exposure_gain_ = 1.0;   // the jumps so far, undone
  std::vector<StoredTrack> stored_;
  std::deque<Packed> closed_;  // blocks, not one array: no doubling of hundreds of MB as it grows // ended
                               // tracks' observations, each track's consecutive
  std::vector<std::vector<Packed>> open_;    // live tracks' observations, by slot
  std::vector<int> free_open_;               // unused slots of open_
  std::vector<int> live_;                    // indices of tracks observed in the last frame
  std::vector<cv::Point2f> live_positions_;  // parallel to live_: their last positions, full precision
  std::vector<int> moved_frames_;            // per track: frames since its start in which the camera moved
  struct LivePatch {
    AffinePatch patch;                        // as the track first saw it
    cv::Matx22d linear = cv::Matx22d::eye();  // its deformation up to the last frame
  };
  std::vector<LivePatch> live_patches_;  // parallel to live_ (when affine_refinement)
  int affine_failures_ = 0;
  double last_turn_px_ = 0.0;  // the median sideways flow of the tracks continued into the last frame
  std::vector<cv::Mat> previous_pyramid_;
  cv::Mat mask_;                                    // 255 = usable, working size (or as given until then)
  std::vector<TiltEstimate> tilts_;                 // per frame
  std::vector<Eigen::Matrix3d> level_from_camera_;  // per frame (level_bearings)
  enum class Levelling { kOff, kDeciding, kOn } levelling_ = Levelling::kOff;
  double tilt_spread_deg_ = 0.0;
  void decide_levelling();  // auto_level, after its first frames
};

}  // namespace plenopath
