#pragma once
// The points the tracker triangulated (processing/egomotion), kept with the path so that the path can be
// registered on the plan later (processing/registration). Each point is in the frame of its piece of the
// path (CameraPath::pieces; the same frame as that piece's poses), metric, with z measured from the camera
// centre (the floor lies at z = -camera height).
//
// Sidecar file (the project file has no place for thousands of points): PROJECT.plenopath's points are in
// PROJECT.points.json next to it, a path file PATH.json's in PATH.points.json (points_file_beside()); they
// are in the frame of the path as tracked or registered (anchor refinement bends the path, not them):
//   {"format":"plenopath-path-points","version":2,"units":"m",
//    "points":[[x, y, z, piece, observations, frame], ...]}
// Version 1 files (five numbers, no frame) are read with frame -1; a newer version is refused.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace plenopath {

struct PathPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // metres, the piece's frame; camera centre at z = 0
  int piece = 0;                                       // CameraPath::pieces index (0 for a one-piece path)
  int observations = 0;                                // keyframe observations that measured it
  // The capture index (PathFrame::index) of the keyframe the point is tied to (the middle one of those that
  // saw it): the plan refinement moves the point with that frame's pose. -1 = not known (version 1 files).
  int frame = -1;
};
bool operator==(const PathPoint& l, const PathPoint& r);

// Throws Error naming the file (unreadable, not a points file, a bad entry with its position).
std::vector<PathPoint> read_path_points_file(const std::string& file);
class JsonReader;
// The same from parsed JSON (`json` names the file in errors).
std::vector<PathPoint> path_points_from_json(const JsonReader& json);
// Written atomically; throws Error naming the file.
void write_path_points_file(const std::vector<PathPoint>& points, const std::string& file);
// "dir/P.plenopath" -> "dir/P.points.json", "dir/path.json" -> "dir/path.points.json".
std::string points_file_beside(const std::string& file);

// The points of a path renumbered by renumber_frames (camera_path.h): frame i becomes positions[i]. A frame
// outside positions becomes -1 (not known).
void renumber_point_frames(std::vector<PathPoint>* points, const std::vector<int>& positions);

// Moves the points of `piece` by the same similarity as its poses (placed = s R p + t, z scaled by s).
void transform_piece_points(std::vector<PathPoint>* points, int piece, double rotation, double scale,
                            const Eigen::Vector2d& translation);

}  // namespace plenopath
