#pragma once
// Keyframes without a floor plan, from depth panoramas (the seed's fallback for complex scenes): cells
// begin where the depth-based volume changes significantly (processing/sampling/depth_volume.h), each cell's
// size is its mean star volume V (m^3), and the cells get keyframes by the same l^e / v rule (cell_rule.h;
// with V in m^3, the seed's exponent 3 makes l^3 / V dimensionless). Like the visibility sampler, the
// keyframes are then moved by the loss they cause (loss_refinement.h), with each frame's envelope read from
// its own depth map: the ranges along the horizon row, around the frame's pose. No plan is needed.
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"
#include "processing/sampling/cell_rule.h"
#include "processing/sampling/depth_volume.h"
#include "processing/sampling/sampling_loss.h"

namespace plenopath {

struct DepthSamplingOptions {
  VolumeChangeOptions changes;  // what counts as a significant change of volume
  CellRuleOptions cells;        // window and size floor (exponent and boost come from SamplingParameters)
  int max_depth_width = 256;    // depth maps are shrunk to at most this width before integrating (speed)
  bool refine_by_loss = true;   // move keyframes by the loss on eye-level envelopes (when given)
  int refine_sweeps = 6;
  double raster_cell_m = 0.08;  // grid of the loss estimate (envelope_raster.h)
  void check() const;           // throws plenopath::Error saying which field is wrong
};

// The envelope at eye level seen in a depth panorama (CV_32F metres, 0 = no hit) taken at `pose`: for each
// column, the nearer of the two rows astride the horizon, placed at world angle heading - azimuth
// (rig/spherical.h). Columns with no hit are left out; status outside when fewer than 3 columns hit.
Envelope envelope_from_depth(const cv::Mat& depth, const PathFrame& pose);

// The volume of every path frame: read_depth(capture index) gives its depth map (CV_32F metres or CV_16U
// millimetres, 0 = no hit; may throw Error). Also each frame's eye-level envelope when `envelopes` is
// given. `progress` gets the fraction done; a cancel ends it with Cancelled.
std::vector<DepthVolume> depth_volumes_along_path(const CameraPath& path,
                                                  const std::function<cv::Mat(int index)>& read_depth,
                                                  const DepthSamplingOptions& options = {},
                                                  Progress& progress = null_progress(),
                                                  PathEnvelopes* envelopes = nullptr);

// One frame's part of depth_volumes_along_path: its volume, and its eye-level envelope when `envelope` is
// given (the depth shrunk to max_depth_width first). For callers whose depth comes frame by frame.
DepthVolume summarise_depth(cv::Mat depth, const PathFrame& pose, const DepthSamplingOptions& options,
                            Envelope* envelope = nullptr);

// Cells between significant changes: a change detected at frame k starts a new cell halfway between
// frames k-1 and k. Size = mean star volume of the cell's frames with enough coverage (the neighbouring
// cell's when none has). volumes: one per path frame.
std::vector<SamplingCell> sampling_cells_from_depth(const CameraPath& path,
                                                    const std::vector<DepthVolume>& volumes,
                                                    const DepthSamplingOptions& options = {});

// eye_level: every frame's envelope from its depth map (depth_volumes_along_path); without it (or with
// refine_by_loss off) the keyframes stay where the cell rule put them.
Keyframes sample_by_depth(const CameraPath& path, const std::vector<DepthVolume>& volumes,
                          const SamplingParameters& parameters, const std::vector<int>& pinned,
                          const DepthSamplingOptions& options = {}, const PathEnvelopes* eye_level = nullptr);

}  // namespace plenopath
