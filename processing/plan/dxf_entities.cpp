#include "processing/plan/dxf_entities.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "processing/plan/dxf_text.h"

namespace plenopath {
namespace {

constexpr double kMaxValue = 1e12;  // drawing units; beyond this a value is junk (1e20 extents, ...)
constexpr int kMaxArrayCells = 100000;

[[noreturn]] void fail(const std::string& why) { throw DxfEntityError{why}; }

double number_of(const DxfTag& t) {
  double v = 0.0;
  if (!dxf_number(t, &v))
    fail("line " + std::to_string(t.line) + ": group code " + std::to_string(t.code) + ": '" +
         t.value.substr(0, 30) + "' is not a number");
  if (std::abs(v) > kMaxValue)
    fail("line " + std::to_string(t.line) + ": group code " + std::to_string(t.code) + ": value " +
         t.value.substr(0, 30) + " out of range");
  return v;
}

// First-occurrence access to an entity's tags.
class Tags {
 public:
  explicit Tags(const DxfEntityTags& e) : e_(e) {}
  const DxfTag* find(int code) const {
    for (const DxfTag* t = e_.begin + 1; t != e_.end; ++t)
      if (t->code == code) return t;
    return nullptr;
  }
  bool has(int code) const { return find(code) != nullptr; }
  double real(int code, double fallback) const {
    const DxfTag* t = find(code);
    return t ? number_of(*t) : fallback;
  }
  int integer(int code, int fallback) const {
    const DxfTag* t = find(code);
    if (!t) return fallback;
    const double v = number_of(*t);  // some writers put integers as reals
    return static_cast<int>(std::clamp(v, -2.0e9, 2.0e9));
  }
  std::string text(int code, const std::string& fallback = {}) const {
    const DxfTag* t = find(code);
    return t ? t->value : fallback;
  }
  Eigen::Vector3d point(int x_code, const Eigen::Vector3d& fallback = Eigen::Vector3d::Zero()) const {
    if (!has(x_code)) return fallback;
    return {real(x_code, 0.0), real(x_code + 10, 0.0), real(x_code + 20, 0.0)};
  }
  // A point the entity cannot do without: x and y must be there.
  Eigen::Vector3d required_point(int x_code, const char* what) const {
    if (!has(x_code) || !has(x_code + 10))
      fail(std::string("no ") + what + " (group codes " + std::to_string(x_code) + "/" +
           std::to_string(x_code + 10) + ")");
    return point(x_code);
  }
  Eigen::Vector3d extrusion() const {
    const Eigen::Vector3d n = point(210, Eigen::Vector3d::UnitZ());
    if (!(n.norm() > 1e-12)) fail("extrusion direction of length 0");
    return n;
  }
  const DxfTag* begin() const { return e_.begin + 1; }
  const DxfTag* end() const { return e_.end; }

 private:
  const DxfEntityTags& e_;
};

double positive_sweep(double start, double end) {  // radians, in (0, 2 pi]
  double sweep = end - start;
  while (sweep <= 1e-12) sweep += 2.0 * M_PI;
  while (sweep > 2.0 * M_PI + 1e-12) sweep -= 2.0 * M_PI;
  return sweep;
}

DxfCurve line_curve(const Tags& t) {
  DxfCurve c;
  c.whole = false;
  c.points = {t.required_point(10, "start point"), t.required_point(11, "end point")};
  return c;
}

DxfCurve arc_curve(const Tags& t, bool circle) {
  DxfCurve c;
  c.kind = DxfCurve::Kind::arc;
  c.centre = t.required_point(10, "centre");
  c.radius = t.real(40, 0.0);
  if (!(c.radius > 0.0)) fail("radius " + t.text(40, "missing") + " (must be positive)");
  if (circle) {
    c.start = 0.0;
    c.sweep = 2.0 * M_PI;
    c.closed = true;
  } else {
    c.start = t.real(50, 0.0) * M_PI / 180.0;
    c.sweep = positive_sweep(c.start, t.real(51, 360.0) * M_PI / 180.0);
  }
  c.to_parent = world_from_ocs(t.extrusion());
  return c;
}

DxfCurve ellipse_curve(const Tags& t) {
  DxfCurve c;
  c.kind = DxfCurve::Kind::ellipse;
  c.centre = t.required_point(10, "centre");
  c.major = t.required_point(11, "major axis");
  const double ratio = t.real(40, 1.0);
  if (!(c.major.norm() > 0.0)) fail("major axis of length 0");
  if (!(ratio > 0.0 && ratio <= 1.0 + 1e-9)) fail("axis ratio " + t.text(40) + " (must be in (0, 1])");
  c.minor = ratio * t.extrusion().normalized().cross(c.major);
  c.start = t.real(41, 0.0);
  c.sweep = positive_sweep(c.start, t.real(42, 2.0 * M_PI));
  c.closed = std::abs(c.sweep - 2.0 * M_PI) < 1e-9;
  return c;
}

DxfCurve spline_curve(const Tags& t) {
  DxfCurve c;
  c.kind = DxfCurve::Kind::spline;
  c.degree = t.integer(71, 3);
  const int flags = t.integer(70, 0);
  c.closed = (flags & 1) != 0;
  std::vector<Eigen::Vector3d> ctrl, fit;
  std::vector<double> weights;
  for (const DxfTag* g = t.begin(); g != t.end(); ++g) {
    switch (g->code) {
      case 40:
        c.knots.push_back(number_of(*g));
        break;
      case 41:
        weights.push_back(number_of(*g));
        break;
      case 10:
        ctrl.emplace_back(number_of(*g), 0.0, 0.0);
        break;
      case 20:
        if (!ctrl.empty()) ctrl.back().y() = number_of(*g);
        break;
      case 30:
        if (!ctrl.empty()) ctrl.back().z() = number_of(*g);
        break;
      case 11:
        fit.emplace_back(number_of(*g), 0.0, 0.0);
        break;
      case 21:
        if (!fit.empty()) fit.back().y() = number_of(*g);
        break;
      case 31:
        if (!fit.empty()) fit.back().z() = number_of(*g);
        break;
      default:
        break;
    }
  }
  if (ctrl.size() >= 2) {
    for (std::size_t i = 0; i < ctrl.size(); ++i) {
      const double w = i < weights.size() && weights[i] > 0.0 ? weights[i] : 1.0;
      c.control.emplace_back(ctrl[i].x() * w, ctrl[i].y() * w, ctrl[i].z() * w, w);
    }
    return c;
  }
  if (fit.size() >= 2) {  // fit points only: the curve through them
    DxfCurve p;
    p.points = fit;
    p.closed = c.closed;
    return p;
  }
  fail("fewer than 2 control or fit points");
}

DxfCurve lwpolyline_curve(const Tags& t) {
  DxfCurve c;
  const int flags = t.integer(70, 0);
  c.closed = (flags & 1) != 0;
  const double elevation = t.real(38, 0.0);
  const double constant_width = t.real(43, 0.0);
  bool any_width = constant_width > 0.0;
  for (const DxfTag* g = t.begin(); g != t.end(); ++g) {
    switch (g->code) {
      case 10:
        c.points.emplace_back(number_of(*g), 0.0, elevation);
        c.bulges.push_back(0.0);
        c.widths.emplace_back(constant_width, constant_width);
        break;
      case 20:
        if (!c.points.empty()) c.points.back().y() = number_of(*g);
        break;
      case 40:
        if (!c.points.empty()) {
          c.widths.back().x() = number_of(*g);
          any_width |= c.widths.back().x() > 0.0;
        }
        break;
      case 41:
        if (!c.points.empty()) {
          c.widths.back().y() = number_of(*g);
          any_width |= c.widths.back().y() > 0.0;
        }
        break;
      case 42:
        if (!c.points.empty()) c.bulges.back() = number_of(*g);
        break;
      default:
        break;
    }
  }
  if (c.points.empty()) fail("no vertices");
  if (!any_width) c.widths.clear();
  c.to_parent = world_from_ocs(t.extrusion());
  return c;
}

DxfCurve polyline_curve(const Tags& t, const std::vector<DxfEntityTags>& vertices) {
  DxfCurve c;
  const int flags = t.integer(70, 0);
  c.closed = (flags & 1) != 0;
  const double elevation = t.point(10).z();
  const double w0 = t.real(40, 0.0), w1 = t.real(41, 0.0);
  bool any_width = w0 > 0.0 || w1 > 0.0;
  for (const auto& v : vertices) {
    const Tags vt(v);
    if (vt.integer(70, 0) & 16) continue;  // a spline frame's control point, not on the curve
    const Eigen::Vector3d p = vt.point(10);
    c.points.emplace_back(p.x(), p.y(), elevation);
    c.bulges.push_back(vt.real(42, 0.0));
    c.widths.emplace_back(vt.real(40, w0), vt.real(41, w1));
    any_width |= c.widths.back().x() > 0.0 || c.widths.back().y() > 0.0;
  }
  if (c.points.empty()) fail("no vertices");
  if (!any_width) c.widths.clear();
  c.to_parent = world_from_ocs(t.extrusion());
  return c;
}

DxfCurve quad_curve(const Tags& t) {  // SOLID, TRACE: corners 1 2 4 3
  DxfCurve c;
  c.closed = true;
  const Eigen::Vector3d p0 = t.required_point(10, "first corner"), p1 = t.required_point(11, "second corner"),
                        p2 = t.required_point(12, "third corner");
  const Eigen::Vector3d p3 = t.has(13) ? t.point(13) : p2;
  const double elevation = t.real(38, p0.z());
  c.points = {p0, p1, p3, p2};
  if ((p3 - p2).norm() == 0.0) c.points.pop_back();
  for (auto& p : c.points) p.z() = elevation;
  c.to_parent = world_from_ocs(t.extrusion());
  return c;
}

// HATCH boundaries: a strict cursor over the tags after "91 number of boundary paths".
class Cursor {
 public:
  Cursor(const DxfTag* at, const DxfTag* end) : at_(at), end_(end) {}
  bool next_is(int code) const { return at_ != end_ && at_->code == code; }
  const DxfTag& take(int code, const char* what) {
    if (!next_is(code))
      fail(std::string("boundary ") + what + ": expected group code " + std::to_string(code) +
           (at_ == end_ ? " at the end of the entity" : " at line " + std::to_string(at_->line)));
    return *at_++;
  }
  double real(int code, const char* what) { return number_of(take(code, what)); }
  int count(int code, const char* what) {
    const DxfTag& t = take(code, what);
    const double v = number_of(t);
    if (v < 0 || v > static_cast<double>(end_ - at_) + 1)
      fail(std::string("boundary ") + what + ": count " + t.value + " at line " + std::to_string(t.line) +
           " is more than the entity holds");
    return static_cast<int>(v);
  }
  Eigen::Vector3d xy(int code, const char* what, double z) {
    const double x = real(code, what);
    const double y = real(code + 10, what);
    return {x, y, z};
  }

 private:
  const DxfTag* at_;
  const DxfTag* end_;
};

DxfCurve hatch_edge(Cursor& cur, double z) {
  const int type = static_cast<int>(cur.real(72, "edge type"));
  DxfCurve e;
  e.whole = false;
  switch (type) {
    case 1:
      e.points = {cur.xy(10, "line edge", z), cur.xy(11, "line edge", z)};
      return e;
    case 2: {
      e.kind = DxfCurve::Kind::arc;
      e.centre = cur.xy(10, "arc edge", z);
      e.radius = cur.real(40, "arc edge");
      double a0 = cur.real(50, "arc edge"), a1 = cur.real(51, "arc edge");
      const bool ccw = cur.real(73, "arc edge") != 0.0;
      // Clockwise edges store complementary angles (360 - angle), start and end swapped.
      if (!ccw) std::swap(a0, a1), a0 = 360.0 - a0, a1 = 360.0 - a1;
      if (!(e.radius > 0.0)) fail("boundary arc edge with radius " + std::to_string(e.radius));
      e.start = a0 * M_PI / 180.0;
      e.sweep = std::abs(a1 - a0) >= 360.0 ? 2.0 * M_PI : positive_sweep(e.start, a1 * M_PI / 180.0);
      return e;
    }
    case 3: {
      e.kind = DxfCurve::Kind::ellipse;
      e.centre = cur.xy(10, "ellipse edge", z);
      const Eigen::Vector3d major = cur.xy(11, "ellipse edge", 0.0);
      const double ratio = cur.real(40, "ellipse edge");
      double a0 = cur.real(50, "ellipse edge"), a1 = cur.real(51, "ellipse edge");
      const bool ccw = cur.real(73, "ellipse edge") != 0.0;
      if (!ccw) std::swap(a0, a1), a0 = 360.0 - a0, a1 = 360.0 - a1;
      if (!(major.norm() > 0.0) || !(ratio > 0.0)) fail("boundary ellipse edge without axes");
      e.major = major;
      e.minor = ratio * Eigen::Vector3d(-major.y(), major.x(), 0.0);
      // The stored angles are geometric; the parameter of angle a is atan2(sin a / ratio, cos a).
      auto param = [ratio](double deg) {
        const double a = deg * M_PI / 180.0;
        return std::atan2(std::sin(a) / ratio, std::cos(a));
      };
      e.start = param(a0);
      e.sweep = std::abs(a1 - a0) >= 360.0 ? 2.0 * M_PI : positive_sweep(e.start, param(a1));
      return e;
    }
    case 4: {
      e.kind = DxfCurve::Kind::spline;
      e.degree = static_cast<int>(cur.real(94, "spline edge"));
      const bool rational = cur.real(73, "spline edge") != 0.0;
      cur.real(74, "spline edge");  // periodic
      const int knots = cur.count(95, "spline edge");
      const int controls = cur.count(96, "spline edge");
      for (int k = 0; k < knots; ++k) e.knots.push_back(cur.real(40, "spline edge knots"));
      for (int k = 0; k < controls; ++k) {
        const Eigen::Vector3d p = cur.xy(10, "spline edge control points", z);
        const double w = rational && cur.next_is(42) ? cur.real(42, "spline edge weights") : 1.0;
        e.control.emplace_back(p.x() * w, p.y() * w, p.z() * w, w);
      }
      if (cur.next_is(97)) {
        const int fits = cur.count(97, "spline edge fit points");
        std::vector<Eigen::Vector3d> fit;
        for (int k = 0; k < fits; ++k) fit.push_back(cur.xy(11, "spline edge fit points", z));
        if (cur.next_is(12)) cur.xy(12, "spline edge tangent", z);
        if (cur.next_is(13)) cur.xy(13, "spline edge tangent", z);
        if (e.control.size() < 2 && fit.size() >= 2) {
          DxfCurve p;
          p.whole = false;
          p.points = fit;
          return p;
        }
      }
      if (e.control.size() < 2) fail("boundary spline edge with fewer than 2 control points");
      return e;
    }
    default:
      fail("boundary edge of unknown type " + std::to_string(type));
  }
}

// Each boundary path as one closed curve: a polyline path, or a path of line, arc, ellipse and spline edges.
std::vector<DxfCurve> hatch_boundaries(const Tags& t, bool* solid) {
  const Eigen::Affine3d ocs = world_from_ocs(t.extrusion());
  const double z = t.point(10).z();
  *solid = t.integer(70, 0) == 1 || t.text(2) == "SOLID";
  const DxfTag* at = t.begin();
  while (at != t.end() && at->code != 91) ++at;
  if (at == t.end()) fail("no boundary paths (group code 91)");
  Cursor cur(at, t.end());
  const int paths = cur.count(91, "paths");
  std::vector<DxfCurve> out;
  for (int p = 0; p < paths; ++p) {
    const int flags = static_cast<int>(cur.real(92, "path type"));
    DxfCurve path;
    path.closed = true;
    path.to_parent = ocs;
    if (flags & 2) {  // a polyline path
      const bool has_bulge = cur.real(72, "polyline path") != 0.0;
      cur.real(73, "polyline path");  // closed flag: a boundary is always closed
      const int vertices = cur.count(93, "polyline path vertices");
      for (int v = 0; v < vertices; ++v) {
        path.points.push_back(cur.xy(10, "polyline path vertex", z));
        path.bulges.push_back(has_bulge && cur.next_is(42) ? cur.real(42, "polyline path bulge") : 0.0);
      }
      if (path.points.size() >= 2 && (path.points.front() - path.points.back()).norm() == 0.0) {
        path.points.pop_back();
        path.bulges.pop_back();
      }
    } else {
      const int edges = cur.count(93, "edges");
      path.kind = DxfCurve::Kind::path;
      for (int e = 0; e < edges; ++e) path.pieces.push_back(hatch_edge(cur, z));
    }
    if (cur.next_is(97)) {
      const int sources = cur.count(97, "source objects");
      for (int s = 0; s < sources && cur.next_is(330); ++s) cur.take(330, "source objects");
    }
    if (path.points.size() >= 2 || !path.pieces.empty()) out.push_back(std::move(path));
  }
  return out;
}

}  // namespace

const char* dxf_skip_reason(const std::string& kind) {
  static const std::map<std::string, const char*> skipped = {{"DIMENSION", "dimension"},
                                                             {"ARC_DIMENSION", "dimension"},
                                                             {"LEADER", "annotation"},
                                                             {"MLEADER", "annotation"},
                                                             {"MULTILEADER", "annotation"},
                                                             {"TOLERANCE", "annotation"},
                                                             {"3DFACE", "3-D only"},
                                                             {"3DSOLID", "3-D only"},
                                                             {"BODY", "3-D only"},
                                                             {"REGION", "3-D only"},
                                                             {"SURFACE", "3-D only"},
                                                             {"PLANESURFACE", "3-D only"},
                                                             {"EXTRUDEDSURFACE", "3-D only"},
                                                             {"LOFTEDSURFACE", "3-D only"},
                                                             {"REVOLVEDSURFACE", "3-D only"},
                                                             {"SWEPTSURFACE", "3-D only"},
                                                             {"NURBSURFACE", "3-D only"},
                                                             {"MESH", "3-D only"},
                                                             {"POLYFACE", "3-D only"},
                                                             {"VIEWPORT", "viewport"},
                                                             {"IMAGE", "image"},
                                                             {"WIPEOUT", "image mask"},
                                                             {"OLE2FRAME", "embedded object"},
                                                             {"OLEFRAME", "embedded object"},
                                                             {"POINT", "a point has no extent"},
                                                             {"RAY", "infinite construction line"},
                                                             {"XLINE", "infinite construction line"},
                                                             {"ATTRIB", "block attribute"},
                                                             {"ATTDEF", "block attribute"},
                                                             {"ACAD_TABLE", "table"},
                                                             {"SHAPE", "shape font symbol"},
                                                             {"HELIX", "3-D only"},
                                                             {"LIGHT", "3-D only"},
                                                             {"SUN", "3-D only"},
                                                             {"UNDERLAY", "underlay"},
                                                             {"PDFUNDERLAY", "underlay"},
                                                             {"DWFUNDERLAY", "underlay"},
                                                             {"DGNUNDERLAY", "underlay"},
                                                             {"SECTIONOBJECT", "3-D only"},
                                                             {"GEOPOSITIONMARKER", "annotation"}};
  static const char* read[] = {"LINE",   "LWPOLYLINE", "POLYLINE", "ARC",   "CIRCLE", "ELLIPSE", "SPLINE",
                               "INSERT", "HATCH",      "SOLID",    "TRACE", "MLINE",  "TEXT",    "MTEXT"};
  for (const char* r : read)
    if (kind == r) return nullptr;
  auto it = skipped.find(kind);
  return it == skipped.end() ? "not plan geometry" : it->second;
}

DxfEntity parse_dxf_entity(const DxfEntityTags& entity, const std::vector<DxfEntityTags>& vertices) {
  const Tags t(entity);
  DxfEntity out;
  out.kind = entity.kind();
  out.line = entity.line();
  out.layer = t.text(8, "0");
  if (out.layer.empty()) out.layer = "0";
  out.paper_space = t.integer(67, 0) == 1;
  if (const DxfTag* layout = t.find(410)) {
    std::string name = layout->value;
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    if (!name.empty() && name != "model") out.paper_space = true;
  }
  const std::string& k = out.kind;
  if (k == "LINE") {
    out.curves.push_back(line_curve(t));
  } else if (k == "ARC" || k == "CIRCLE") {
    out.curves.push_back(arc_curve(t, k == "CIRCLE"));
  } else if (k == "ELLIPSE") {
    out.curves.push_back(ellipse_curve(t));
  } else if (k == "SPLINE") {
    out.curves.push_back(spline_curve(t));
  } else if (k == "LWPOLYLINE") {
    out.curves.push_back(lwpolyline_curve(t));
  } else if (k == "POLYLINE") {
    const int flags = t.integer(70, 0);
    if (flags & (8 | 16 | 64)) fail("3-D only (3-D polyline, mesh or polyface)");
    out.curves.push_back(polyline_curve(t, vertices));
  } else if (k == "SOLID" || k == "TRACE") {
    out.curves.push_back(quad_curve(t));
    out.solid_fill = true;
  } else if (k == "HATCH") {
    out.curves = hatch_boundaries(t, &out.solid_fill);
    if (out.curves.empty()) fail("no boundary with at least two points");
  } else if (k == "MLINE") {
    // Vertices (11), segment directions (12), mitre directions (13); per vertex and element the offset
    // along the mitre is the element's first parameter (41).
    const int flags = t.integer(71, 0);
    const int elements = std::max(0, t.integer(73, 0));
    std::vector<DxfCurve> lines(static_cast<std::size_t>(std::min(elements, 64)));
    Eigen::Vector3d vertex = Eigen::Vector3d::Zero(), mitre = Eigen::Vector3d::Zero();
    int element = -1, params_left = 0;
    bool first_param = false;
    for (const DxfTag* g = t.begin(); g != t.end(); ++g) {
      switch (g->code) {
        case 11:
          vertex.x() = number_of(*g);
          element = -1;
          break;
        case 21:
          vertex.y() = number_of(*g);
          break;
        case 31:
          vertex.z() = number_of(*g);
          break;
        case 13:
          mitre.x() = number_of(*g);
          break;
        case 23:
          mitre.y() = number_of(*g);
          break;
        case 33:
          mitre.z() = number_of(*g);
          break;
        case 74:
          ++element;
          params_left = static_cast<int>(number_of(*g));
          first_param = true;
          if (params_left == 0 && element < static_cast<int>(lines.size()))
            lines[element].points.push_back(vertex);
          break;
        case 41:
          if (first_param && element >= 0 && element < static_cast<int>(lines.size()))
            lines[element].points.push_back(vertex + number_of(*g) * mitre);
          first_param = false;
          --params_left;
          break;
        default:
          break;
      }
    }
    for (auto& l : lines) {
      l.closed = (flags & 2) != 0;
      if (l.points.size() >= 2) out.curves.push_back(std::move(l));
    }
    if (out.curves.empty()) fail("no element with two vertices");
  } else if (k == "INSERT") {
    out.block = t.text(2);
    if (out.block.empty()) fail("no block name");
    const Eigen::Vector3d scale(t.real(41, 1.0), t.real(42, 1.0), t.real(43, 1.0));
    if (scale.x() == 0.0 || scale.y() == 0.0) fail("scale of 0");
    const double rotation = t.real(50, 0.0) * M_PI / 180.0;
    const int cols = std::max(1, t.integer(70, 1)), rows = std::max(1, t.integer(71, 1));
    if (static_cast<long long>(cols) * rows > kMaxArrayCells)
      fail("array of " + std::to_string(cols) + " x " + std::to_string(rows) + " block copies");
    const double col_spacing = t.real(44, 0.0), row_spacing = t.real(45, 0.0);
    const Eigen::Vector3d position = t.point(10);
    const Eigen::Affine3d ocs = world_from_ocs(t.extrusion());
    const Eigen::AngleAxisd rot(rotation, Eigen::Vector3d::UnitZ());
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        // parent <- OCS <- translate(position + R * cell offset) <- R <- S
        Eigen::Affine3d cell = Eigen::Affine3d::Identity();
        cell.translate(position + rot * Eigen::Vector3d(c * col_spacing, r * row_spacing, 0.0));
        cell.rotate(rot);
        cell.scale(Eigen::Vector3d(scale.x(), scale.y(), scale.z() == 0.0 ? 1.0 : scale.z()));
        out.cells.push_back(ocs * cell);
      }
  } else if (k == "TEXT") {
    out.has_label = true;
    out.label_position = world_from_ocs(t.extrusion()) * t.point(10);
    out.label_text = dxf_decode_escapes(t.text(1));
    out.label_height = std::abs(t.real(40, 0.0));
  } else if (k == "MTEXT") {
    out.has_label = true;
    out.label_position = t.point(10);
    std::string raw;
    for (const DxfTag* g = t.begin(); g != t.end(); ++g)
      if (g->code == 3) raw += g->value;
    raw += t.text(1);
    out.label_text = dxf_decode_escapes(dxf_plain_mtext(raw));
    out.label_height = std::abs(t.real(40, 0.0));
  } else {
    fail(dxf_skip_reason(k));
  }
  for (const auto& c : out.curves)
    for (const auto& p : c.points)
      if (!p.allFinite()) fail("a vertex that is not a number");
  return out;
}

}  // namespace plenopath
