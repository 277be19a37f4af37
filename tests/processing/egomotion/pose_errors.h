#pragma once
// A synthetic bundle's poses (x, y, heading) scored against its truth by evaluate_path (a 2-D similarity
// aligns them first), for the refinement tests.
#include <Eigen/Core>
#include <vector>

#include "model/camera_path.h"
#include "processing/egomotion/path_evaluation.h"

namespace plenopath {

inline PathErrors pose_errors(const std::vector<Eigen::Vector3d>& estimate,
                              const std::vector<Eigen::Vector3d>& truth) {
  CameraPath a, b;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const int index = static_cast<int>(i);
    a.frames.push_back({index, "", estimate[i].x(), estimate[i].y(), estimate[i].z(), 1.0, 0, ""});
    b.frames.push_back({index, "", truth[i].x(), truth[i].y(), truth[i].z(), 1.0, 0, ""});
  }
  return evaluate_path(a, b);
}

}  // namespace plenopath
