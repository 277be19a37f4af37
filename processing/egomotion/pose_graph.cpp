#include "processing/egomotion/pose_graph.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

#include "model/error.h"

namespace plenopath {
namespace {

// Residual of one edge, whitened by its standard deviations: translation (2), turn (1), log scale (1).
// Node parameters: x, y, heading, log scale.
struct SimilarityEdgeCost {
  explicit SimilarityEdgeCost(const PoseGraphEdge& e) : edge(e) {}
  template <typename T>
  bool operator()(const T* a, const T* b, T* residual) const {
    using std::cos;
    using std::exp;
    using std::sin;
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    const T c = cos(a[2]), s = sin(a[2]), shrink = exp(-a[3]);
    const T lx = (c * dx + s * dy) * shrink, ly = (-s * dx + c * dy) * shrink;
    residual[0] = (lx - T(edge.translation.x())) / T(edge.translation_sigma);
    residual[1] = (ly - T(edge.translation.y())) / T(edge.translation_sigma);
    // The turn's difference wrapped through its sine and cosine would flatten the cost far from the
    // solution; headings here come from a tracker that never loses a full turn, so a plain difference.
    residual[2] = (b[2] - a[2] - T(edge.turn)) / T(edge.turn_sigma);
    residual[3] = (b[3] - a[3] - T(edge.log_scale)) / T(edge.log_scale_sigma);
    return true;
  }
  PoseGraphEdge edge;
};

class CancelCallback : public ceres::IterationCallback {
 public:
  CancelCallback(Progress& progress, int max_iterations)
      : progress_(progress), max_iterations_(std::max(1, max_iterations)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    progress_.report(std::min(1.0, static_cast<double>(summary.iteration) / max_iterations_));
    return progress_.is_cancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  Progress& progress_;
  int max_iterations_;
};

}  // namespace

PoseGraphReport solve_pose_graph(std::vector<PoseGraphNode>& nodes, const std::vector<PoseGraphEdge>& edges,
                                 int max_iterations, Progress& progress) {
  PoseGraphReport report;
  const int n = static_cast<int>(nodes.size());
  if (n < 2 || edges.empty()) return report;
  std::vector<Eigen::Vector4d> x(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) x[i] << nodes[i].pose, nodes[i].log_scale;
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::HuberLoss huber(3.0);  // in standard deviations
  for (const PoseGraphEdge& e : edges) {
    if (e.from < 0 || e.to < 0 || e.from >= n || e.to >= n || e.from == e.to)
      throw Error("pose graph: an edge names node " + std::to_string(e.from) + " and " +
                  std::to_string(e.to) + " of " + std::to_string(n));
    if (!(e.translation_sigma > 0 && e.turn_sigma > 0 && e.log_scale_sigma > 0))
      throw Error("pose graph: an edge's standard deviations must be > 0");
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<SimilarityEdgeCost, 4, 4, 4>(new SimilarityEdgeCost(e)),
        e.robust ? &huber : nullptr, x[static_cast<std::size_t>(e.from)].data(),
        x[static_cast<std::size_t>(e.to)].data());
  }
  if (!problem.HasParameterBlock(x[0].data())) return report;
  problem.SetParameterBlockConstant(x[0].data());
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-10;
  options.logging_type = ceres::SILENT;
  CancelCallback callback(progress, max_iterations);
  options.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  progress.throw_if_cancelled();
  report.iterations = static_cast<int>(summary.iterations.size());
  report.initial_cost = summary.initial_cost;
  report.final_cost = summary.final_cost;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    nodes[i].pose = x[i].head<3>();
    nodes[i].log_scale = x[i][3];
  }
  return report;
}

}  // namespace plenopath
