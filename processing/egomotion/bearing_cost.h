#pragma once
// The refinement's residual: the angle between an observed unit bearing (camera frame) and the bearing
// predicted from a planar pose (x, y, heading; camera at z = 0) and a 3-D point. Residuals are the two
// tangent-plane components of the predicted unit direction around the observation (sines of the angle),
// so they are in radians near the solution and do not stretch near the poles like equirect pixels would.
// The functor needs no Ceres header (Jets are found by argument-dependent lookup); Create() lives in the .cpp.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace ceres {
class CostFunction;
}

namespace plenopath {

struct PlanarBearingCost {
  explicit PlanarBearingCost(const Eigen::Vector3d& observed_bearing) {
    const Eigen::Vector3d b = observed_bearing.normalized();
    // Any orthonormal tangent basis around b.
    const Eigen::Vector3d helper = std::abs(b.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
    tangent_1 = b.cross(helper).normalized();
    tangent_2 = b.cross(tangent_1);
    bearing = b;
  }

  // pose = (x, y, heading), point = (X, Y, Z) in the plan frame; residual[2].
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
    residual[0] = (T(tangent_1.x()) * px + T(tangent_1.y()) * py + T(tangent_1.z()) * pz) / norm;
    residual[1] = (T(tangent_2.x()) * px + T(tangent_2.y()) * py + T(tangent_2.z()) * pz) / norm;
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& observed_bearing);

  Eigen::Vector3d bearing, tangent_1, tangent_2;
};

}  // namespace plenopath
