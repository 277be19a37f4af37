#pragma once
// Which layers block sight, proposed for the author to confirm: layer names first (model/layer_names.h);
// when no layer's name says "wall", the geometry: parallel line pairs 0.05-0.6 m apart (walls drawn as two
// lines), small closed outlines (columns), solid-filled regions (hatched walls and columns).
// A name that votes no is never proposed, with one exception: a wall pattern layer ("A-WALL-PATT",
// "Wandschraffur") whose solid fills are wall- or column-shaped, for plans that draw walls only as poche.
// When no name and no geometry finds walls (single-line plans), the layer holding most of the lines (at
// least half, not text or a hatch pattern) is proposed, saying so.
//
// Input: `plan` as the importer builds it: segments after clean-up (split and snapped, so outline edges
// are matched geometrically, within 2 mm), closed outlines kept whole, labels; all in metres.
#include <map>
#include <string>
#include <vector>

#include "model/floor_plan.h"

namespace plenopath {

struct OccluderProposal {
  std::string layer;
  bool occluder = false;
  std::string reason;  // "AIA wall layer", "412 parallel line pairs 0.1-0.3 m apart", ...
};

// `plan` in metres (segments and outlines filled, layers listed); `solid_fill_outlines` counts, per layer,
// the closed outlines that came from solid HATCH/SOLID entities. One proposal per layer of `plan.layers`.
std::vector<OccluderProposal> propose_occluder_layers(const FloorPlan& plan,
                                                      const std::map<std::string, int>& solid_fill_outlines);

}  // namespace plenopath
