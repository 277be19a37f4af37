#include "processing/stills/edge_lengths.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "processing/util/statistics.h"

namespace plenopath {

void triangulate_unit_baseline(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                               double turn, double direction, double min_parallax_deg,
                               std::vector<double>* depth_a, std::vector<double>* depth_b) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  depth_a->assign(a.size(), nan);
  depth_b->assign(a.size(), nan);
  const Eigen::Vector3d t(std::cos(direction), std::sin(direction), 0.0);
  const double c = std::cos(turn), s = std::sin(turn);
  const double min_parallax = min_parallax_deg * M_PI / 180.0;
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) {
    const Eigen::Vector3d ra = a[k].normalized();
    const Eigen::Vector3d rb =
        Eigen::Vector3d(c * b[k].x() - s * b[k].y(), s * b[k].x() + c * b[k].y(), b[k].z()).normalized();
    if (std::acos(std::clamp(ra.dot(rb), -1.0, 1.0)) < min_parallax) continue;
    const double ab = ra.dot(rb), det = 1.0 - ab * ab;
    if (det < 1e-10) continue;
    const double at = ra.dot(t), bt = rb.dot(t);
    const double lambda = (at - ab * bt) / det, mu = (ab * at - bt) / det;
    if (lambda <= 0 || mu <= 0) continue;
    (*depth_a)[k] = lambda;
    (*depth_b)[k] = mu;
  }
}

EdgeLengths solve_edge_lengths(int still_count, const std::vector<EdgeDepths>& edges, int min_shared,
                               double max_log_spread) {
  EdgeLengths out;
  const int m = static_cast<int>(edges.size());
  out.length.assign(edges.size(), 0.0);
  if (m == 0) return out;
  // Per still: feature -> (edge, depth from this still).
  std::vector<std::map<int, std::vector<std::pair<int, double>>>> seen(static_cast<std::size_t>(still_count));
  for (int e = 0; e < m; ++e) {
    const EdgeDepths& d = edges[static_cast<std::size_t>(e)];
    for (std::size_t k = 0; k < d.features.size(); ++k) {
      if (std::isfinite(d.depth_a[k]))
        seen[static_cast<std::size_t>(d.a)][d.features[k].first].push_back({e, d.depth_a[k]});
      if (std::isfinite(d.depth_b[k]))
        seen[static_cast<std::size_t>(d.b)][d.features[k].second].push_back({e, d.depth_b[k]});
    }
  }
  // Ratio equations log L1 - log L2 = log(d2 / d1), one per pair of edges at a still.
  struct Ratio {
    int e1, e2;
    double value, weight;
  };
  std::vector<Ratio> ratios;
  for (const auto& features : seen) {
    std::map<std::pair<int, int>, std::vector<double>> logs;
    for (const auto& [feature, list] : features)
      for (std::size_t i = 0; i < list.size(); ++i)
        for (std::size_t j = i + 1; j < list.size(); ++j) {
          const auto [e1, d1] = list[i];
          const auto [e2, d2] = list[j];
          if (e1 == e2) continue;
          logs[{std::min(e1, e2), std::max(e1, e2)}].push_back(e1 < e2 ? std::log(d2 / d1)
                                                                       : std::log(d1 / d2));
        }
    for (const auto& [key, values] : logs) {
      if (static_cast<int>(values.size()) < min_shared) continue;
      const double mid = median(values);
      if (median_absolute_deviation(values, mid) > max_log_spread) continue;
      ratios.push_back({key.first, key.second, mid, std::sqrt(static_cast<double>(values.size()))});
    }
  }
  out.ratios = static_cast<int>(ratios.size());
  // Sets of edges tied by ratios.
  std::vector<int> parent(static_cast<std::size_t>(m));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x)
      x = parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  for (const Ratio& r : ratios) parent[static_cast<std::size_t>(find(r.e1))] = find(r.e2);
  std::map<int, std::vector<int>> sets;
  for (int e = 0; e < m; ++e) sets[find(e)].push_back(e);
  // The set with the most floor trust, else the largest.
  int best_root = -1;
  double best_metric = -1;
  std::size_t best_size = 0;
  for (const auto& [root, members] : sets) {
    double metric = 0;
    for (int e : members)
      metric += edges[static_cast<std::size_t>(e)].metric_length > 0
                    ? edges[static_cast<std::size_t>(e)].metric_weight
                    : 0.0;
    if (metric > best_metric || (metric == best_metric && members.size() > best_size)) {
      best_metric = metric;
      best_size = members.size();
      best_root = root;
    }
  }
  const std::vector<int>& chosen = sets[best_root];
  if (chosen.size() < 2 && best_metric <= 0) return out;  // nothing tied, nothing measured
  std::vector<int> slot(static_cast<std::size_t>(m), -1);
  for (std::size_t k = 0; k < chosen.size(); ++k)
    slot[static_cast<std::size_t>(chosen[k])] = static_cast<int>(k);
  const int n = static_cast<int>(chosen.size());
  // Rows: ratios inside the set, metric lengths, or (no metric) the first edge at log length 0.
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> values, weights;
  for (const Ratio& r : ratios) {
    const int i = slot[static_cast<std::size_t>(r.e1)], j = slot[static_cast<std::size_t>(r.e2)];
    if (i < 0 || j < 0) continue;
    Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
    row(i) = 1.0;
    row(j) = -1.0;
    rows.push_back(row);
    values.push_back(r.value);
    weights.push_back(r.weight);
  }
  out.metric = best_metric > 0;
  for (int k = 0; k < n; ++k) {
    const EdgeDepths& d = edges[static_cast<std::size_t>(chosen[static_cast<std::size_t>(k)])];
    if (out.metric ? d.metric_length <= 0 : k != 0) continue;
    Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
    row(k) = 1.0;
    rows.push_back(row);
    values.push_back(out.metric ? std::log(d.metric_length) : 0.0);
    weights.push_back(out.metric ? std::sqrt(d.metric_weight) : 1.0);
  }
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), n);
  Eigen::VectorXd y(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    A.row(static_cast<Eigen::Index>(r)) = weights[r] * rows[r].transpose();
    y(static_cast<Eigen::Index>(r)) = weights[r] * values[r];
  }
  const Eigen::VectorXd x = A.colPivHouseholderQr().solve(y);
  for (int k = 0; k < n; ++k)
    out.length[static_cast<std::size_t>(chosen[static_cast<std::size_t>(k)])] = std::exp(x(k));
  return out;
}

}  // namespace plenopath
