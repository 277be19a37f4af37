#include "processing/export/plan_svg_frame.h"

#include <algorithm>
#include <cmath>

namespace plenopath {

int PlanSvgFrame::width_px() const {
  return std::max(1, static_cast<int>(std::lround((hi.x() - lo.x()) * pixels_per_metre)));
}
int PlanSvgFrame::height_px() const {
  return std::max(1, static_cast<int>(std::lround((hi.y() - lo.y()) * pixels_per_metre)));
}

Eigen::Vector2d PlanSvgFrame::pixel(const Eigen::Vector2d& plan) const {
  return {(plan.x() - lo.x()) * pixels_per_metre, (hi.y() - plan.y()) * pixels_per_metre};
}

PlanSvgFrame plan_svg_frame(const FloorPlan& plan) {
  const PlanExtents e = plan.extents();
  const double margin = 0.5;
  PlanSvgFrame f;
  if (e.valid) {
    f.lo = e.min.array() - margin;
    f.hi = e.max.array() + margin;
  }
  const double larger = std::max(f.hi.x() - f.lo.x(), f.hi.y() - f.lo.y());
  f.pixels_per_metre = std::min(100.0, 4096.0 / larger);
  return f;
}

}  // namespace plenopath
