#include "widgets/map_pieces.h"

#include <algorithm>
#include <limits>

namespace plenopath::widgets {

CameraPath path_as_drawn(const CameraPath& path, const PlanExtents& plan_extents) {
  if (path.piece_count() == 1) return path;
  // What is placed: the plan and the placed pieces.
  Eigen::Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max()), hi = -lo;
  if (plan_extents.valid) {
    lo = plan_extents.min;
    hi = plan_extents.max;
  }
  for (const PathFrame& f : path.frames)
    if (path.piece_placed(f.piece)) {
      lo = lo.cwiseMin(f.position());
      hi = hi.cwiseMax(f.position());
    }
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector2d::Zero();
  const double margin = 1.0 + 0.1 * std::max(1.0, (hi - lo).maxCoeff());
  CameraPath out = path;
  double top = hi.y();  // the next unplaced piece's top edge
  for (int k = 0; k < path.piece_count(); ++k) {
    if (path.piece_placed(k)) continue;
    Eigen::Vector2d plo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max()), phi = -plo;
    for (const PathFrame& f : path.frames)
      if (f.piece == k) {
        plo = plo.cwiseMin(f.position());
        phi = phi.cwiseMax(f.position());
      }
    if (plo.x() > phi.x()) continue;
    const Eigen::Vector2d shift(hi.x() + margin - plo.x(), top - phi.y());
    for (PathFrame& f : out.frames)
      if (f.piece == k) {
        f.x += shift.x();
        f.y += shift.y();
      }
    top -= (phi.y() - plo.y()) + margin;
  }
  return out;
}

std::array<unsigned char, 3> piece_colour(int piece) {
  // Dark, saturated and far from the cell palette's pastels, so a piece reads as a line of its own.
  static const std::array<std::array<unsigned char, 3>, 6> palette = {
      {{31, 119, 180}, {214, 39, 40}, {44, 160, 44}, {148, 103, 189}, {255, 127, 14}, {23, 190, 207}}};
  return palette[static_cast<std::size_t>(std::max(0, piece)) % palette.size()];
}

}  // namespace plenopath::widgets
