#pragma once
// Keyframes without a floor plan, from depth panoramas (the seed's fallback for complex scenes): cells
// begin where the depth-based volume changes significantly (processing/depth_volume.h), each cell's size is
// its mean star volume V (m^3), and the cells get keyframes by the same l^e / v rule (cell_rule.h; with
// V in m^3, the seed's exponent 3 makes l^3 / V dimensionless).
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"
#include "processing/depth_volume.h"
#include "processing/sampling/cell_rule.h"

namespace plenopath {

struct DepthSamplingOptions {
  VolumeChangeOptions changes;  // what counts as a significant change of volume
  CellRuleOptions cells;        // window and size floor (exponent and boost come from SamplingParameters)
  int max_depth_width = 256;    // depth maps are shrunk to at most this width before integrating (speed)
  void check() const;           // throws plenopath::Error saying which field is wrong
};

// The volume of every path frame: read_depth(capture index) gives its depth map (CV_32F metres or CV_16U
// millimetres, 0 = no hit; may throw Error). `progress` (optional) gets the fraction done and may throw.
std::vector<DepthVolume> depth_volumes_along_path(const CameraPath& path,
                                                  const std::function<cv::Mat(int index)>& read_depth,
                                                  const DepthSamplingOptions& options = {},
                                                  const std::function<void(double)>& progress = {});

// Cells between significant changes: a change detected at frame k starts a new cell halfway between
// frames k-1 and k. Size = mean star volume of the cell's frames with enough coverage (the neighbouring
// cell's when none has). volumes: one per path frame.
std::vector<SamplingCell> sampling_cells_from_depth(const CameraPath& path, const std::vector<DepthVolume>& volumes,
                                                    const DepthSamplingOptions& options = {});

Keyframes sample_by_depth(const CameraPath& path, const std::vector<DepthVolume>& volumes,
                          const SamplingParameters& parameters, const std::vector<int>& pinned,
                          const DepthSamplingOptions& options = {});

}  // namespace plenopath
