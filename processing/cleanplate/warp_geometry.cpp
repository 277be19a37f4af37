#include "processing/cleanplate/warp_geometry.h"

#include <algorithm>
#include <cmath>

#include "rig/spherical.h"

namespace plenopath {

std::vector<int> neighbours_within(const CameraPath& path, int key_position, double min_m, double max_m,
                                   int each_side) {
  const PathFrame& key = path.frames[static_cast<std::size_t>(key_position)];
  const int count = static_cast<int>(path.size());
  std::vector<int> within;
  for (int side : {-1, 1})
    for (int j = key_position + side; j >= 0 && j < count; j += side) {
      const PathFrame& n = path.frames[static_cast<std::size_t>(j)];
      if (n.piece != key.piece) break;
      const double baseline = std::hypot(n.x - key.x, n.y - key.y);
      if (baseline > max_m) break;
      if (baseline >= min_m) within.push_back(j);
    }
  std::sort(within.begin(), within.end());
  const std::size_t wanted = static_cast<std::size_t>(2 * each_side);
  if (within.size() <= wanted) return within;
  std::vector<int> out;
  for (std::size_t i = 0; i < wanted; ++i) out.push_back(within[(i * (within.size() - 1)) / (wanted - 1)]);
  return out;
}

std::vector<Eigen::Vector3f> plan_rays(double heading, int w, int h) {
  std::vector<Eigen::Vector3f> rays(static_cast<std::size_t>(w) * h);
  const Eigen::Matrix3d world_from_key = world_from_camera_rotation(heading);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      rays[static_cast<std::size_t>(v) * w + u] =
          (world_from_key * equirect_to_bearing({u + 0.5, v + 0.5}, w, h)).cast<float>();
  return rays;
}

}  // namespace plenopath
