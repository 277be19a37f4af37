// The global search of registration (registration.h, step 3): for each rotation, the score of every
// translation at once by FFT cross-correlation on the coarse raster,
//   score(k) = sum_j A[j] W[j + k]
// with A the wall points' raster (each point 1 / n) and W the plan's wall proximity; at the best few
// peaks of each rotation, the share of the path's frames off free space (N: the plan's share of cells off
// free space, 1 outside the plan) times free_space_weight is taken off.
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "processing/registration/registration_internal.h"

namespace plenopath::registration_detail {
namespace {

constexpr double kDeg = M_PI / 180.0;

double angle_distance(double a, double b) {
  double d = std::fmod(std::abs(a - b), 2 * M_PI);
  return std::min(d, 2 * M_PI - d);
}

}  // namespace

std::vector<Placement> distinct_placements(std::vector<Placement> all, const RegistrationOptions& options,
                                           int keep) {
  std::sort(all.begin(), all.end(), [](const Placement& a, const Placement& b) { return a.score > b.score; });
  std::vector<Placement> out;
  for (const Placement& p : all) {
    bool distinct = true;
    for (const Placement& q : out)
      if (angle_distance(p.transform.rotation, q.transform.rotation) < options.distinct_rotation_deg * kDeg &&
          (p.centre - q.centre).norm() < options.distinct_translation_m) {
        distinct = false;
        break;
      }
    if (!distinct) continue;
    out.push_back(p);
    if (static_cast<int>(out.size()) >= keep) break;
  }
  return out;
}

std::vector<Placement> global_search(const std::vector<Eigen::Vector2d>& wall_points,
                                     const std::vector<Eigen::Vector2d>& frames, const CoarseRaster& coarse,
                                     const std::vector<double>& plan_dirs, const RegistrationOptions& options,
                                     Progress& progress) {
  const double cell = coarse.cell;
  // Rotate about the wall points' centre; R bounds every point and frame around it.
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : wall_points) centre += p;
  centre /= static_cast<double>(wall_points.size());
  double radius = 0;
  for (const Eigen::Vector2d& p : wall_points) radius = std::max(radius, (p - centre).norm());
  for (const Eigen::Vector2d& f : frames) radius = std::max(radius, (f - centre).norm());
  const int rc = static_cast<int>(std::ceil(radius / cell)) + 1;  // the centre's cell in A and B
  const int cols = coarse.wall_proximity.cols, rows = coarse.wall_proximity.rows;
  // No wrap-around aliasing for the shifts that keep the centre on the plan: A spans [0, 2 rc].
  const int pc = cv::getOptimalDFTSize(cols + 4 * rc + 2), pr = cv::getOptimalDFTSize(rows + 4 * rc + 2);
  cv::Mat w(pr, pc, CV_32F, cv::Scalar(0));
  coarse.wall_proximity.copyTo(w(cv::Rect(0, 0, cols, rows)));
  cv::Mat fw;
  cv::dft(w, fw, 0, rows);
  auto not_free = [&](const Eigen::Vector2d& p) {
    const double x = std::floor((p.x() - coarse.origin.x()) / cell),
                 y = std::floor((p.y() - coarse.origin.y()) / cell);
    if (!(x >= 0 && y >= 0 && x < cols && y < rows)) return 1.0f;
    return coarse.not_free.at<float>(static_cast<int>(y), static_cast<int>(x));
  };

  // Rotations: the regular steps, and the dominant-direction alignments (with their neighbours).
  std::vector<double> rotations;
  for (double a = 0; a < 360 - 1e-9; a += options.rotation_step_deg) rotations.push_back(a * kDeg);
  if (options.dominant_directions && !plan_dirs.empty()) {
    const double pd = points_direction(wall_points);
    for (double d : plan_dirs)
      for (int quarter = 0; quarter < 4; ++quarter)
        for (double off : {-0.5, 0.0, 0.5}) rotations.push_back(d - pd + quarter * M_PI / 2 + off * kDeg);
  }
  // Scale 1 only: within +-3 % it moves a point 10 m from the centre by 30 cm, less than the proximity's
  // reach (two coarse cells); the refinement finds it.
  const std::vector<double> scales = {1.0};

  const double point_weight = 1.0 / wall_points.size();
  const double frame_weight = frames.empty() ? 0.0 : options.free_space_weight / frames.size();
  const int peaks_per_rotation = 4;
  const int suppress = std::max(1, static_cast<int>(std::ceil(options.distinct_translation_m / cell)));
  std::vector<Placement> all;
  cv::Mat a(pr, pc, CV_32F), fa, product, score;
  const std::size_t total = rotations.size() * scales.size();
  std::size_t done = 0;
  for (double s : scales)
    for (double rotation : rotations) {
      if (done % 16 == 0) progress.checkpoint(double(done) / total, "search");
      ++done;
      const double c = std::cos(rotation) * s, sn = std::sin(rotation) * s;
      a.setTo(0);
      for (const Eigen::Vector2d& p : wall_points) {
        const Eigen::Vector2d d = p - centre;
        const int x = static_cast<int>(std::floor((c * d.x() - sn * d.y()) / cell)) + rc;
        const int y = static_cast<int>(std::floor((sn * d.x() + c * d.y()) / cell)) + rc;
        a.at<float>(y, x) += static_cast<float>(point_weight);
      }
      cv::dft(a, fa, 0, 2 * rc + 1);
      cv::mulSpectrums(fw, fa, product, 0, true);
      cv::dft(product, score, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
      // Shifts k keeping the centre (cell rc of A) on the plan: plan cell rc + k in [0, cols) x [0, rows).
      cv::Mat valid(rows, cols, CV_32F);
      for (int y = 0; y < rows; ++y)
        for (int x = 0; x < cols; ++x) {
          const int kx = ((x - rc) % pc + pc) % pc, ky = ((y - rc) % pr + pr) % pr;
          valid.at<float>(y, x) = score.at<float>(ky, kx);
        }
      for (int peak = 0; peak < peaks_per_rotation; ++peak) {
        double best = 0;
        cv::Point at;
        cv::minMaxLoc(valid, nullptr, &best, nullptr, &at);
        if (!(best > -1e30)) break;
        // The centre (the corner of A's cell rc) lands on the corner of the plan's coarse cell `at`.
        Placement p;
        p.score = best;
        p.transform.scale = s;
        p.transform.rotation = std::remainder(rotation, 2 * M_PI);
        p.centre = coarse.origin + cell * Eigen::Vector2d(at.x, at.y);
        const Eigen::Vector2d rotated_centre(c * centre.x() - sn * centre.y(),
                                             sn * centre.x() + c * centre.y());
        p.transform.translation = p.centre - rotated_centre;
        double off = 0;
        for (const Eigen::Vector2d& f : frames) off += not_free(p.transform.apply(f));
        p.score -= frame_weight * off;
        all.push_back(p);
        cv::rectangle(valid, cv::Rect(at.x - suppress, at.y - suppress, 2 * suppress + 1, 2 * suppress + 1),
                      cv::Scalar(-1e31), cv::FILLED);
      }
    }
  progress.report(1.0, "search");
  return distinct_placements(std::move(all), options, options.refine_candidates);
}

}  // namespace plenopath::registration_detail
