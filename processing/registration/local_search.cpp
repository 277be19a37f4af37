// Registration, step 3b (registration.h): each start of the coarse search refined on the fine raster
// before ICP, by exhaustive search of rotations and shifts around it.
#include <algorithm>
#include <cmath>

#include "processing/registration/registration_internal.h"

namespace plenopath::registration_detail {

cv::Mat soft_wall_raster(const PlanRaster& plan, double tolerance_m) {
  cv::Mat soft(plan.distance.size(), CV_32F);
  for (int row = 0; row < soft.rows; ++row) {
    const float* d = plan.distance.ptr<float>(row);
    float* out = soft.ptr<float>(row);
    for (int col = 0; col < soft.cols; ++col) {
      const double u = d[col] / tolerance_m;
      out[col] = static_cast<float>(std::max(0.0, 1.0 - u * u));
    }
  }
  return soft;
}

Similarity2 local_search(const std::vector<Eigen::Vector2d>& points, const cv::Mat& soft,
                         const PlanRaster& plan, const Similarity2& start,
                         const RegistrationOptions& options) {
  if (points.empty() || options.local_search_deg <= 0) return start;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  const Eigen::Vector2d mean_at = start.apply(mean);
  const int turns = static_cast<int>(std::floor(options.local_search_deg / options.local_search_step_deg));
  const int reach = static_cast<int>(std::ceil(options.local_search_m / plan.cell));
  const int side = 2 * reach + 1;
  std::vector<float> sums(static_cast<std::size_t>(side * side));
  Similarity2 best = start;
  double best_sum = -1;
  for (int k = -turns; k <= turns; ++k) {
    Similarity2 turned = start;
    turned.rotation += k * options.local_search_step_deg * M_PI / 180;
    turned.translation += mean_at - turned.apply(mean);  // turned about where the points' mean lands
    std::fill(sums.begin(), sums.end(), 0.0f);
    for (const Eigen::Vector2d& p : points) {
      const Eigen::Vector2d q = turned.apply(p);
      const int col = static_cast<int>(std::floor((q.x() - plan.origin.x()) / plan.cell));
      const int row = static_cast<int>(std::floor((q.y() - plan.origin.y()) / plan.cell));
      for (int dy = -reach; dy <= reach; ++dy) {
        const int r = row + dy;
        if (r < 0 || r >= soft.rows) continue;
        const float* line = soft.ptr<float>(r);
        float* out = sums.data() + static_cast<std::size_t>((dy + reach) * side);
        const int first = std::max(-reach, -col), last = std::min(reach, soft.cols - 1 - col);
        for (int dx = first; dx <= last; ++dx) out[dx + reach] += line[col + dx];
      }
    }
    // Near-ties (a plain wall says nothing along it) go to the smallest move.
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        const double sum = sums[static_cast<std::size_t>((dy + reach) * side + dx + reach)] -
                           1e-3 * (dx * dx + dy * dy + k * k);
        if (sum <= best_sum) continue;
        best_sum = sum;
        best = turned;
        best.translation += plan.cell * Eigen::Vector2d(dx, dy);
      }
  }
  return best;
}

}  // namespace plenopath::registration_detail
