#include "model/camera_path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "model/error.h"

namespace plenopath {

bool operator==(const PathFrame& l, const PathFrame& r) {
  return std::tie(l.index, l.file, l.x, l.y, l.heading, l.confidence, l.flags, l.reason, l.piece) ==
         std::tie(r.index, r.file, r.x, r.y, r.heading, r.confidence, r.flags, r.reason, r.piece);
}

bool operator==(const PathPiece& l, const PathPiece& r) {
  return std::tie(l.first_index, l.last_index, l.placed, l.scale_source, l.scale_factor, l.break_reason) ==
         std::tie(r.first_index, r.last_index, r.placed, r.scale_source, r.scale_factor, r.break_reason);
}

bool operator==(const CameraPath& l, const CameraPath& r) {
  return std::tie(l.frames, l.scale_source, l.pieces) == std::tie(r.frames, r.scale_source, r.pieces);
}

bool CameraPath::piece_placed(int piece) const {
  if (pieces.empty()) return true;
  return piece >= 0 && piece < static_cast<int>(pieces.size()) &&
         pieces[static_cast<std::size_t>(piece)].placed;
}

CameraPath CameraPath::piece_path(int piece) const {
  CameraPath out;
  out.scale_source = scale_source;
  if (!pieces.empty() && piece >= 0 && piece < static_cast<int>(pieces.size()))
    out.scale_source = pieces[static_cast<std::size_t>(piece)].scale_source;
  for (const PathFrame& f : frames) {
    if (f.piece != piece) continue;
    out.frames.push_back(f);
    out.frames.back().piece = 0;
  }
  return out;
}

std::vector<double> CameraPath::arc_lengths() const {
  std::vector<double> s(frames.size(), 0.0);
  for (std::size_t i = 1; i < frames.size(); ++i)
    s[i] = s[i - 1] + (frames[i].piece == frames[i - 1].piece
                           ? (frames[i].position() - frames[i - 1].position()).norm()
                           : 0.0);
  return s;
}

double CameraPath::length() const { return frames.empty() ? 0.0 : arc_lengths().back(); }

const PathFrame* CameraPath::find_frame(int index) const {
  auto it = std::lower_bound(frames.begin(), frames.end(), index,
                             [](const PathFrame& f, int i) { return f.index < i; });
  return (it != frames.end() && it->index == index) ? &*it : nullptr;
}

void require_placed(const CameraPath& path, const std::string& who) {
  std::string unplaced;
  for (std::size_t k = 0; k < path.pieces.size(); ++k) {
    if (path.pieces[k].placed) continue;
    unplaced += (unplaced.empty() ? "" : ", ") +
                ("piece " + std::to_string(k) + " (frames " + std::to_string(path.pieces[k].first_index) +
                 "-" + std::to_string(path.pieces[k].last_index) + ")");
  }
  if (!unplaced.empty())
    throw Error(
        who + ": the path is in pieces and " + unplaced +
        " is not placed on the plan yet: anchor one of its frames where it was (Ctrl+drag on the map, "
        "or `plenopath refine --anchors`)");
}

void renumber_frames(CameraPath* path, const std::vector<int>& positions) {
  if (path->frames.size() != positions.size())
    throw Error("renumbering a path of " + std::to_string(path->frames.size()) + " frames with " +
                std::to_string(positions.size()) + " capture positions");
  auto position_of = [&](int i) {
    if (i < 0 || i >= static_cast<int>(positions.size()))
      throw Error("renumbering a path: frame " + std::to_string(i) + " is outside the capture");
    return positions[static_cast<std::size_t>(i)];
  };
  for (PathFrame& f : path->frames) f.index = position_of(f.index);
  for (PathPiece& p : path->pieces) {
    p.first_index = position_of(p.first_index);
    p.last_index = position_of(p.last_index);
  }
}

double wrap_angle(double radians) {
  double a = std::remainder(radians, 2.0 * M_PI);  // in [-pi, pi]
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}
double degrees(double radians) { return radians * 180.0 / M_PI; }
double radians(double degrees) { return degrees * M_PI / 180.0; }

double radians_of_written(double deg) {
  const double r = radians(deg);
  if (!std::isfinite(r) || degrees(r) == deg) return r;
  double down = r, up = r;
  for (int i = 0; i < 4; ++i) {
    up = std::nextafter(up, std::numeric_limits<double>::infinity());
    if (degrees(up) == deg) return up;
    down = std::nextafter(down, -std::numeric_limits<double>::infinity());
    if (degrees(down) == deg) return down;
  }
  return r;  // not written by degrees(): the nearest
}

}  // namespace plenopath
