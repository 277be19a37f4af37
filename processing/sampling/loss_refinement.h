#pragma once
// Keyframes placed by the loss they cause. Given the per-frame loss estimate (envelope_raster.h), a
// keyframe set (positions in path.frames) is improved by coordinate descent: each movable keyframe in turn
// moves to the frame between its neighbours that minimises the summed loss of the frames it and they stand
// in for (a dropped frame's stand-in is the nearest keyframe along the path). Then the keyframes are ranked
// coarse to fine by backward elimination: repeatedly the keyframe whose removal adds the least loss is
// taken out; the reverse of that order is the progressive order, so every prefix is a low-loss sampling of
// its size.
#include <functional>
#include <vector>

#include "model/camera_path.h"
#include "model/keyframes.h"
#include "processing/sampling/envelope_raster.h"
#include "processing/util/progress.h"

namespace plenopath {

struct LossRefinementOptions {
  int sweeps = 6;              // passes over all keyframes (stops early when nothing moves)
  int coarse_candidates = 24;  // positions tried per keyframe before the fine search around the best
  double min_spacing_m = 0.0;  // moves keep these (0 = none)
  double max_spacing_m = 0.0;
  void check() const;  // throws plenopath::Error saying which field is wrong
};

// Summed loss of the frames strictly between keyframes a < b (each against the nearer of the two by arc
// length, ties to a).
double interval_loss(const EnvelopeRaster& raster, const std::vector<double>& arc_lengths, int a, int b);

// positions: ascending positions in path.frames; fixed: same size, true = never moved (first, last, pinned).
// Returns the improved positions (same count, ascending, fixed ones unchanged). A cancel ends it with
// Cancelled.
std::vector<int> refine_by_loss(const EnvelopeRaster& raster, const std::vector<double>& arc_lengths,
                                std::vector<int> positions, const std::vector<bool>& fixed,
                                const LossRefinementOptions& options = {},
                                Progress& progress = null_progress());

// Progressive rank per keyframe: first and last, then the other fixed ones, then the reverse of backward
// elimination by least added loss.
std::vector<int> loss_ranks(const EnvelopeRaster& raster, const std::vector<double>& arc_lengths,
                            const std::vector<int>& positions, const std::vector<bool>& fixed);

// The whole step on a keyframe set: first, last and `pinned` stay; keyframes move (refine_by_loss with
// `options`) and are re-ranked (loss_ranks). The budget and parameters are kept.
Keyframes refine_keyframes_by_loss(const CameraPath& path, const Keyframes& keyframes,
                                   const std::vector<int>& pinned, const EnvelopeRaster& raster,
                                   const LossRefinementOptions& options = {},
                                   Progress& progress = null_progress());

}  // namespace plenopath
