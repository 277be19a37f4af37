#pragma once
// The camera path: one planar pose per frame (x, y in metres, heading in radians, CCW from +X).
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace plenopath {

// Why a frame is not trusted. Flags combine; `reason` says it in words for the author.
enum FrameFlag : std::uint32_t {
  kFrameOk = 0,
  kFrameTextureless = 1u << 0,
  kFrameDuplicate = 1u << 1,      // the trolley stopped
  kFrameJump = 1u << 2,           // sudden change the motion model rejects
  kFrameMovingObjects = 1u << 3,  // many tracks inconsistent with the static scene
  kFrameBridged = 1u << 4,        // pose interpolated across a stretch the tracker could not solve
  kFrameCorrupt = 1u << 5,        // the image could not be decoded
  kFrameManual = 1u << 6,         // placed by the author
  kFramePieceStart = 1u << 7,     // first frame of a piece: no image connects it to the frame before
};

struct PathFrame {
  int index = 0;     // position in the capture
  std::string file;  // frame file, relative to the path file's folder (may be empty for video)
  double x = 0.0;
  double y = 0.0;
  double heading = 0.0;  // radians
  double confidence = 1.0;
  std::uint32_t flags = kFrameOk;
  std::string reason;
  int piece = 0;  // the PathPiece this frame belongs to (CameraPath::pieces)

  Eigen::Vector2d position() const { return {x, y}; }
};
bool operator==(const PathFrame& l, const PathFrame& r);

// A stretch of the capture that the images connect. Where nothing connects one stretch to the next (a
// recording stopped and restarted elsewhere, the camera through a wall, a dark corridor), the path is in
// pieces: each has its own metric scale and its own gauge, and is placed on the plan on its own. A piece not
// placed yet has coordinates of its own (its first frame at the origin, heading 0) and is drawn as unplaced.
struct PathPiece {
  int first_index = 0, last_index = 0;  // capture indices of its first and last frames
  bool placed = true;                   // in the path's (plan's) frame; false: own coordinates only
  std::string scale_source;             // "camera_height", "distance", "relative", ...
  double scale_factor = 1.0;            // metres per tracker unit, as the tracker found it
  std::string break_reason;             // why the piece before ended (empty for the first piece)
};
bool operator==(const PathPiece& l, const PathPiece& r);

struct CameraPath {
  std::vector<PathFrame> frames;  // sorted by index
  std::string scale_source;       // how metric scale was found: "ground_truth", "camera_height", ...
  // Empty: one piece, placed. Otherwise pieces[k] describes the frames with PathFrame::piece == k, in
  // capture order.
  std::vector<PathPiece> pieces;

  bool empty() const { return frames.empty(); }
  std::size_t size() const { return frames.size(); }
  double length() const;
  // Cumulative arc length at each frame (same size as frames, starting at 0); no length is counted from
  // one piece to the next.
  std::vector<double> arc_lengths() const;
  int piece_count() const { return pieces.empty() ? 1 : static_cast<int>(pieces.size()); }
  bool piece_placed(int piece) const;  // true for a path without pieces
  // The frames of one piece, as a path of its own (piece 0 of it; scale source that of the piece).
  CameraPath piece_path(int piece) const;
  // Position of the frame with this capture index, or nullptr.
  const PathFrame* find_frame(int index) const;
};
bool operator==(const CameraPath& l, const CameraPath& r);

// Throws Error "<who>: piece k (frames a-b) is not placed on the plan yet: ..." when a piece is unplaced:
// what needs plan positions (visibility, sampling, export) cannot use it.
void require_placed(const CameraPath& path, const std::string& who);

// Renumbers a path whose frame i is the capture's frame positions[i] (a tracker numbers the frames it was
// given 0..n-1): frame and piece indices become capture positions. Throws Error when sizes disagree.
void renumber_frames(CameraPath* path, const std::vector<int>& positions);

// Heading helpers: radians wrapped to (-pi, pi].
double wrap_angle(double radians);
double degrees(double radians);
double radians(double degrees);
// An angle read from a file that degrees() wrote: the radians whose degrees() gives back exactly `degrees`
// (within a few ulps of radians(degrees)), so that a project or path file read and written again keeps its
// digits: deg(rad(deg(h))) can differ from deg(h) in the last bit, and the command line, which reads back
// what each step wrote, would then write other bytes than the studio, which keeps the angle in memory.
double radians_of_written(double degrees);

}  // namespace plenopath
