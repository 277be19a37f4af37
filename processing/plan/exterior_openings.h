#pragma once
// Openings in a building's outer walls (windows drawn as gaps, an open entrance, a slit where two wall
// outlines do not quite meet): the segments that close them. Without them the rooms behind such an opening
// are one face with the world outside, and to visibility and registration the building has no inside.
#include <vector>

#include "processing/plan/segment_grid.h"

namespace plenopath {

struct ExteriorOpeningOptions {
  // Gaps up to this wide (metres) are closed: a disc of this diameter rolled in from outside cannot pass
  // them, so what lies behind is inside. Wider gaps (a glass facade left open) stay open. 0 = close none.
  double max_opening_m = 3.0;
  // Cell of the raster the rolling-disc test runs on (metres); coarser on very large plans.
  double cell_m = 0.05;

  void check() const;  // throws plenopath::Error saying which field is wrong
};

// Segments between wall endpoints, at most max_opening_m long, crossing no wall, that separate the outside
// (where the rolled disc reaches) from space it cannot reach. Each opening gets one or a few (its inner and
// outer line); shortest first; none crosses another.
std::vector<Segment2> exterior_openings(const std::vector<Segment2>& walls,
                                        const ExteriorOpeningOptions& options = {});

}  // namespace plenopath
