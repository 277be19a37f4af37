#pragma once
// The refinement's residual: the angle between an observed unit bearing (camera frame) and the bearing
// predicted from a planar pose (x, y, heading; camera at z = 0) and a 3-D point, measured on the sphere
// (not in equirect pixels, which stretch near the poles).
// The functor needs no Ceres header (Jets are found by argument-dependent lookup); Create() lives in the
// .cpp.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace ceres {
class CostFunction;
}

namespace plenopath {

struct PlanarBearingCost {
  explicit PlanarBearingCost(const Eigen::Vector3d& observed_bearing)
      : bearing(observed_bearing.normalized()) {}

  // pose = (x, y, heading), point = (X, Y, Z) in the plan frame; residual[3] = predicted unit bearing minus
  // the observed one (the chord: 2 sin(angle / 2), about the angle near the solution, and unlike tangent
  // components it has no false minimum at the antipode, so points cannot slip behind the camera).
  template <typename T>
  bool operator()(const T* pose, const T* point, T* residual) const {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T dx = point[0] - pose[0], dy = point[1] - pose[1], dz = point[2];
    const T c = cos(pose[2]), s = sin(pose[2]);
    // camera_from_world rotation is R(heading)^T.
    const T px = c * dx + s * dy;
    const T py = -s * dx + c * dy;
    const T pz = dz;
    const T norm = sqrt(px * px + py * py + pz * pz + T(1e-18));
    residual[0] = px / norm - T(bearing.x());
    residual[1] = py / norm - T(bearing.y());
    residual[2] = pz / norm - T(bearing.z());
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& observed_bearing);

  Eigen::Vector3d bearing;
};

}  // namespace plenopath
