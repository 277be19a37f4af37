#pragma once
// Least-squares 2-D similarity (scale, rotation, translation) taking estimated positions onto true ones,
// closed form on complex numbers: with centred points z (estimate) and w (truth), w ~ a z, a = sum(conj(z) w)
// / sum(|z|^2). For comparing a solution to ground truth up to the gauge a solver cannot see.
#include <Eigen/Core>
#include <complex>
#include <vector>

namespace plenopath {

struct Similarity2d {
  double scale = 1.0, rotation = 0.0;  // radians, CCW
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();
  Eigen::Vector2d apply(const Eigen::Vector2d& p) const {
    const std::complex<double> a = std::polar(scale, rotation) * std::complex<double>(p.x(), p.y());
    return Eigen::Vector2d(a.real(), a.imag()) + translation;
  }
};

inline Similarity2d fit_similarity_2d(const std::vector<Eigen::Vector2d>& from,
                                      const std::vector<Eigen::Vector2d>& to) {
  std::complex<double> mz = 0, mw = 0;
  const double n = static_cast<double>(from.size());
  for (std::size_t k = 0; k < from.size(); ++k) {
    mz += std::complex<double>(from[k].x(), from[k].y()) / n;
    mw += std::complex<double>(to[k].x(), to[k].y()) / n;
  }
  std::complex<double> num = 0;
  double den = 0;
  for (std::size_t k = 0; k < from.size(); ++k) {
    const std::complex<double> z = std::complex<double>(from[k].x(), from[k].y()) - mz;
    const std::complex<double> w = std::complex<double>(to[k].x(), to[k].y()) - mw;
    num += std::conj(z) * w;
    den += std::norm(z);
  }
  const std::complex<double> a = den > 0 ? num / den : std::complex<double>(1.0, 0.0);
  Similarity2d s;
  s.scale = std::abs(a);
  s.rotation = std::arg(a);
  const std::complex<double> t = mw - a * mz;
  s.translation = Eigen::Vector2d(t.real(), t.imag());
  return s;
}

}  // namespace plenopath
