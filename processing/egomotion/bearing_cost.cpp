#include "processing/egomotion/bearing_cost.h"

#include <ceres/autodiff_cost_function.h>

namespace plenopath {

ceres::CostFunction* PlanarBearingCost::Create(const Eigen::Vector3d& observed_bearing) {
  return new ceres::AutoDiffCostFunction<PlanarBearingCost, 3, 3, 3>(new PlanarBearingCost(observed_bearing));
}

}  // namespace plenopath
