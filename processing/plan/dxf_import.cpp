// DXF to FloorPlan in five stages: tags (ASCII or binary) with their strings decoded to UTF-8; sections
// into layers, blocks and model-space entities, each entity validated on its own; block expansion into
// placed curves (still exact, drawing units); units from the header or the drawing; then chords, strays,
// re-centring, metres, clean-up and the occluder proposal.
#include "processing/plan/dxf_import.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "model/error.h"
#include "processing/plan/dxf_cleanup.h"
#include "processing/plan/dxf_entities.h"
#include "processing/plan/dxf_tags.h"
#include "processing/plan/dxf_text.h"
#include "processing/plan/occluder_proposal.h"
#include "processing/plan/units_inference.h"
#include "processing/util/statistics.h"

namespace plenopath {

double metres_per_unit(const std::string& units) {
  static const std::map<std::string, double> table = {
      {"m", 1.0},       {"mm", 0.001},  {"cm", 0.01},   {"dm", 0.1},    {"km", 1000.0},
      {"um", 1e-6},     {"in", 0.0254}, {"ft", 0.3048}, {"yd", 0.9144}, {"mi", 1609.344},
      {"mil", 2.54e-5}, {"dam", 10.0},  {"hm", 100.0}};
  auto it = table.find(units);
  if (it == table.end())
    throw Error("unknown units '" + units + "' (use mm, cm, dm, m, km, um, in, ft, yd, mi)");
  return it->second;
}

std::string units_of_insunits(int insunits) {
  switch (insunits) {
    case 1:
      return "in";
    case 2:
      return "ft";
    case 3:
      return "mi";
    case 4:
      return "mm";
    case 5:
      return "cm";
    case 6:
      return "m";
    case 7:
      return "km";
    case 9:
      return "mil";
    case 10:
      return "yd";
    case 13:
      return "um";
    case 14:
      return "dm";
    case 15:
      return "dam";
    case 16:
      return "hm";
    default:
      return "";
  }
}

void DxfImportOptions::check() const {
  auto fail = [](const std::string& what) { throw Error("DXF import options: " + what); };
  if (!units_override.empty()) metres_per_unit(units_override);
  if (!(snap_tolerance_m >= 0.0 && snap_tolerance_m <= 0.1)) fail("snap_tolerance_m must be in [0, 0.1] m");
  if (!(chord_tolerance_m > 0.0 && chord_tolerance_m <= 1.0)) fail("chord_tolerance_m must be in (0, 1] m");
  if (!(single_line_wall_thickness_m > 0.0 && single_line_wall_thickness_m <= 0.5))
    fail("single_line_wall_thickness_m must be in (0, 0.5] m");
  if (!(recentre_beyond_m > 0.0)) fail("recentre_beyond_m must be positive");
  if (max_segments == 0) fail("max_segments must be positive");
}

namespace {

constexpr int kMaxBlockDepth = 32;

// ---------------------------------------------------------------------------------------------------------
// Stage 1: tags, the header's encoding and units, strings to UTF-8.

struct Header {
  std::string acadver, codepage;
  int insunits = -1;
};

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
  return s;
}

// "$VAR" (code 9) and the value tags that follow it, anywhere before the first entity section.
Header read_header(const std::vector<DxfTag>& tags) {
  Header h;
  for (std::size_t i = 0; i + 1 < tags.size(); ++i) {
    if (tags[i].code == 0 && (tags[i].value == "ENDSEC")) {
      if (!h.acadver.empty() || !h.codepage.empty() || h.insunits >= 0) break;  // the header is done
      continue;
    }
    if (tags[i].code != 9) continue;
    const DxfTag& v = tags[i + 1];
    if (tags[i].value == "$ACADVER" && v.code == 1) h.acadver = upper(v.value);
    if (tags[i].value == "$DWGCODEPAGE" && v.code == 3) h.codepage = v.value;
    if (tags[i].value == "$INSUNITS" && v.code == 70) {
      int u = -1;  // beyond int range: unknown (a fuzzer's 2.7e10 was undefined behaviour cast)
      if (dxf_integer(v, &u)) h.insunits = u;
    }
  }
  return h;
}

void decode_strings(std::vector<DxfTag>* tags, const std::string& encoding) {
  for (DxfTag& t : *tags)
    if (dxf_value_type(t.code) == DxfValueType::string)
      t.value = dxf_decode_unicode_escapes(dxf_to_utf8(t.value, encoding));
}

// ---------------------------------------------------------------------------------------------------------
// Stage 2: sections.

struct Block {
  std::string name;
  std::size_t line = 0;
  Eigen::Vector3d base = Eigen::Vector3d::Zero();
  bool external = false;  // an external reference: its content lives in another file
  std::vector<DxfEntity> entities;
};

struct Drawing {
  std::map<std::string, PlanLayer> layers;
  std::map<std::string, Block> blocks;
  std::vector<DxfEntity> model;            // model-space entities that parsed
  std::map<std::string, int> block_skips;  // reason -> count, inside blocks
};

struct Section {
  std::string name;
  std::size_t begin = 0, end = 0;  // tag indices of its content
};

std::vector<Section> find_sections(const std::vector<DxfTag>& tags) {
  std::vector<Section> sections;
  bool open = false;
  for (std::size_t i = 0; i < tags.size(); ++i) {
    if (tags[i].code != 0) continue;
    const std::string& v = tags[i].value;
    if (v == "SECTION") {
      if (open) sections.back().end = i;  // SECTION inside a section: the first one ends here
      Section s;
      if (i + 1 < tags.size() && tags[i + 1].code == 2) {
        s.name = upper(tags[i + 1].value);
        ++i;
      }
      s.begin = i + 1;
      s.end = tags.size();
      sections.push_back(s);
      open = true;
    } else if ((v == "ENDSEC" || v == "EOF") && open) {
      sections.back().end = i;
      open = false;
    }
  }
  if (sections.empty()) sections.push_back({"ENTITIES", 0, tags.size()});  // bare entities, no sections
  return sections;
}

// The entities of [begin, end): each from a code-0 tag to the next.
std::vector<DxfEntityTags> split_entities(const std::vector<DxfTag>& tags, std::size_t begin,
                                          std::size_t end) {
  std::vector<DxfEntityTags> out;
  std::size_t i = begin;
  while (i < end && tags[i].code != 0) ++i;
  while (i < end) {
    std::size_t j = i + 1;
    while (j < end && tags[j].code != 0) ++j;
    out.push_back({&tags[i], &tags[0] + j});
    i = j;
  }
  return out;
}

void read_layers(const std::vector<DxfTag>& tags, const Section& s, Drawing* d) {
  for (const DxfEntityTags& e : split_entities(tags, s.begin, s.end)) {
    if (e.kind() != "LAYER") continue;
    PlanLayer layer;
    int colour = 7, flags = 0;
    for (const DxfTag* t = e.begin + 1; t != e.end; ++t) {
      if (t->code == 2) layer.name = t->value;
      if (t->code == 62) dxf_integer(*t, &colour);
      if (t->code == 70) dxf_integer(*t, &flags);
    }
    if (layer.name.empty()) continue;
    layer.color = std::abs(std::clamp(colour, -256, 256));  // abs(INT_MIN) would overflow
    layer.visible = colour >= 0 && !(flags & 1);
    d->layers[layer.name] = layer;
  }
}

struct Skips {
  DxfImportReport* report;
  void model(const std::string& kind, const std::string& layer, std::size_t line, const std::string& why) {
    ++report->entities_skipped;
    ++report->skipped_by_kind[kind];
    if (report->skipped.size() < DxfImportReport::max_listed_skips)
      report->skipped.push_back({line, kind, layer, why});
  }
};

// The entities of an ENTITIES section or of one block, parsed. POLYLINE takes the VERTEX entities that
// follow it; the ATTRIBs after an INSERT and every SEQEND are consumed here.
template <typename OnEntity, typename OnSkip>
void read_entities(const std::vector<DxfEntityTags>& entities, std::size_t from, std::size_t to,
                   OnEntity on_entity, OnSkip on_skip) {
  for (std::size_t i = from; i < to; ++i) {
    const DxfEntityTags& e = entities[i];
    const std::string& kind = e.kind();
    if (kind == "SEQEND" || kind == "VERTEX") continue;
    std::vector<DxfEntityTags> vertices;
    if (kind == "POLYLINE")
      while (i + 1 < to && entities[i + 1].kind() == "VERTEX") vertices.push_back(entities[++i]);
    if (kind == "INSERT")
      while (i + 1 < to && entities[i + 1].kind() == "ATTRIB") ++i;
    std::string layer = "0";
    for (const DxfTag* t = e.begin + 1; t != e.end; ++t)
      if (t->code == 8) {
        layer = t->value.empty() ? "0" : t->value;
        break;
      }
    if (const char* why = dxf_skip_reason(kind)) {
      on_skip(kind, layer, e.line(), why);
      continue;
    }
    try {
      on_entity(parse_dxf_entity(e, vertices));
    } catch (const DxfEntityError& err) {
      on_skip(kind, layer, e.line(), err.why);
    }
  }
}

void read_blocks(const std::vector<DxfTag>& tags, const Section& s, Drawing* d, DxfImportReport* report) {
  const std::vector<DxfEntityTags> entities = split_entities(tags, s.begin, s.end);
  for (std::size_t i = 0; i < entities.size(); ++i) {
    if (entities[i].kind() != "BLOCK") continue;
    Block block;
    block.line = entities[i].line();
    int flags = 0;
    Eigen::Vector3d base = Eigen::Vector3d::Zero();
    for (const DxfTag* t = entities[i].begin + 1; t != entities[i].end; ++t) {
      double v = 0.0;
      if (t->code == 2 || (t->code == 3 && block.name.empty())) block.name = t->value;
      if (t->code == 70) dxf_integer(*t, &flags);
      if (t->code >= 10 && t->code <= 30 && t->code % 10 == 0 && dxf_number(*t, &v) && std::abs(v) < 1e12)
        base[(t->code - 10) / 10] = v;
    }
    block.base = base;
    block.external = (flags & (4 | 8)) != 0;
    std::size_t j = i + 1;
    while (j < entities.size() && entities[j].kind() != "ENDBLK" && entities[j].kind() != "BLOCK") ++j;
    read_entities(
        entities, i + 1, j, [&](DxfEntity e) { block.entities.push_back(std::move(e)); },
        [&](const std::string& kind, const std::string&, std::size_t, const std::string& why) {
          ++d->block_skips[kind + " (" + why + ")"];
        });
    i = (j < entities.size() && entities[j].kind() == "ENDBLK") ? j : j - 1;
    if (block.name.empty()) {
      report->warnings.push_back("line " + std::to_string(block.line) +
                                 ": a block without a name is ignored");
      continue;
    }
    if (d->blocks.count(block.name))
      report->warnings.push_back("line " + std::to_string(block.line) + ": block '" + block.name +
                                 "' is defined twice; the first definition is used");
    else
      d->blocks.emplace(block.name, std::move(block));
  }
}

// ---------------------------------------------------------------------------------------------------------
// Stage 3: block expansion.

struct PlacedCurve {
  const DxfCurve* curve;
  Eigen::Affine3d world_from_curve;
  std::string layer;
  int top;  // index of the model-space entity it came from
  bool solid_fill;
};

struct PlacedLabel {
  Eigen::Vector2d position;
  std::string text;
  double height;
  std::string layer;
  int top;
};

struct TooLarge {};

struct Expander {
  const Drawing& drawing;
  std::size_t max_curves;
  std::vector<PlacedCurve> curves;
  std::vector<PlacedLabel> labels;
  int expanded = 0;
  std::map<std::string, int> missing_blocks, cycles, external_blocks;
  std::vector<std::string> stack;

  static double xy_scale(const Eigen::Affine3d& t) {
    return std::sqrt(std::abs(t.linear().topLeftCorner<2, 2>().determinant()));
  }

  void place(const DxfEntity& e, const Eigen::Affine3d& world_from_parent, const std::string& layer, int top,
             int depth) {
    for (const DxfCurve& c : e.curves) {
      if (curves.size() >= max_curves) throw TooLarge{};
      curves.push_back({&c, world_from_parent * c.to_parent, layer, top, e.solid_fill});
    }
    if (e.has_label) {
      const Eigen::Vector3d p = world_from_parent * e.label_position;
      labels.push_back({p.head<2>(), e.label_text, e.label_height * xy_scale(world_from_parent), layer, top});
    }
    if (e.block.empty()) return;
    auto it = drawing.blocks.find(e.block);
    if (it == drawing.blocks.end()) {
      ++missing_blocks[e.block];
      return;
    }
    const Block& block = it->second;
    if (block.external) {
      ++external_blocks[e.block];
      return;
    }
    if (std::find(stack.begin(), stack.end(), e.block) != stack.end() || depth >= kMaxBlockDepth) {
      ++cycles[e.block];
      return;
    }
    stack.push_back(e.block);
    for (const Eigen::Affine3d& cell : e.cells) {
      ++expanded;
      const Eigen::Affine3d world_from_block = world_from_parent * cell * Eigen::Translation3d(-block.base);
      for (const DxfEntity& child : block.entities) {
        // Layer "0" inside a block takes the layer of the reference that places it.
        const std::string& child_layer = child.layer == "0" ? layer : child.layer;
        place(child, world_from_block, child_layer, top, depth + 1);
      }
    }
    stack.pop_back();
  }
};

std::string plural(int n, const std::string& kind) { return std::to_string(n) + " " + kind; }

std::string join_counts(const std::map<std::string, int>& counts, std::size_t max_items = 8) {
  std::vector<std::pair<int, std::string>> items;
  for (const auto& [k, n] : counts) items.emplace_back(-n, k);
  std::sort(items.begin(), items.end());
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < max_items; ++i)
    out += (i ? ", " : "") + plural(-items[i].first, items[i].second);
  if (items.size() > max_items) out += ", ...";
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// Stage 4: units.

UnitsEvidence evidence_of(const std::vector<PlacedCurve>& curves) {
  std::vector<DrawingSegment> segments;
  std::vector<DrawingArc> arcs;
  for (const PlacedCurve& p : curves) {
    const DxfCurve& c = *p.curve;
    const double s = Expander::xy_scale(p.world_from_curve);
    auto xy = [&p](const Eigen::Vector3d& q) { return Eigen::Vector2d((p.world_from_curve * q).head<2>()); };
    const bool mirrored = p.world_from_curve.linear().topLeftCorner<2, 2>().determinant() < 0.0;
    if (c.kind == DxfCurve::Kind::arc) {
      // The arc's ends in the world; a mirroring transform turns the sweep around, so the other end starts
      // it.
      const Eigen::Vector2d centre = xy(c.centre);
      const double a0 = c.start, a1 = c.start + c.sweep;
      const Eigen::Vector2d e0 =
          xy(c.centre + std::abs(c.radius) * Eigen::Vector3d(std::cos(a0), std::sin(a0), 0));
      const Eigen::Vector2d e1 =
          xy(c.centre + std::abs(c.radius) * Eigen::Vector3d(std::cos(a1), std::sin(a1), 0));
      const Eigen::Vector2d start = (mirrored != (c.sweep < 0)) ? e1 : e0;
      arcs.push_back({centre, std::abs(c.radius) * s, std::abs(c.sweep),
                      std::atan2(start.y() - centre.y(), start.x() - centre.x())});
    } else if (c.kind == DxfCurve::Kind::polyline && c.widths.empty()) {
      const std::size_t n = c.points.size();
      const std::size_t spans = c.closed ? n : (n > 0 ? n - 1 : 0);
      for (std::size_t i = 0; i < spans; ++i) {
        double bulge = i < c.bulges.size() ? c.bulges[i] : 0.0;
        Eigen::Vector2d a = xy(c.points[i]), b = xy(c.points[(i + 1) % n]);
        if (std::abs(bulge) < 1e-9) {
          segments.push_back({a, b});
        } else if (std::isfinite(
                       bulge)) {  // a bulged span: an arc from a to b, counter-clockwise if positive
          if (mirrored) bulge = -bulge;
          if (bulge < 0) std::swap(a, b), bulge = -bulge;
          const double sweep = 4.0 * std::atan(bulge);
          const double chord = (b - a).norm();
          if (!(chord > 0.0)) continue;
          const double radius = chord / (2.0 * std::sin(sweep / 2.0));
          const Eigen::Vector2d dir = (b - a) / chord, left(-dir.y(), dir.x());
          const Eigen::Vector2d centre = 0.5 * (a + b) + radius * std::cos(sweep / 2.0) * left;
          arcs.push_back({centre, radius, sweep, std::atan2(a.y() - centre.y(), a.x() - centre.x())});
        }
      }
    }
  }
  return collect_units_evidence(segments, arcs);
}

void choose_units(const DxfImportOptions& options, int insunits, const std::vector<PlacedCurve>& curves,
                  DxfImportReport* report) {
  if (!options.units_override.empty()) {
    report->units = options.units_override;
    report->units_source = "override";
    report->units_reason = "units chosen by the author";
    return;
  }
  const UnitsEvidence evidence = evidence_of(curves);
  const std::string header_units = units_of_insunits(insunits);
  if (!header_units.empty()) {
    std::string why;
    if (units_plausible(header_units, evidence, &why)) {
      report->units = header_units;
      report->units_source = "header";
      report->units_from_header = true;
      report->units_reason = "$INSUNITS " + std::to_string(insunits) + " (" + header_units + ")" +
                             (why.empty() ? std::string() : ": " + why);
      return;
    }
    // Overrule the header only on strong evidence: doors (the most telling cue) and a confident guess;
    // wall gaps or the size alone are not enough, since many drawings are not floor plans.
    const UnitsInference inferred = infer_units(evidence);
    bool strong = false;
    if (!inferred.units.empty() && (evidence.door_leaves >= 2 || evidence.door_swing_radii.size() >= 3)) {
      std::vector<double> radii = evidence.door_swing_radii;
      std::nth_element(radii.begin(), radii.begin() + static_cast<long>(radii.size() / 2), radii.end());
      const double door_m = radii[radii.size() / 2] * metres_per_unit(inferred.units);
      strong = door_m >= 0.6 && door_m <= 1.1;  // the doors come out door-sized in the inferred units
    }
    if (strong && !inferred.units.empty() && inferred.units != header_units) {
      report->units = inferred.units;
      report->units_source = "inferred";
      report->units_reason = "the header says " + header_units + " ($INSUNITS " + std::to_string(insunits) +
                             "), but " + why + "; " + inferred.reason;
      report->warnings.push_back("units: " + report->units_reason);
      return;
    }
    report->units = header_units;
    report->units_source = "header";
    report->units_from_header = true;
    report->units_reason =
        "$INSUNITS " + std::to_string(insunits) + " (" + header_units + "), kept although " + why;
    report->warnings.push_back("units: " + report->units_reason);
    return;
  }
  const UnitsInference inferred = infer_units(evidence);
  const std::string said =
      insunits < 0 ? "no $INSUNITS in the header" : "$INSUNITS " + std::to_string(insunits) + " (unitless)";
  if (!inferred.units.empty()) {
    report->units = inferred.units;
    report->units_source = "inferred";
    report->units_reason = said + "; " + inferred.reason;
  } else {
    report->units = "m";
    report->units_source = "assumed";
    report->units_reason = said + " and nothing in the drawing to tell: assuming metres" +
                           (inferred.reason.empty() ? std::string() : " (" + inferred.reason + ")");
  }
  report->warnings.push_back("units: " + report->units_reason);
}

// ---------------------------------------------------------------------------------------------------------
// Strays.

struct Chain {
  std::vector<Eigen::Vector2d> points;  // drawing units
  bool closed;
  bool whole;
  std::string layer;
  int top;
  bool solid_fill;
};

struct Box {
  Eigen::Vector2d min = Eigen::Vector2d::Constant(1e300), max = Eigen::Vector2d::Constant(-1e300);
  bool valid() const { return min.x() <= max.x(); }
  void add(const Eigen::Vector2d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  double distance_to(const Box& b) const {
    const Eigen::Vector2d gap = (b.min - max).cwiseMax(min - b.max).cwiseMax(Eigen::Vector2d::Zero());
    return gap.norm();
  }
};

// Entities whose box lies more than ten bulk-sizes away from the bulk of the drawing (the box of the
// middle 80 % of entity centres), when they are a small minority.
std::set<int> find_strays(const std::map<int, Box>& boxes) {
  std::set<int> strays;
  if (boxes.size() < 10) return strays;
  std::vector<double> xs, ys;
  for (const auto& [top, b] : boxes) {
    xs.push_back(0.5 * (b.min.x() + b.max.x()));
    ys.push_back(0.5 * (b.min.y() + b.max.y()));
  }
  Box bulk;
  bulk.add({percentile(xs, 0.1), percentile(ys, 0.1)});
  bulk.add({percentile(xs, 0.9), percentile(ys, 0.9)});
  double size = (bulk.max - bulk.min).maxCoeff();
  if (!(size > 0.0)) {
    for (const auto& [top, b] : boxes) size = std::max(size, (b.max - b.min).maxCoeff());
  }
  if (!(size > 0.0)) return strays;
  for (const auto& [top, b] : boxes)
    if (bulk.distance_to(b) > 10.0 * size) strays.insert(top);
  if (strays.size() > std::max<std::size_t>(1, boxes.size() / 20))
    strays.clear();  // two clusters, not strays
  return strays;
}

}  // namespace

FloorPlan import_dxf_from_memory(const std::string& bytes, const std::string& name,
                                 const DxfImportOptions& options, DxfImportReport* report_out) {
  options.check();
  DxfImportReport report;
  Skips skips{&report};

  // Stage 1
  DxfTags tags = read_dxf_tags(bytes, name);
  report.binary = tags.binary;
  for (const auto& w : tags.warnings) report.warnings.push_back(w);
  if (!tags.reached_eof && tags.warnings.empty())
    report.warnings.push_back("no EOF marker: the file may be cut short");
  const Header header = read_header(tags.tags);
  report.version = header.acadver;
  report.codepage = valid_utf8(header.codepage);
  decode_strings(&tags.tags, dxf_string_encoding(header.acadver, header.codepage));

  // Stage 2
  Drawing drawing;
  std::vector<Section> sections = find_sections(tags.tags);
  for (const Section& s : sections)
    if (s.name == "TABLES") read_layers(tags.tags, s, &drawing);
  for (const Section& s : sections)
    if (s.name == "BLOCKS") read_blocks(tags.tags, s, &drawing, &report);
  for (const Section& s : sections) {
    if (s.name != "ENTITIES") continue;
    const std::vector<DxfEntityTags> entities = split_entities(tags.tags, s.begin, s.end);
    read_entities(
        entities, 0, entities.size(),
        [&](DxfEntity e) {
          if (e.paper_space)
            skips.model(e.kind, e.layer, e.line, "paper space");
          else
            drawing.model.push_back(std::move(e));
        },
        [&](const std::string& kind, const std::string& layer, std::size_t line, const std::string& why) {
          skips.model(kind, layer, line, why);
        });
  }
  if (!drawing.block_skips.empty())
    report.warnings.push_back("inside blocks, left out: " + join_counts(drawing.block_skips));

  auto wanted = [&](const std::string& layer) {
    return options.layers.empty() ||
           std::find(options.layers.begin(), options.layers.end(), layer) != options.layers.end();
  };

  // Stage 3: each model-space entity on its own, so one block bomb is skipped alone.
  Expander expander{drawing, options.max_segments, {}, {}, 0, {}, {}, {}, {}};
  std::vector<const DxfEntity*> tops;
  for (const DxfEntity& e : drawing.model) {
    if (!wanted(e.layer) && e.block.empty()) {
      skips.model(e.kind, e.layer, e.line, "on a layer not chosen for import");
      continue;
    }
    const std::size_t curves_before = expander.curves.size(), labels_before = expander.labels.size();
    const int top = static_cast<int>(tops.size());
    try {
      expander.place(e, Eigen::Affine3d::Identity(), e.layer, top, 0);
    } catch (const TooLarge&) {
      expander.curves.resize(curves_before);
      expander.labels.resize(labels_before);
      expander.stack.clear();
      skips.model(
          e.kind, e.layer, e.line,
          "expands to more than " + std::to_string(options.max_segments) + " curves (nested arrays?)");
      continue;
    }
    if (!e.block.empty() && !drawing.blocks.count(e.block)) {
      skips.model(e.kind, e.layer, e.line, "block '" + e.block + "' is not defined");
      continue;
    }
    tops.push_back(&e);
    ++report.entities_read;
    ++report.entities_by_layer[e.layer][e.kind];
  }
  report.blocks_expanded = expander.expanded;
  for (const auto& [block, n] : expander.missing_blocks)
    if (drawing.blocks.count(block) == 0)
      report.warnings.push_back(plural(n, n == 1 ? "reference" : "references") + " to undefined block '" +
                                block + "'");
  for (const auto& [block, n] : expander.cycles)
    report.warnings.push_back("block '" + block + "' contains itself (or nests deeper than " +
                              std::to_string(kMaxBlockDepth) + " levels): not expanded there");
  for (const auto& [block, n] : expander.external_blocks)
    report.warnings.push_back("block '" + block +
                              "' is an external reference (xref): its drawing is not in this file");

  // Strays first, from coarse chords (a box per model-space entity needs no tolerance), so that neither the
  // units nor the extents see a title block or a point at 1e7.
  std::map<int, Box> all_boxes;
  {
    int ignored = 0;
    for (const PlacedCurve& p : expander.curves) {
      if (!wanted(p.layer)) continue;
      bool closed = false;
      for (const auto& q : tessellate(*p.curve, p.world_from_curve, 1e300, &closed, &ignored))
        if (q.allFinite()) all_boxes[p.top].add(q);
    }
    for (const PlacedLabel& l : expander.labels)
      if (!all_boxes.count(l.top) && l.position.allFinite()) all_boxes[l.top].add(l.position);
  }
  const std::set<int> strays = find_strays(all_boxes);
  report.stray_entities = static_cast<int>(strays.size());
  const bool drop_strays = !options.keep_stray && !strays.empty();
  for (int top : strays) {
    const DxfEntity& e = *tops[static_cast<std::size_t>(top)];
    if (drop_strays) {
      --report.entities_read;
      if (--report.entities_by_layer[e.layer][e.kind] == 0) report.entities_by_layer[e.layer].erase(e.kind);
      if (report.entities_by_layer[e.layer].empty()) report.entities_by_layer.erase(e.layer);
      skips.model(e.kind, e.layer, e.line, "far from the rest of the drawing (stray)");
    }
  }
  if (!strays.empty())
    report.warnings.push_back(std::to_string(strays.size()) +
                              (strays.size() == 1 ? " entity lies" : " entities lie") +
                              " far from the rest of the drawing" +
                              (drop_strays ? ": left out (keep_stray keeps them)" : ": kept"));

  // Stage 4: units, from the entities that are not strays.
  std::vector<PlacedCurve> bulk_curves;
  bulk_curves.reserve(expander.curves.size());
  for (const PlacedCurve& p : expander.curves)
    if (!strays.count(p.top)) bulk_curves.push_back(p);
  choose_units(options, header.insunits, bulk_curves, &report);
  const double scale = metres_per_unit(report.units);
  const double tolerance = options.chord_tolerance_m / scale;

  // Stage 5: chords.
  std::vector<Chain> chains;
  chains.reserve(expander.curves.size());
  for (const PlacedCurve& p : expander.curves) {
    if (!wanted(p.layer)) continue;
    Chain c{{}, false, p.curve->whole, p.layer, p.top, p.solid_fill};
    c.points = tessellate(*p.curve, p.world_from_curve, tolerance, &c.closed, &report.arcs_tessellated);
    if (c.points.empty() || !std::all_of(c.points.begin(), c.points.end(),
                                         [](const Eigen::Vector2d& q) { return q.allFinite(); }))
      continue;
    if (c.points.size() < 2 && !c.closed) continue;
    chains.push_back(std::move(c));
  }
  Box extents, bulk;  // what is imported; the building without its strays (which decides the re-centring)
  for (const Chain& c : chains) {
    const bool stray = strays.count(c.top) > 0;
    for (const auto& q : c.points) {
      if (!drop_strays || !stray) extents.add(q);
      if (!stray) bulk.add(q);
    }
  }
  if (extents.valid()) {
    report.drawing_extents.min = extents.min;
    report.drawing_extents.max = extents.max;
    report.drawing_extents.valid = true;
  }
  if (bulk.valid()) {
    const Eigen::Vector2d centre_m = 0.5 * (bulk.min + bulk.max) * scale;
    if (centre_m.norm() > options.recentre_beyond_m) {
      report.origin_m = centre_m.array().round().matrix();
      report.warnings.push_back("the drawing lies " +
                                std::to_string(static_cast<long long>(centre_m.norm())) +
                                " m from the DXF origin: re-centred (the offset is kept with the plan)");
    }
  }

  FloorPlan plan;
  plan.source_file = name;
  plan.units = report.units;
  plan.metres_per_unit = scale;
  plan.dxf_origin_m = report.origin_m;
  auto to_plan = [&](const Eigen::Vector2d& p) { return Eigen::Vector2d(p * scale - report.origin_m); };

  std::map<std::string, PlanLayer> layers = drawing.layers;
  auto touch_layer = [&](const std::string& l) -> PlanLayer& {
    PlanLayer& layer = layers[l];
    if (layer.name.empty()) layer.name = l;
    return layer;
  };
  std::map<std::string, int> solid_fill_outlines;
  std::vector<PlanSegment> raw_segments;
  std::set<std::pair<int, std::string>> counted;  // one count per entity and layer
  for (const Chain& c : chains) {
    if (drop_strays && strays.count(c.top)) continue;
    if (counted.insert({c.top, c.layer}).second) ++touch_layer(c.layer).entity_count;
    std::vector<Eigen::Vector2d> pts;
    pts.reserve(c.points.size());
    for (const auto& q : c.points) pts.push_back(to_plan(q));
    const std::size_t n = pts.size();
    const std::size_t spans = c.closed && n > 2 ? n : n - 1;
    for (std::size_t i = 0; i < spans; ++i)
      raw_segments.push_back({pts[i], pts[(i + 1) % n], c.layer, false});
    if (c.whole) plan.outlines.push_back({pts, c.layer, c.closed});
    if (c.solid_fill && c.closed) {
      ++solid_fill_outlines[c.layer];
      ++report.hatch_outlines;
    } else if (c.closed && (tops[static_cast<std::size_t>(c.top)]->kind == "HATCH")) {
      ++report.hatch_outlines;
    }
  }
  for (const PlacedLabel& l : expander.labels) {
    if (!wanted(l.layer) || (drop_strays && strays.count(l.top))) continue;
    if (counted.insert({l.top, l.layer}).second) ++touch_layer(l.layer).entity_count;
    plan.labels.push_back({to_plan(l.position), l.text, l.height * scale, l.layer});
  }

  CleanupCounts counts;
  plan.segments = clean_segments(raw_segments, options.snap_tolerance_m, &counts);
  report.snapped_endpoints = counts.snapped_endpoints;
  report.zero_length_dropped = counts.zero_length_dropped;
  report.duplicates_dropped = counts.duplicates_dropped;
  report.collinear_merged = counts.collinear_merged;
  report.intersections_split = counts.intersections_split;

  for (auto& [layer_name, layer] : layers)
    if (wanted(layer_name)) plan.layers.push_back(layer);
  if (options.occluder_layers.empty()) {
    for (const OccluderProposal& p : propose_occluder_layers(plan, solid_fill_outlines)) {
      if (PlanLayer* l = plan.find_layer(p.layer)) l->occluder = p.occluder;
      if (p.occluder) report.occluder_reasons[p.layer] = p.reason;
    }
  } else {
    for (auto& l : plan.layers) {
      l.occluder = std::find(options.occluder_layers.begin(), options.occluder_layers.end(), l.name) !=
                   options.occluder_layers.end();
      if (l.occluder) report.occluder_reasons[l.name] = "chosen by the author";
    }
  }
  for (auto& s : plan.segments) {
    const PlanLayer* l = plan.find_layer(s.layer);
    s.occluder = l && l->occluder;
  }

  if (plan.segments.empty() && plan.labels.empty()) {
    std::string what =
        std::string(report.binary ? "binary DXF with " : "") + "no 2-D plan geometry in model space";
    if (!options.layers.empty()) what += " on the chosen layers";
    if (!report.skipped_by_kind.empty()) {
      std::map<std::string, int> reasons;
      for (const auto& s : report.skipped) ++reasons[s.kind + " (" + s.why + ")"];
      what += "; left out: " + join_counts(reasons);
    }
    if (!tags.warnings.empty()) what += "; " + tags.warnings.front();
    throw file_error(name, what);
  }
  if (report_out) *report_out = report;
  return plan;
}

FloorPlan import_dxf(const std::string& file, const DxfImportOptions& options, DxfImportReport* report) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw file_error(file, "cannot open the file");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw file_error(file, "read error");
  return import_dxf_from_memory(bytes.str(), file, options, report);
}

}  // namespace plenopath
