#include "processing/sampling/depth_sampler.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "processing/sampling/keyframe_placement.h"

namespace plenopath {

void DepthSamplingOptions::check() const {
  changes.check();
  cells.check();
  if (max_depth_width < 8) throw Error("depth sampling: max depth width must be >= 8");
}

std::vector<DepthVolume> depth_volumes_along_path(const CameraPath& path,
                                                  const std::function<cv::Mat(int index)>& read_depth,
                                                  const DepthSamplingOptions& options,
                                                  const std::function<void(double)>& progress) {
  options.check();
  std::vector<DepthVolume> out;
  out.reserve(path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    cv::Mat depth = read_depth(path.frames[i].index);
    if (depth.type() == CV_16U) depth.convertTo(depth, CV_32F, 0.001);  // millimetres -> metres, 0 stays 0
    if (depth.cols > options.max_depth_width) {
      // Nearest, not area: averaging a hit with a no-hit (0) would invent short ranges at silhouettes.
      cv::Mat small;
      cv::resize(depth, small, cv::Size(options.max_depth_width, std::max(1, depth.rows * options.max_depth_width / depth.cols)),
                 0, 0, cv::INTER_NEAREST);
      depth = small;
    }
    out.push_back(depth_volume(depth));
    if (progress && (i % 16 == 0 || i + 1 == path.size())) progress(static_cast<double>(i + 1) / path.size());
  }
  return out;
}

std::vector<SamplingCell> sampling_cells_from_depth(const CameraPath& path, const std::vector<DepthVolume>& volumes,
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
      if (volumes[i].covered_solid_angle >= covered && volumes[i].star_volume > 0.0) sum += volumes[i].star_volume, ++count;
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
                          const DepthSamplingOptions& options_in) {
  DepthSamplingOptions options = options_in;
  options.cells.exponent = parameters.exponent;
  options.cells.transition_boost = parameters.transition_boost;
  options.check();
  check_sampling_parameters(parameters);
  const std::vector<SamplingCell> cells = sampling_cells_from_depth(path, volumes, options);
  Keyframes k = place_keyframes(path, cell_rule_density(cells, path.length(), options.cells), parameters, pinned);
  k.parameters.method = "depth";
  return k;
}

}  // namespace plenopath
