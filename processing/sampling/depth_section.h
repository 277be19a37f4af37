#pragma once
// A floor plan from depth panoramas, for a scene that comes without one (issue 23: "the plan can be the
// DXF, or a section of the scene cut at eye height"): the scene cut at the camera's height, as the path saw
// it. Each frame's horizon rows say where sight stops in every direction (as envelope_from_depth reads
// them). The space the frames saw through is free; the surfaces where sight stopped bound it (neighbouring
// columns whose distances agree are joined as one surface, a silhouette is not, so a wall with no
// thickness still parts the rooms on its two sides). The free space's boundary, traced along those
// surfaces on a raster, is the plan: each room (or rooms joined by open doors) one closed outline, each
// pillar or piece of furniture seen from around it one more. Its sides along surfaces are walls (layer
// `layer`); the rest is where the frames' sight ended at its side (past a door jamb, round a corner) or at
// max_range_m, the limit of what the path saw (layer `layer`-UNSEEN); both block sight, so the free space
// stays closed. So visibility, cells, sampling and the tour's map work on an author's scene as on a DXF
// plan; what the path never saw is not in it.
#include <Eigen/Core>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/camera_path.h"
#include "model/floor_plan.h"
#include "processing/util/progress.h"

namespace plenopath {

struct DepthSectionOptions {
  double cell_m = 0.05;           // raster cell: outlines lie within half a cell of the surfaces
  double max_range_m = 40.0;      // sight is taken to stop here when nothing nearer was hit
  double join_ratio = 0.08;       // adjacent columns are one surface when their distances differ by less
                                  // than this fraction (plus two cells)
  int max_columns = 1024;         // wider depth is read every k-th column: memory per frame stays bounded
                                  // (a long full-size render keeps every frame's sight until finish)
  double simplify_m = 0.03;       // outlines simplified to this tolerance (Douglas-Peucker)
  double min_outline_m = 0.15;    // pillars and holes smaller than this across are dropped (noise)
  std::string layer = "SECTION";  // the walls' layer (the unseen limit's is this + "-UNSEEN")
  void check() const;             // throws Error naming the bad field
};

struct DepthSection {
  FloorPlan plan;       // metres, the path's frame; the walls' layer and the unseen limit's, both occluders
  int frames_used = 0;  // frames with depth
  int free_cells = 0;   // raster cells seen through
};

// Gathers the frames one by one, for callers whose depth comes as it is rendered (the CG capture's passes).
class DepthSectionBuilder {
 public:
  explicit DepthSectionBuilder(const DepthSectionOptions& options = {});
  // depth: CV_32F metres or CV_16U millimetres, 0 = no hit; any width.
  void add(const cv::Mat& depth, const PathFrame& pose);
  // Throws Error when no frame had depth at eye level, or when the frames span more than 8 000 cells.
  DepthSection finish(Progress& progress = null_progress()) const;

 private:
  struct Frame {
    Eigen::Vector2d centre;
    std::vector<Eigen::Vector2d> sight;                  // where sight stops, every column, in order
    std::vector<std::vector<Eigen::Vector2d>> surfaces;  // runs of columns on one surface
  };
  DepthSectionOptions options_;
  std::vector<Frame> frames_;
};

// read_depth(capture index) gives the frame's depth (CV_32F metres or CV_16U millimetres, 0 = no hit), or an
// empty Mat when the frame has none. Throws Error when no frame has depth, or Cancelled.
DepthSection plan_from_depth_section(const CameraPath& path,
                                     const std::function<cv::Mat(int index)>& read_depth,
                                     const DepthSectionOptions& options = {},
                                     Progress& progress = null_progress());

}  // namespace plenopath
