#include "processing/sampling/depth_sampler.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "processing/sampling/envelope_raster.h"
#include "processing/sampling/keyframe_placement.h"
#include "processing/sampling/loss_refinement.h"

namespace plenopath {

void DepthSamplingOptions::check() const {
  changes.check();
  cells.check();
  if (max_depth_width < 8) throw Error("depth sampling: max depth width must be >= 8");
  if (refine_sweeps < 0) throw Error("depth sampling: refine sweeps must be >= 0");
  if (!(raster_cell_m > 0.0)) throw Error("depth sampling: raster cell must be > 0 m");
}

Envelope envelope_from_depth(const cv::Mat& depth, const PathFrame& pose) {
  if (depth.empty() || depth.type() != CV_32F)
    throw Error("envelope from depth: CV_32F depth in metres expected");
  Envelope e;
  const int w = depth.cols, h = depth.rows;
  const int upper = std::max(0, h / 2 - 1), lower = std::min(h - 1, h / 2);
  for (int u = 0; u < w; ++u) {
    float d = 0.0f;
    for (int v : {upper, lower}) {
      const float r = depth.at<float>(v, u);
      if (std::isfinite(r) && r > 0.0f && (d == 0.0f || r < d)) d = r;
    }
    if (d == 0.0f) continue;
    const double azimuth = (u + 0.5) / w * 2.0 * M_PI - M_PI;
    const double world = pose.heading - azimuth;
    e.polygon.push_back(pose.position() + d * Eigen::Vector2d(std::cos(world), std::sin(world)));
  }
  if (e.polygon.size() < 3) {
    e.polygon.clear();
    return e;
  }
  std::reverse(e.polygon.begin(),
               e.polygon.end());  // columns run clockwise: counter-clockwise as envelopes are
  double twice = 0.0;
  for (std::size_t i = 0; i < e.polygon.size(); ++i) {
    const auto& a = e.polygon[i];
    const auto& b = e.polygon[(i + 1) % e.polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  e.area = 0.5 * std::abs(twice);
  e.status = EnvelopeStatus::ok;
  return e;
}

std::vector<DepthVolume> depth_volumes_along_path(const CameraPath& path,
                                                  const std::function<cv::Mat(int index)>& read_depth,
                                                  const DepthSamplingOptions& options, Progress& progress,
                                                  PathEnvelopes* envelopes) {
  options.check();
  std::vector<DepthVolume> out;
  out.reserve(path.size());
  if (envelopes) envelopes->frames.assign(path.size(), Envelope{});
  for (std::size_t i = 0; i < path.size(); ++i) {
    out.push_back(summarise_depth(read_depth(path.frames[i].index), path.frames[i], options,
                                  envelopes ? &envelopes->frames[i] : nullptr));
    if (i % 16 == 0 || i + 1 == path.size()) progress.checkpoint(static_cast<double>(i + 1) / path.size());
  }
  return out;
}

DepthVolume summarise_depth(cv::Mat depth, const PathFrame& pose, const DepthSamplingOptions& options,
                            Envelope* envelope) {
  if (depth.type() == CV_16U) depth.convertTo(depth, CV_32F, 0.001);  // millimetres -> metres, 0 stays 0
  if (depth.cols > options.max_depth_width) {
    // Nearest, not area: averaging a hit with a no-hit (0) would invent short ranges at silhouettes.
    cv::Mat small;
    cv::resize(
        depth, small,
        cv::Size(options.max_depth_width, std::max(1, depth.rows * options.max_depth_width / depth.cols)), 0,
        0, cv::INTER_NEAREST);
    depth = small;
  }
  if (envelope) *envelope = envelope_from_depth(depth, pose);
  return depth_volume(depth);
}

std::vector<SamplingCell> sampling_cells_from_depth(const CameraPath& path,
                                                    const std::vector<DepthVolume>& volumes,
                                                    const DepthSamplingOptions& options) {
  options.check();
  if (volumes.size() != path.size())
    throw Error("depth sampling: " + std::to_string(volumes.size()) + " depth volumes for a path of " +
                std::to_string(path.size()) + " frames");
  const std::vector<double> s = path.arc_lengths();
  std::vector<int> starts = detect_volume_changes(volumes, options.changes);  // frame positions
  starts.insert(starts.begin(), 0);
  std::vector<SamplingCell> cells;
  const double covered = options.changes.min_coverage * 4.0 * M_PI;
  for (std::size_t c = 0; c < starts.size(); ++c) {
    const int first = starts[c];
    const int end = c + 1 < starts.size() ? starts[c + 1] : static_cast<int>(path.size());  // exclusive
    SamplingCell cell;
    cell.s_begin = first == 0 ? 0.0 : 0.5 * (s[first - 1] + s[first]);
    cell.s_end = end == static_cast<int>(path.size()) ? s.back() : 0.5 * (s[end - 1] + s[end]);
    double sum = 0.0;
    int count = 0;
    for (int i = first; i < end; ++i)
      if (volumes[i].covered_solid_angle >= covered && volumes[i].star_volume > 0.0)
        sum += volumes[i].star_volume, ++count;
    cell.size = count > 0 ? sum / count : 0.0;
    cells.push_back(cell);
  }
  // Cells with no usable depth borrow their neighbour's size.
  for (std::size_t c = 1; c < cells.size(); ++c)
    if (!(cells[c].size > 0.0)) cells[c].size = cells[c - 1].size;
  for (std::size_t c = cells.size(); c-- > 1;)
    if (!(cells[c - 1].size > 0.0)) cells[c - 1].size = cells[c].size;
  return cells;
}

Keyframes sample_by_depth(const CameraPath& path, const std::vector<DepthVolume>& volumes,
                          const SamplingParameters& parameters, const std::vector<int>& pinned,
                          const DepthSamplingOptions& options_in, const PathEnvelopes* eye_level) {
  DepthSamplingOptions options = options_in;
  options.cells.exponent = parameters.exponent;
  options.cells.transition_boost = parameters.transition_boost;
  options.check();
  check_sampling_parameters(parameters);
  const std::vector<SamplingCell> cells = sampling_cells_from_depth(path, volumes, options);
  Keyframes k =
      place_keyframes(path, cell_rule_density(cells, path.length(), options.cells), parameters, pinned);
  k.parameters.method = SamplingMethod::kDepth;
  k.sampler.cell_rule = {options.cells.transition_window_m, options.cells.min_size};
  k.sampler.depth_changes = {options.changes.log_ratio_threshold, options.changes.use_mean_range,
                             options.changes.min_coverage, options.max_depth_width};
  if (!options.refine_by_loss || !eye_level || eye_level->frames.size() != path.size()) return k;
  const EnvelopeRaster raster(*eye_level, options.raster_cell_m);
  LossRefinementOptions refine;
  refine.sweeps = options.refine_sweeps;
  refine.min_spacing_m = parameters.min_spacing_m;
  refine.max_spacing_m = parameters.max_spacing_m;
  k = refine_keyframes_by_loss(path, k, pinned, raster, refine);
  k.sampler.refinement = {true, options.refine_sweeps, raster.cell_m()};
  return k;
}

}  // namespace plenopath
