#pragma once
// One DXF entity's tags to what the plan needs of it: its curves (exact, in the coordinate system of the
// block or model space holding it), a label, or a block reference. Each entity is validated on its own:
// a bad value throws DxfEntityError with the reason, and the importer skips just that entity.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "processing/plan/dxf_curves.h"
#include "processing/plan/dxf_tags.h"

namespace plenopath {

// The tags of one entity: from its "0 KIND" tag (included) to the next "0" (excluded).
struct DxfEntityTags {
  const DxfTag* begin = nullptr;
  const DxfTag* end = nullptr;
  const std::string& kind() const { return begin->value; }
  std::size_t line() const { return begin->line; }
};

struct DxfEntityError {
  std::string why;
};

struct DxfEntity {
  std::string kind;
  std::string layer = "0";
  std::size_t line = 0;
  bool paper_space = false;
  std::vector<DxfCurve> curves;  // geometry
  bool solid_fill = false;       // a solid HATCH, SOLID or TRACE: the curves are filled regions
  bool has_label = false;        // TEXT, MTEXT
  Eigen::Vector3d label_position = Eigen::Vector3d::Zero();
  std::string label_text;  // UTF-8, formatting removed
  double label_height = 0.0;
  std::string block;                   // INSERT: the block's name
  std::vector<Eigen::Affine3d> cells;  // INSERT: parent_from_block (block base already subtracted
                                       // by the caller), one per array cell
};

// nullptr for the kinds the importer reads; otherwise why a kind is left out ("dimension", "3-D only",
// "viewport", "image", "a point has no extent", "not plan geometry").
const char* dxf_skip_reason(const std::string& kind);

// `vertices` are the VERTEX entities that follow a POLYLINE (empty for every other kind). Strings in the
// tags are UTF-8 already. Throws DxfEntityError for an entity that cannot be drawn (a number that is not
// one, a radius of 0, coordinates beyond 1e12 units, a boundary whose counts do not add up, ...).
DxfEntity parse_dxf_entity(const DxfEntityTags& entity, const std::vector<DxfEntityTags>& vertices);

}  // namespace plenopath
