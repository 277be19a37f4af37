#pragma once
// Ceres cost functions of the planar pose graphs that bend a path (anchor_refinement.cpp, and the plan
// refinement in processing/registration): poses are (x, y, heading) blocks of three doubles; the drift
// block is {scale, turn bias per step}. Header only (templates for Ceres' autodiff); include from .cpp files.
#include <ceres/ceres.h>

#include <Eigen/Core>
#include <algorithm>
#include <string>

#include "processing/util/progress.h"

namespace plenopath::pose_graph {

// Relative motion of step i -> i+1 expressed in frame i, as the tracker measured it, corrected by the
// drift unknowns of its stretch of path: drift = {scale, turn bias per step}. A tracker's drift is a slow
// heading bias and a scale error; modelling them keeps the solver from explaining them by bending the path.
struct StepResidual {
  StepResidual(const Eigen::Vector2d& local_step, double turn, double sigma_t, double sigma_r)
      : local_step_(local_step), turn_(turn), sigma_t_(sigma_t), sigma_r_(sigma_r) {}

  template <typename T>
  bool operator()(const T* a, const T* b, const T* drift, T* residual) const {
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    const T c = ceres::cos(a[2]), s = ceres::sin(a[2]);
    residual[0] = (c * dx + s * dy - drift[0] * T(local_step_.x())) / T(sigma_t_);
    residual[1] = (-s * dx + c * dy - drift[0] * T(local_step_.y())) / T(sigma_t_);
    // Heading difference wrapped through atan2 so a turn across +-pi costs what it should.
    const T d = b[2] - a[2] - (T(turn_) - drift[1]);
    residual[2] = ceres::atan2(ceres::sin(d), ceres::cos(d)) / T(sigma_r_);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector2d& local_step, double turn, double sigma_t,
                                     double sigma_r) {
    return new ceres::AutoDiffCostFunction<StepResidual, 3, 3, 3, 2>(
        new StepResidual(local_step, turn, sigma_t, sigma_r));
  }

 private:
  Eigen::Vector2d local_step_;
  double turn_, sigma_t_, sigma_r_;
};

// Keeps the drift unknowns near "no drift" where the anchors say nothing about them.
struct DriftPrior {
  DriftPrior(double sigma_scale, double sigma_bias) : sigma_scale_(sigma_scale), sigma_bias_(sigma_bias) {}
  template <typename T>
  bool operator()(const T* drift, T* residual) const {
    residual[0] = (drift[0] - T(1.0)) / T(sigma_scale_);
    residual[1] = drift[1] / T(sigma_bias_);
    return true;
  }
  static ceres::CostFunction* Create(double sigma_scale, double sigma_bias) {
    return new ceres::AutoDiffCostFunction<DriftPrior, 2, 2>(new DriftPrior(sigma_scale, sigma_bias));
  }

 private:
  double sigma_scale_, sigma_bias_;
};

struct AnchorPrior {
  AnchorPrior(const Eigen::Vector2d& position, double sigma) : position_(position), sigma_(sigma) {}
  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    residual[0] = (pose[0] - T(position_.x())) / T(sigma_);
    residual[1] = (pose[1] - T(position_.y())) / T(sigma_);
    return true;
  }
  static ceres::CostFunction* Create(const Eigen::Vector2d& position, double sigma) {
    return new ceres::AutoDiffCostFunction<AnchorPrior, 2, 3>(new AnchorPrior(position, sigma));
  }

 private:
  Eigen::Vector2d position_;
  double sigma_;
};

struct HeadingPrior {
  HeadingPrior(double heading, double sigma) : heading_(heading), sigma_(sigma) {}
  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const T d = pose[2] - T(heading_);
    residual[0] = ceres::atan2(ceres::sin(d), ceres::cos(d)) / T(sigma_);
    return true;
  }
  static ceres::CostFunction* Create(double heading, double sigma) {
    return new ceres::AutoDiffCostFunction<HeadingPrior, 1, 3>(new HeadingPrior(heading, sigma));
  }

 private:
  double heading_, sigma_;
};

// Reports each iteration (fraction of max_iterations) and stops the solver when cancelled; the caller throws
// once Solve() has returned (no exception through Ceres).
class ProgressCallback : public ceres::IterationCallback {
 public:
  ProgressCallback(Progress& progress, int max_iterations)
      : progress_(progress), max_iterations_(std::max(1, max_iterations)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    progress_.report(std::min(0.99, (summary.iteration + 1.0) / max_iterations_),
                     "iteration " + std::to_string(summary.iteration));
    return progress_.is_cancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  Progress& progress_;
  int max_iterations_;
};

}  // namespace plenopath::pose_graph
