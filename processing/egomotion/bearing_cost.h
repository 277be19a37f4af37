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

// A camera that rocks on an uneven floor: world_from_camera = Rz(heading) Ry(pitch) Rx(roll), the camera
// centre still at z = 0. tilt = (pitch, roll), radians. Undoing the tilt after the heading keeps the
// heading what it is for a level camera (the direction of the image's centre column, seen from above).
template <typename T>
void tilted_camera_direction(const T* pose, const T* tilt, const T* point, T* out) {
  using std::cos;
  using std::sin;
  const T dx = point[0] - pose[0], dy = point[1] - pose[1], dz = point[2];
  const T c = cos(pose[2]), s = sin(pose[2]);
  const T lx = c * dx + s * dy, ly = -s * dx + c * dy, lz = dz;  // level camera frame
  const T cp = cos(tilt[0]), sp = sin(tilt[0]), cr = cos(tilt[1]), sr = sin(tilt[1]);
  const T x1 = cp * lx - sp * lz, z1 = sp * lx + cp * lz;  // Ry(-pitch)
  out[0] = x1;
  out[1] = cr * ly + sr * z1;  // Rx(-roll)
  out[2] = -sr * ly + cr * z1;
}

struct TiltedBearingCost {
  explicit TiltedBearingCost(const Eigen::Vector3d& observed_bearing)
      : bearing(observed_bearing.normalized()) {}

  template <typename T>
  bool operator()(const T* pose, const T* tilt, const T* point, T* residual) const {
    using std::sqrt;
    T p[3];
    tilted_camera_direction(pose, tilt, point, p);
    const T norm = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + T(1e-18));
    residual[0] = p[0] / norm - T(bearing.x());
    residual[1] = p[1] / norm - T(bearing.y());
    residual[2] = p[2] / norm - T(bearing.z());
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& observed_bearing);

  Eigen::Vector3d bearing;
};

// Holds a pose's tilt near level: residual = weight * (pitch, roll).
struct TiltPrior {
  explicit TiltPrior(double weight) : weight(weight) {}
  template <typename T>
  bool operator()(const T* tilt, T* residual) const {
    residual[0] = T(weight) * tilt[0];
    residual[1] = T(weight) * tilt[1];
    return true;
  }
  static ceres::CostFunction* Create(double weight);
  double weight;
};

// Angle (radians) between an observed bearing and the direction to `point` from a tilted camera.
double tilted_ray_error(const Eigen::Vector3d& pose, const Eigen::Vector2d& tilt,
                        const Eigen::Vector3d& point, const Eigen::Vector3d& bearing);

}  // namespace plenopath
