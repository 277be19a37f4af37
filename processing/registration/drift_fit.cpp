// Plan refinement, stiff rounds (plan_refinement.h): the path keeps its tracked shape but for the drift model
// (scale, heading bias per step) and its placement (shift and turn about its first frame), five unknowns
// fitted to the walls by Gauss-Newton with Cauchy weights (iteratively reweighted), every round with fresh
// ties at a shrinking distance. Five unknowns seen through thousands of wall points: found from the whole
// building at once, where a pose graph with stiff steps would crawl (its damping grows with the stiffness).
#include <Eigen/Dense>
#include <cmath>

#include "processing/registration/registration_internal.h"

namespace plenopath::registration_detail {
std::vector<Eigen::Vector3d> apply_drift_model(const std::vector<Eigen::Vector3d>& start,
                                               const DriftModel& m) {
  std::vector<Eigen::Vector3d> out(start.size());
  if (start.empty()) return out;
  Eigen::Vector2d p = start[0].head<2>() + m.shift;
  for (std::size_t i = 0; i < start.size(); ++i) {
    if (i > 0) {
      const double turn =
          m.turn - double(i - 1) * m.bias;  // of frame i-1, in whose axes the step was tracked
      p += m.scale * rotate(start[i].head<2>() - start[i - 1].head<2>(), turn);
    }
    out[i] = {p.x(), p.y(), start[i].z() + m.turn - double(i) * m.bias};
  }
  return out;
}

DriftModel fit_drift_model(const std::vector<Eigen::Vector3d>& start, const std::vector<DriftTie>& ties,
                           const SegmentGrid& grid, const DriftFitOptions& options, Progress& progress) {
  DriftModel model;
  using Vector5 = Eigen::Matrix<double, 5, 1>;
  auto to_vector = [](const DriftModel& m) {
    Vector5 v;
    v << m.shift.x(), m.shift.y(), m.turn, m.scale, m.bias;
    return v;
  };
  auto from_vector = [](const Vector5& v) {
    DriftModel m;
    m.shift = {v[0], v[1]};
    m.turn = v[2];
    m.scale = v[3];
    m.bias = v[4];
    return m;
  };
  // Prior sigmas per unknown (placement, scale, bias), as weights on the normal equations.
  const Vector5 prior_sigma(options.shift_sigma_m, options.shift_sigma_m, options.turn_sigma_rad,
                            options.scale_sigma, options.bias_sigma_rad);
  for (std::size_t round = 0; round < options.within_m.size(); ++round) {
    const double within = options.within_m[round];
    const double loss = std::max(options.min_loss_m, options.loss_fraction * within);
    // Fresh ties at this round's distance, from where the model puts the points now.
    const std::vector<Eigen::Vector3d> now = apply_drift_model(start, model);
    struct Tie {
      const DriftTie* tie;
      Eigen::Vector2d on_wall, normal;
    };
    std::vector<Tie> tied;
    for (const DriftTie& t : ties) {
      const Eigen::Vector3d& p = now[t.pose];
      const Eigen::Vector2d q = p.head<2>() + model.scale * rotate(t.local, p.z());
      Tie k{&t, {}, {}};
      if (wall_of(q, p.head<2>(), grid, within, &k.on_wall, &k.normal)) tied.push_back(k);
    }
    if (tied.size() < 10) break;
    for (int iteration = 0; iteration < options.iterations; ++iteration) {
      progress.checkpoint((round + (iteration + 1.0) / options.iterations) / options.within_m.size(),
                          "drift model, round " + std::to_string(round + 1));
      // Residuals (metres) of the ties under model m.
      auto residuals = [&](const DriftModel& m) {
        const std::vector<Eigen::Vector3d> poses = apply_drift_model(start, m);
        Eigen::VectorXd r(tied.size());
        for (std::size_t j = 0; j < tied.size(); ++j) {
          const Eigen::Vector3d& p = poses[tied[j].tie->pose];
          const Eigen::Vector2d q = p.head<2>() + m.scale * rotate(tied[j].tie->local, p.z());
          r[static_cast<Eigen::Index>(j)] = tied[j].normal.dot(q - tied[j].on_wall);
        }
        return r;
      };
      const Vector5 x = to_vector(model);
      const Eigen::VectorXd r0 = residuals(model);
      Eigen::MatrixXd jac(r0.size(), 5);
      const Vector5 step(1e-5, 1e-5, 1e-7, 1e-7, 1e-9);
      for (int k = 0; k < 5; ++k) {
        Vector5 plus = x, minus = x;
        plus[k] += step[k];
        minus[k] -= step[k];
        jac.col(k) = (residuals(from_vector(plus)) - residuals(from_vector(minus))) / (2 * step[k]);
      }
      // Cauchy weights (iteratively reweighted least squares) and the priors at no drift, no move.
      Eigen::Matrix<double, 5, 5> h = Eigen::Matrix<double, 5, 5>::Zero();
      Vector5 g = Vector5::Zero();
      for (Eigen::Index j = 0; j < r0.size(); ++j) {
        const double w = 1.0 / (1.0 + std::pow(r0[j] / loss, 2));
        h += w * jac.row(j).transpose() * jac.row(j);
        g += w * jac.row(j).transpose() * r0[j];
      }
      const Vector5 at_prior(0, 0, 0, 1, 0);
      const double noise2 = options.wall_sigma_m * options.wall_sigma_m;
      for (int k = 0; k < 5; ++k) {
        const double w = noise2 / (prior_sigma[k] * prior_sigma[k]);
        h(k, k) += w;
        g[k] += w * (x[k] - at_prior[k]);
      }
      const Vector5 delta = h.ldlt().solve(-g);
      if (!delta.allFinite()) break;
      model = from_vector(x + delta);
      if (std::abs(delta[0]) + std::abs(delta[1]) < 1e-5 && std::abs(delta[2]) < 1e-7 &&
          std::abs(delta[3]) < 1e-6 && std::abs(delta[4]) < 1e-9)
        break;
    }
  }
  return model;
}

}  // namespace plenopath::registration_detail
