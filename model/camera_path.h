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

  Eigen::Vector2d position() const { return {x, y}; }
};
bool operator==(const PathFrame& l, const PathFrame& r);

struct CameraPath {
  std::vector<PathFrame> frames;  // sorted by index
  std::string scale_source;       // how metric scale was found: "ground_truth", "camera_height", ...

  bool empty() const { return frames.empty(); }
  std::size_t size() const { return frames.size(); }
  double length() const;
  // Cumulative arc length at each frame (same size as frames, starting at 0).
  std::vector<double> arc_lengths() const;
  // Position of the frame with this capture index, or nullptr.
  const PathFrame* find_frame(int index) const;
};
bool operator==(const CameraPath& l, const CameraPath& r);

// Heading helpers: radians wrapped to (-pi, pi].
double wrap_angle(double radians);
double degrees(double radians);
double radians(double degrees);

}  // namespace plenopath
