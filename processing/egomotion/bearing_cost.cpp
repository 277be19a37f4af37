#include "processing/egomotion/bearing_cost.h"

#include <ceres/autodiff_cost_function.h>

#include <cmath>

namespace plenopath {

ceres::CostFunction* PlanarBearingCost::Create(const Eigen::Vector3d& observed_bearing) {
  return new ceres::AutoDiffCostFunction<PlanarBearingCost, 3, 3, 3>(new PlanarBearingCost(observed_bearing));
}

ceres::CostFunction* TiltedBearingCost::Create(const Eigen::Vector3d& observed_bearing) {
  return new ceres::AutoDiffCostFunction<TiltedBearingCost, 3, 3, 2, 3>(
      new TiltedBearingCost(observed_bearing));
}

ceres::CostFunction* TiltPrior::Create(double weight) {
  return new ceres::AutoDiffCostFunction<TiltPrior, 2, 2>(new TiltPrior(weight));
}

double tilted_ray_error(const Eigen::Vector3d& pose, const Eigen::Vector2d& tilt,
                        const Eigen::Vector3d& point, const Eigen::Vector3d& bearing) {
  Eigen::Vector3d d;
  tilted_camera_direction(pose.data(), tilt.data(), point.data(), d.data());
  const double angle = std::atan2(d.cross(bearing).norm(), d.dot(bearing));
  return std::isfinite(angle) ? angle : M_PI;
}

}  // namespace plenopath
