#pragma once
// Fast estimate of the geometric loss between any two frames of a path: every frame's envelope is
// rasterised once onto a common grid (bit masks), and 1 - IoU of two frames is a popcount. Exact IoU
// (polygon_iou.h) costs ~0.3 ms a pair; this costs ~1 us, which lets the visibility sampler search keyframe
// positions by the loss they would cause. The estimate's error is about a cell's width along the envelopes'
// boundaries (a few per cent for rooms of a few metres at 8 cm cells).
#include <cstdint>
#include <vector>

#include "processing/sampling/sampling_loss.h"

namespace plenopath {

class EnvelopeRaster {
 public:
  // cell_m: wanted grid cell (metres); grown so the grid has at most max_cells cells.
  EnvelopeRaster(const PathEnvelopes& envelopes, double cell_m = 0.08, int max_cells = 60000);

  int frames() const { return static_cast<int>(count_.size()); }
  double cell_m() const { return cell_; }
  // 1 - |Ei ∩ Ej| / |Ei ∪ Ej| of the rasterised envelopes of path frames i and j; 0 when neither has an
  // envelope, 1 when only one has.
  double loss(int i, int j) const;

 private:
  double cell_ = 0.1;
  double x0_ = 0.0, y0_ = 0.0;
  int columns_ = 0, rows_ = 0, words_per_row_ = 0;
  std::vector<std::uint64_t> bits_;         // frame-major, then row-major words
  std::vector<int> count_;                  // set cells per frame (-1 = no envelope)
  std::vector<int> row_begin_, row_end_;    // rows holding set cells per frame [begin, end)
  std::vector<int> word_begin_, word_end_;  // words (within a row) holding set cells per frame [begin, end)
};

}  // namespace plenopath
