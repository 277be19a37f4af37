#include "processing/stills/view_graph.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <string>

#include "model/camera_path.h"
#include "model/option_check.h"

namespace plenopath {

void HeadingAveragingOptions::check() const {
  const std::string s = "HeadingAveragingOptions.";
  require_option(iterations >= 1, s + "iterations", "must be >= 1", iterations);
  require_option(max_residual_deg > 0, s + "max_residual_deg", "must be > 0", max_residual_deg);
}

namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(static_cast<std::size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    return true;
  }
};

std::vector<std::vector<int>> groups_of_edges(int still_count, const std::vector<ViewEdge>& edges,
                                              const std::vector<bool>* kept) {
  UnionFind uf(still_count);
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (!kept || (*kept)[e]) uf.unite(edges[e].a, edges[e].b);
  std::vector<std::vector<int>> groups;
  std::vector<int> group_of(static_cast<std::size_t>(still_count), -1);
  for (int i = 0; i < still_count; ++i) {
    const int root = uf.find(i);
    if (group_of[static_cast<std::size_t>(root)] < 0) {
      group_of[static_cast<std::size_t>(root)] = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[static_cast<std::size_t>(group_of[static_cast<std::size_t>(root)])].push_back(i);
  }
  std::stable_sort(groups.begin(), groups.end(),
                   [](const std::vector<int>& l, const std::vector<int>& r) { return l.size() > r.size(); });
  return groups;
}

}  // namespace

std::vector<std::vector<int>> connected_groups(int still_count, const std::vector<ViewEdge>& edges) {
  return groups_of_edges(still_count, edges, nullptr);
}

std::vector<double> average_headings(int still_count, const std::vector<int>& group,
                                     const std::vector<ViewEdge>& edges,
                                     const HeadingAveragingOptions& options, std::vector<bool>* kept) {
  options.check();
  std::vector<char> in_group(static_cast<std::size_t>(still_count), 0);
  for (int i : group) in_group[static_cast<std::size_t>(i)] = 1;
  kept->assign(edges.size(), false);
  std::vector<std::size_t> order;
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (in_group[static_cast<std::size_t>(edges[e].a)] && in_group[static_cast<std::size_t>(edges[e].b)]) {
      order.push_back(e);
      (*kept)[e] = true;
    }
  std::vector<double> heading(static_cast<std::size_t>(still_count), 0.0);
  if (group.size() < 2) return heading;
  const double max_residual = options.max_residual_deg * M_PI / 180.0;

  for (int round = 0; round < 2; ++round) {
    // Maximum spanning tree (Kruskal on the kept edges, heaviest first), headings propagated from the
    // group's first still.
    std::vector<std::size_t> by_weight;
    for (std::size_t e : order)
      if ((*kept)[e]) by_weight.push_back(e);
    std::stable_sort(by_weight.begin(), by_weight.end(),
                     [&](std::size_t l, std::size_t r) { return edges[l].weight > edges[r].weight; });
    UnionFind uf(still_count);
    std::vector<std::vector<std::pair<int, double>>> tree(static_cast<std::size_t>(still_count));
    for (std::size_t e : by_weight)
      if (uf.unite(edges[e].a, edges[e].b)) {
        tree[static_cast<std::size_t>(edges[e].a)].push_back({edges[e].b, edges[e].turn});
        tree[static_cast<std::size_t>(edges[e].b)].push_back({edges[e].a, -edges[e].turn});
      }
    std::vector<char> done(static_cast<std::size_t>(still_count), 0);
    std::vector<int> stack = {group.front()};
    heading[static_cast<std::size_t>(group.front())] = 0.0;
    done[static_cast<std::size_t>(group.front())] = 1;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      for (const auto& [j, turn] : tree[static_cast<std::size_t>(i)])
        if (!done[static_cast<std::size_t>(j)]) {
          done[static_cast<std::size_t>(j)] = 1;
          heading[static_cast<std::size_t>(j)] = wrap_angle(heading[static_cast<std::size_t>(i)] + turn);
          stack.push_back(j);
        }
    }
    // Each still where its neighbours say it is (Gauss-Seidel): first the weighted circular median of
    // their predictions (a wrong edge in the tree, or among the neighbours, does not pull), then
    // Cauchy-weighted circular means for precision.
    const double cauchy = 0.5 * max_residual;
    for (int it = 0; it < 2 * options.iterations; ++it) {
      const bool median_step = it < options.iterations;
      for (int i : group) {
        if (i == group.front()) continue;
        std::vector<std::pair<double, double>> predictions;  // (heading, weight)
        for (std::size_t e : order) {
          if (!(*kept)[e]) continue;
          const ViewEdge& v = edges[e];
          if (v.a == i)
            predictions.push_back({heading[static_cast<std::size_t>(v.b)] - v.turn, v.weight});
          else if (v.b == i)
            predictions.push_back({heading[static_cast<std::size_t>(v.a)] + v.turn, v.weight});
        }
        if (predictions.empty()) continue;
        double& h = heading[static_cast<std::size_t>(i)];
        if (median_step) {
          double best = 1e300;
          for (const auto& [candidate, unused] : predictions) {
            double cost = 0;
            for (const auto& [p, w] : predictions) cost += w * std::abs(wrap_angle(p - candidate));
            if (cost < best) {
              best = cost;
              h = wrap_angle(candidate);
            }
          }
        } else {
          std::complex<double> sum = 0;
          for (const auto& [p, w] : predictions) {
            const double r = wrap_angle(p - h) / cauchy;
            sum += w / (1.0 + r * r) * std::polar(1.0, p);
          }
          if (std::abs(sum) > 0) h = std::arg(sum);
        }
      }
    }
    // Drop the edges that disagree, then once more from a tree of the rest.
    bool dropped = false;
    for (std::size_t e : order) {
      if (!(*kept)[e]) continue;
      const ViewEdge& v = edges[e];
      const double r = wrap_angle(heading[static_cast<std::size_t>(v.b)] -
                                  heading[static_cast<std::size_t>(v.a)] - v.turn);
      if (std::abs(r) > max_residual) {
        (*kept)[e] = false;
        dropped = true;
      }
    }
    if (!dropped) break;
  }
  return heading;
}

bool solve_positions(int still_count, const std::vector<int>& group, const std::vector<ViewEdge>& edges,
                     const std::vector<bool>& kept, const std::vector<double>& headings,
                     std::vector<Eigen::Vector2d>* positions, bool* scale_known) {
  positions->assign(static_cast<std::size_t>(still_count), Eigen::Vector2d::Zero());
  *scale_known = false;
  const int n = static_cast<int>(group.size());
  if (n < 2) return n == 1;
  std::vector<int> slot(static_cast<std::size_t>(still_count), -1);
  for (int k = 0; k < n; ++k) slot[static_cast<std::size_t>(group[static_cast<std::size_t>(k)])] = k;
  // Rows: for an edge with a length, the two components of (c_b - c_a) - L u = 0; for one without, the
  // component across u: n . (c_b - c_a) = 0. Unknowns: (x, y) of every still of the group.
  struct Row {
    int a, b;
    Eigen::Vector2d coefficient;
    double value, weight;
  };
  std::vector<Row> rows;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (!kept[e] || !edges[e].direction_known) continue;
    const ViewEdge& v = edges[e];
    const int a = slot[static_cast<std::size_t>(v.a)], b = slot[static_cast<std::size_t>(v.b)];
    if (a < 0 || b < 0) continue;
    const double angle = headings[static_cast<std::size_t>(v.a)] + v.direction;
    const Eigen::Vector2d u(std::cos(angle), std::sin(angle)), across(-u.y(), u.x());
    const double w = std::sqrt(v.weight);
    if (v.length > 0) {
      *scale_known = true;
      rows.push_back({a, b, u, v.length, w});
      rows.push_back({a, b, across, 0.0, w});
    } else {
      rows.push_back({a, b, across, 0.0, w});
    }
  }
  const int m = static_cast<int>(rows.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, 2 * n);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(m);
  for (int r = 0; r < m; ++r) {
    const Row& row = rows[static_cast<std::size_t>(r)];
    A(r, 2 * row.b) += row.weight * row.coefficient.x();
    A(r, 2 * row.b + 1) += row.weight * row.coefficient.y();
    A(r, 2 * row.a) -= row.weight * row.coefficient.x();
    A(r, 2 * row.a + 1) -= row.weight * row.coefficient.y();
    y(r) = row.weight * row.value;
  }
  Eigen::VectorXd c;
  if (*scale_known) {
    // The group's first still at the origin: drop its two columns.
    const Eigen::MatrixXd Ar = A.rightCols(2 * n - 2);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Ar, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd s = svd.singularValues();
    if (s.size() < 2 * n - 2 || s(s.size() - 1) < 1e-6 * s(0)) return false;
    c = Eigen::VectorXd::Zero(2 * n);
    c.tail(2 * n - 2) = svd.solve(y);
  } else {
    // Directions only: the smallest eigenvector orthogonal to the two translations, unit norm, its sign the
    // one that puts b ahead of a along most edges.
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(2 * n, 2);
    for (int k = 0; k < n; ++k) {
      T(2 * k, 0) = 1.0 / std::sqrt(n);
      T(2 * k + 1, 1) = 1.0 / std::sqrt(n);
    }
    const Eigen::MatrixXd P = Eigen::MatrixXd::Identity(2 * n, 2 * n) - T * T.transpose();
    const Eigen::MatrixXd L = P * (A.transpose() * A) * P;
    const double big = std::max(1.0, L.trace());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(L + big * T * T.transpose());
    const Eigen::VectorXd values = eig.eigenvalues();
    // A second shape that fits the directions as well: the positions are not fixed by them.
    if (values.size() < 2 || values(1) < 1e-9 * big) return false;
    c = eig.eigenvectors().col(0) * std::sqrt(static_cast<double>(n));
    double ahead = 0;
    for (const Row& row : rows) {
      const Eigen::Vector2d u(row.coefficient.y(), -row.coefficient.x());  // across = perp(u)
      ahead += u.dot(Eigen::Vector2d(c(2 * row.b) - c(2 * row.a), c(2 * row.b + 1) - c(2 * row.a + 1)));
    }
    if (ahead < 0) c = -c;
    const Eigen::Vector2d first(c(0), c(1));
    for (int k = 0; k < n; ++k) c.segment<2>(2 * k) -= first;
  }
  for (int k = 0; k < n; ++k)
    (*positions)[static_cast<std::size_t>(group[static_cast<std::size_t>(k)])] = c.segment<2>(2 * k);
  return true;
}

bool solve_positions_robust(int still_count, const std::vector<int>& group, std::vector<ViewEdge> edges,
                            std::vector<bool>* kept, const std::vector<double>& headings,
                            double max_direction_residual_deg, double max_length_residual,
                            std::vector<Eigen::Vector2d>* positions, bool* scale_known) {
  if (!solve_positions(still_count, group, edges, *kept, headings, positions, scale_known)) return false;
  const double max_angle = max_direction_residual_deg * M_PI / 180.0;
  std::vector<char> tried(edges.size(), 0);  // removal of this edge left the positions unfixed
  for (std::size_t round = 0; round < edges.size(); ++round) {
    // The worst edge by its residual relative to its threshold.
    double worst = 1.0;
    int worst_edge = -1;
    bool worst_is_length = false;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const ViewEdge& v = edges[e];
      if (!(*kept)[e] || !v.direction_known || tried[e]) continue;
      const Eigen::Vector2d d =
          (*positions)[static_cast<std::size_t>(v.b)] - (*positions)[static_cast<std::size_t>(v.a)];
      if (d.norm() == 0) continue;
      const double angle = std::abs(
          wrap_angle(std::atan2(d.y(), d.x()) - headings[static_cast<std::size_t>(v.a)] - v.direction));
      if (angle / max_angle > worst) {
        worst = angle / max_angle;
        worst_edge = static_cast<int>(e);
        worst_is_length = false;
      }
      if (v.length > 0 && *scale_known) {
        const double r = std::abs(d.norm() / v.length - 1.0) / max_length_residual;
        if (r > worst) {
          worst = r;
          worst_edge = static_cast<int>(e);
          worst_is_length = true;
        }
      }
    }
    if (worst_edge < 0) return true;
    const std::size_t e = static_cast<std::size_t>(worst_edge);
    const ViewEdge before = edges[e];
    if (worst_is_length)
      edges[e].length = 0.0;
    else
      (*kept)[e] = false;
    std::vector<Eigen::Vector2d> trial;
    bool trial_scale = false;
    if (solve_positions(still_count, group, edges, *kept, headings, &trial, &trial_scale)) {
      *positions = trial;
      *scale_known = trial_scale;
    } else {
      edges[e] = before;
      (*kept)[e] = true;
      tried[e] = 1;
    }
  }
  return true;
}

}  // namespace plenopath
