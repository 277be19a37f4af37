#include "processing/egomotion/path_evaluation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "model/error.h"

namespace plenopath {

Eigen::Vector2d Similarity2::apply(const Eigen::Vector2d& p) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  return scale * Eigen::Vector2d(c * p.x() - s * p.y(), s * p.x() + c * p.y()) + translation;
}

Similarity2 align_similarity(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& to,
                             bool fix_scale) {
  if (from.size() != to.size() || from.size() < 2) throw Error("alignment: need two or more matched points");
  const double n = static_cast<double>(from.size());
  Eigen::Vector2d mf = Eigen::Vector2d::Zero(), mt = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < from.size(); ++i) {
    mf += from[i];
    mt += to[i];
  }
  mf /= n;
  mt /= n;
  // In 2-D the optimal proper rotation has a closed form: angle of sum(conj(f) * t) in complex numbers.
  double re = 0.0, im = 0.0, var_from = 0.0;
  for (size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector2d f = from[i] - mf, t = to[i] - mt;
    re += f.x() * t.x() + f.y() * t.y();
    im += f.x() * t.y() - f.y() * t.x();
    var_from += f.squaredNorm();
  }
  Similarity2 s;
  s.rotation = std::atan2(im, re);
  s.scale = fix_scale || var_from <= 0.0 ? 1.0 : std::hypot(re, im) / var_from;
  s.translation = Eigen::Vector2d::Zero();
  s.translation = mt - s.apply(mf);
  return s;
}

PathErrors evaluate_path(const CameraPath& estimate, const CameraPath& truth) {
  std::vector<Eigen::Vector2d> from, to;
  std::vector<double> est_heading, true_heading;
  for (const PathFrame& t : truth.frames) {
    const PathFrame* e = estimate.find_frame(t.index);
    if (!e) continue;
    from.push_back(e->position());
    to.push_back(t.position());
    est_heading.push_back(e->heading);
    true_heading.push_back(t.heading);
  }
  if (from.size() < 2) throw Error("path evaluation: fewer than two frames of the estimate match the truth");
  PathErrors r;
  r.frames_matched = static_cast<int>(from.size());
  const Similarity2 s = align_similarity(from, to);
  double sum2 = 0.0;
  for (size_t i = 0; i < from.size(); ++i) {
    const double e = (s.apply(from[i]) - to[i]).norm();
    sum2 += e * e;
    r.ate_max_m = std::max(r.ate_max_m, e);
  }
  r.ate_rms_m = std::sqrt(sum2 / from.size());
  // Heading: an estimated heading turns with the aligning rotation. The position alignment may be
  // ill-defined (a straight path, all frames in one place), so the heading offset is fitted on its own.
  double sx = 0.0, sy = 0.0;
  for (size_t i = 0; i < est_heading.size(); ++i) {
    sx += std::cos(true_heading[i] - est_heading[i]);
    sy += std::sin(true_heading[i] - est_heading[i]);
  }
  const double offset = std::atan2(sy, sx);
  double h2 = 0.0;
  for (size_t i = 0; i < est_heading.size(); ++i) {
    const double e = wrap_angle(est_heading[i] + offset - true_heading[i]);
    h2 += e * e;
    r.rot_max_deg = std::max(r.rot_max_deg, std::abs(degrees(e)));
  }
  r.rot_rms_deg = degrees(std::sqrt(h2 / est_heading.size()));
  // A mirrored estimate aligns badly in position; its headings run the wrong way round, which the single
  // offset above cannot absorb either.
  double length = 0.0;
  for (size_t i = 1; i < to.size(); ++i) length += (to[i] - to[i - 1]).norm();
  r.truth_length_m = length;
  r.ate_pct = length > 0 ? 100.0 * r.ate_rms_m / length : 0.0;
  r.scale = s.scale;
  r.scale_error_pct = s.scale > 0 ? 100.0 * std::abs(1.0 / s.scale - 1.0) : 100.0;
  return r;
}

}  // namespace plenopath
