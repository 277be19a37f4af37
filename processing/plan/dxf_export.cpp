#include "processing/plan/dxf_export.h"

#include <dxflib/dl_dxf.h>

#include <cmath>
#include <memory>
#include <set>

#include "model/error.h"
#include "model/option_check.h"

namespace plenopath {

void DxfExportOptions::check() const {
  require_option(units == "mm" || units == "cm" || units == "m", "DxfExportOptions.units",
                 "must be mm, cm or m", units);
}

namespace {

struct Units {
  double per_metre;
  int insunits;
};
Units units_of(const std::string& name) {
  if (name == "mm") return {1000.0, 4};
  if (name == "cm") return {100.0, 5};
  return {1.0, 6};
}

DL_Attributes attributes(const std::string& layer) { return DL_Attributes(layer, 256, -1, "BYLAYER", 1.0); }

void write_polyline(DL_Dxf& dxf, DL_WriterA& dw, const DrawingPolyline& p, double k,
                    const std::string& layer) {
  dxf.writePolyline(dw, DL_PolylineData(static_cast<int>(p.points.size()), 0, 0, p.closed ? 1 : 0),
                    attributes(layer));
  for (const auto& v : p.points) dxf.writeVertex(dw, DL_VertexData(v.x() * k, v.y() * k, 0.0, 0.0));
  dxf.writePolylineEnd(dw);
}

}  // namespace

void write_dxf(const PlanDrawing& d, const std::string& file, const DxfExportOptions& options) {
  try {
    options.check();
  } catch (const Error& e) {
    throw file_error(file, e.what());
  }
  for (const auto& ins : d.inserts)
    if (!d.find_block(ins.block)) throw file_error(file, "insert of unknown block '" + ins.block + "'");
  const Units u = units_of(options.units);
  const double k = u.per_metre;

  DL_Dxf dxf;
  const DL_Codes::version version = DL_Codes::AC1015;
  std::unique_ptr<DL_WriterA> dw(dxf.out(file.c_str(), version));
  if (!dw) throw file_error(file, "cannot open for writing");

  dxf.writeHeader(*dw);
  dw->dxfString(9, "$INSUNITS");
  dw->dxfInt(70, u.insunits);
  dw->dxfString(9, "$HANDSEED");
  dw->dxfHex(5, 0xFFFF);
  dw->sectionEnd();

  dw->sectionTables();
  dxf.writeVPort(*dw);
  dw->tableLinetypes(3);
  dxf.writeLinetype(*dw, DL_LinetypeData("BYBLOCK", "", 0, 0, 0.0));
  dxf.writeLinetype(*dw, DL_LinetypeData("BYLAYER", "", 0, 0, 0.0));
  dxf.writeLinetype(*dw, DL_LinetypeData("CONTINUOUS", "Solid line", 0, 0, 0.0));
  dw->tableEnd();

  std::vector<DrawingLayer> layers{{"0", 7}};
  std::set<std::string> seen{"0"};
  for (const auto& l : d.layers)
    if (seen.insert(l.name).second) layers.push_back(l);
  auto note_layer = [&](const std::string& name) {
    if (seen.insert(name).second) layers.push_back({name, 7});
  };
  for (const auto& e : d.lines) note_layer(e.layer);
  for (const auto& e : d.polylines) note_layer(e.layer);
  for (const auto& e : d.circles) note_layer(e.layer);
  for (const auto& e : d.arcs) note_layer(e.layer);
  for (const auto& e : d.texts) note_layer(e.layer);
  for (const auto& e : d.inserts) note_layer(e.layer);
  dw->tableLayers(static_cast<int>(layers.size()));
  for (const auto& l : layers)
    dxf.writeLayer(*dw, DL_LayerData(l.name, 0), DL_Attributes("", l.color, 100, "CONTINUOUS", 1.0));
  dw->tableEnd();

  dw->tableStyle(1);
  dxf.writeStyle(*dw, DL_StyleData("standard", 0, 0.0, 1.0, 0.0, 0, 2.5, "txt", ""));
  dw->tableEnd();
  dxf.writeView(*dw);
  dxf.writeUcs(*dw);
  dw->tableAppid(1);
  dxf.writeAppid(*dw, "ACAD");
  dw->tableEnd();
  dxf.writeDimStyle(*dw, 1, 1, 1, 1, 1);
  dxf.writeBlockRecord(*dw);
  for (const auto& b : d.blocks) dxf.writeBlockRecord(*dw, b.name);
  dw->tableEnd();
  dw->sectionEnd();

  dw->sectionBlocks();
  for (const char* space : {"*Model_Space", "*Paper_Space", "*Paper_Space0"}) {
    dxf.writeBlock(*dw, DL_BlockData(space, 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(*dw, space);
  }
  for (const auto& b : d.blocks) {
    dxf.writeBlock(*dw, DL_BlockData(b.name, 0, 0.0, 0.0, 0.0));
    for (const auto& p : b.polylines) write_polyline(dxf, *dw, p, k, p.layer.empty() ? "0" : p.layer);
    dxf.writeEndBlock(*dw, b.name);
  }
  dw->sectionEnd();

  dw->sectionEntities();
  for (const auto& l : d.lines)
    dxf.writeLine(*dw, DL_LineData(l.a.x() * k, l.a.y() * k, 0.0, l.b.x() * k, l.b.y() * k, 0.0),
                  attributes(l.layer));
  for (const auto& p : d.polylines) write_polyline(dxf, *dw, p, k, p.layer);
  for (const auto& c : d.circles)
    dxf.writeCircle(*dw, DL_CircleData(c.centre.x() * k, c.centre.y() * k, 0.0, c.radius * k),
                    attributes(c.layer));
  for (const auto& a : d.arcs)
    dxf.writeArc(*dw,
                 DL_ArcData(a.centre.x() * k, a.centre.y() * k, 0.0, a.radius * k, a.start_deg, a.end_deg),
                 attributes(a.layer));
  for (const auto& ins : d.inserts)
    dxf.writeInsert(*dw,
                    DL_InsertData(ins.block, ins.position.x() * k, ins.position.y() * k, 0.0, 1.0, 1.0, 1.0,
                                  ins.rotation_deg, 1, 1, 0.0, 0.0),
                    attributes(ins.layer));
  for (const auto& t : d.texts) {
    const double x = t.position.x() * k, y = t.position.y() * k;
    // Centred both ways (72 = 1, 73 = 2): the alignment point is the text's centre.
    dxf.writeText(*dw, DL_TextData(x, y, 0.0, x, y, 0.0, t.height * k, 1.0, 0, 1, 2, t.text, "standard", 0.0),
                  attributes(t.layer));
  }
  dw->sectionEnd();
  // No OBJECTS section: dxflib's default layouts carry 1e20 "empty extents" that strict readers (ours
  // included) reject as absurd coordinates, and no reader we target needs them.
  dw->dxfEOF();
  dw->close();
}

PlanDrawing drawing_from_plan(const FloorPlan& plan) {
  PlanDrawing d;
  for (const auto& l : plan.layers) d.layers.push_back({l.name, l.color});
  // Segments that are edges of an outline are written with the outline only.
  auto key = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::string& layer) {
    auto lt = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
      return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
    };
    const Eigen::Vector2d& lo = lt(a, b) ? a : b;
    const Eigen::Vector2d& hi = lt(a, b) ? b : a;
    return std::make_tuple(lo.x(), lo.y(), hi.x(), hi.y(), layer);
  };
  std::multiset<std::tuple<double, double, double, double, std::string>> outline_edges;
  for (const auto& o : plan.outlines) {
    d.polylines.push_back({o.points, o.closed, o.layer});
    for (std::size_t i = 0; i + 1 < o.points.size(); ++i)
      outline_edges.insert(key(o.points[i], o.points[i + 1], o.layer));
    if (o.closed && o.points.size() > 2)
      outline_edges.insert(key(o.points.back(), o.points.front(), o.layer));
  }
  for (const auto& s : plan.segments) {
    auto it = outline_edges.find(key(s.a, s.b, s.layer));
    if (it != outline_edges.end()) {
      outline_edges.erase(it);
      continue;
    }
    d.lines.push_back({s.a, s.b, s.layer});
  }
  for (const auto& l : plan.labels)
    d.texts.push_back({l.position, l.height > 0 ? l.height : 0.3, l.text, l.layer});
  return d;
}

}  // namespace plenopath
