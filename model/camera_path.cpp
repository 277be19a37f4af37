#include "model/camera_path.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace plenopath {

bool operator==(const PathFrame& l, const PathFrame& r) {
  return std::tie(l.index, l.file, l.x, l.y, l.heading, l.confidence, l.flags, l.reason) ==
         std::tie(r.index, r.file, r.x, r.y, r.heading, r.confidence, r.flags, r.reason);
}

bool operator==(const CameraPath& l, const CameraPath& r) {
  return std::tie(l.frames, l.scale_source) == std::tie(r.frames, r.scale_source);
}

std::vector<double> CameraPath::arc_lengths() const {
  std::vector<double> s(frames.size(), 0.0);
  for (std::size_t i = 1; i < frames.size(); ++i)
    s[i] = s[i - 1] + (frames[i].position() - frames[i - 1].position()).norm();
  return s;
}

double CameraPath::length() const { return frames.empty() ? 0.0 : arc_lengths().back(); }

const PathFrame* CameraPath::find_frame(int index) const {
  auto it = std::lower_bound(frames.begin(), frames.end(), index,
                             [](const PathFrame& f, int i) { return f.index < i; });
  return (it != frames.end() && it->index == index) ? &*it : nullptr;
}

double wrap_angle(double radians) {
  double a = std::remainder(radians, 2.0 * M_PI);  // in [-pi, pi]
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}
double degrees(double radians) { return radians * 180.0 / M_PI; }
double radians(double degrees) { return degrees * M_PI / 180.0; }

}  // namespace plenopath
