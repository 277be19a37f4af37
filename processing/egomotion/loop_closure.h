#pragma once
// Loop closure: where the walk comes back to a place it has been, the points seen then and now are tied
// together, so that the global refinement removes the drift accumulated in between (a tracker alone keeps
// it: on a 10 000-frame walk there and back, heading wandered 0.12 deg RMS).
//
// While frames stream in, every few frames the live KLT features get ORB descriptors (at the tracks'
// positions: no second detector). After the windowed refinement, frames whose estimated positions lie close
// together but far apart along the path are candidates; their descriptors are matched (mutual nearest
// neighbours, Lowe's ratio), and the matches are verified by planar two-view geometry with the estimated
// turn. The verified track pairs are returned; the caller merges their points.
#include <Eigen/Core>
#include <functional>
#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "processing/egomotion/planar_two_view.h"

namespace plenopath {

struct LoopClosureOptions {
  bool enabled = true;
  int descriptor_stride = 3;  // describe every this many frames
  // Candidates: estimated positions within max_distance_steps typical keyframe steps of each other, at least
  // min_travel_steps steps apart along the path (so the two are not simply neighbours).
  double max_distance_steps = 8.0;
  // 40: 4 m at 10 cm steps. At 100 the POV-Ray gap walk, looping within one office, crossed its own path
  // after 9 m and was never closed.
  double min_travel_steps = 40.0;
  double max_turn_disagreement_deg = 6.0;  // the verified turn may differ this much from the estimated one
  int min_inliers = 40;                    // verified matches needed to accept a pair
  double ratio = 0.8;                      // Lowe's ratio test on Hamming distances
  int spacing_frames = 24;  // after an accepted pair, the next candidate frame is this much later
  void check() const;       // throws Error naming the bad field
};

struct FrameDescriptors {
  int frame = 0;
  std::vector<int> tracks;  // the track of each descriptor row
  cv::Mat descriptors;      // CV_8U, ORB
};

// gray: the working image (CV_8U); positions of the given tracks in it (OpenCV pixel coordinates).
FrameDescriptors describe_frame(const cv::Mat& gray, int frame, const std::vector<int>& tracks,
                                const std::vector<cv::Point2f>& positions);

struct LoopMatch {
  int frame_a = 0, frame_b = 0;                  // frame_a < frame_b
  std::vector<std::pair<int, int>> track_pairs;  // (track seen at frame_a, track seen at frame_b), verified
  double turn = 0.0;                             // verified heading of b minus a, radians
};

// Mutual nearest neighbours that also pass Lowe's ratio test on Hamming distances: (row in a, row in b).
std::vector<std::pair<int, int>> match_descriptors(const cv::Mat& a, const cv::Mat& b, double ratio);

// Matches two described frames and verifies the matches by planar two-view geometry started from
// turn_guess (NaN: the median azimuth change of the matches) (or, when the frames are on the very spot, by a
// pure turn). A match is accepted with at least min_inliers verified pairs and a verified turn within
// max_turn_error (radians) of the guess; returns false otherwise. `direction` (when not null) gets B's
// direction seen from A in A's frame, NaN when the baseline is too short to see it.
bool verify_frame_match(const FrameDescriptors& fa, const FrameDescriptors& fb,
                        const std::function<Eigen::Vector3d(int, int)>& bearing, double turn_guess,
                        double max_turn_error, int min_inliers, double ratio,
                        const PlanarTwoViewOptions& two_view, std::mt19937& rng, LoopMatch* match,
                        double* direction = nullptr);

// pose(frame): estimated (x, y, heading); travelled(frame): estimated path length up to it; bearing(track,
// frame): the track's unit bearing in that frame (camera frame). typical_step: the median keyframe step in
// the same units as the poses.
class DescriptorStore;
// Only the described frames in [first_frame, last_frame] take part.
std::vector<LoopMatch> find_loop_closures(const DescriptorStore& described, int first_frame, int last_frame,
                                          const std::function<Eigen::Vector3d(int)>& pose,
                                          const std::function<double(int)>& travelled,
                                          const std::function<Eigen::Vector3d(int, int)>& bearing,
                                          double typical_step, const PlanarTwoViewOptions& two_view,
                                          const LoopClosureOptions& options, std::mt19937& rng);

}  // namespace plenopath
