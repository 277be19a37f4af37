// DXF to FloorPlan. Three stages: a structural pre-scan of the group-code pairs (line numbers for errors;
// binary, truncated and malformed files stop here), dxflib's entity callbacks into per-block primitive
// lists (in drawing units, OCS mirrored back to WCS), then block expansion, unit conversion and clean-up.
#include "processing/plan/dxf_import.h"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "model/error.h"
#include "processing/plan/dxf_cleanup.h"

namespace plenopath {

double metres_per_unit(const std::string& units) {
  static const std::map<std::string, double> table = {
      {"m", 1.0},      {"mm", 0.001},     {"cm", 0.01},    {"dm", 0.1},     {"km", 1000.0},
      {"um", 1e-6},    {"in", 0.0254},    {"ft", 0.3048},  {"yd", 0.9144},  {"mi", 1609.344},
      {"mil", 2.54e-5}, {"dam", 10.0},    {"hm", 100.0}};
  auto it = table.find(units);
  if (it == table.end()) throw Error("unknown units '" + units + "' (use mm, cm, dm, m, km, um, in, ft, yd, mi)");
  return it->second;
}

std::string units_of_insunits(int insunits) {
  switch (insunits) {
    case 1: return "in";
    case 2: return "ft";
    case 3: return "mi";
    case 4: return "mm";
    case 5: return "cm";
    case 6: return "m";
    case 7: return "km";
    case 9: return "mil";
    case 10: return "yd";
    case 13: return "um";
    case 14: return "dm";
    case 15: return "dam";
    case 16: return "hm";
    default: return "";
  }
}

void DxfImportOptions::check() const {
  auto fail = [](const std::string& what) { throw Error("DXF import options: " + what); };
  if (!units_override.empty()) metres_per_unit(units_override);
  if (!(snap_tolerance_m >= 0.0 && snap_tolerance_m <= 0.1)) fail("snap_tolerance_m must be in [0, 0.1] m");
  if (!(chord_tolerance_m > 0.0 && chord_tolerance_m <= 1.0)) fail("chord_tolerance_m must be in (0, 1] m");
  if (!(single_line_wall_thickness_m > 0.0 && single_line_wall_thickness_m <= 0.5))
    fail("single_line_wall_thickness_m must be in (0, 0.5] m");
  if (!(max_coordinate_m > 0.0)) fail("max_coordinate_m must be positive");
  if (max_segments == 0) fail("max_segments must be positive");
}

namespace {

constexpr int kMaxBlockDepth = 16;
constexpr int kMaxArcPieces = 4096;
constexpr int kMaxArrayCells = 100000;

// ---------------------------------------------------------------------------------------------------------
// Stage 1: structure. Every pair is "integer group code line, value line"; numbers must parse; the file
// must end with EOF (or at least close its last section).

bool is_real_code(int c) {
  return (c >= 10 && c <= 59) || (c >= 110 && c <= 149) || (c >= 210 && c <= 239) || (c >= 460 && c <= 469) ||
         (c >= 1010 && c <= 1059);
}
bool is_int_code(int c) {
  return (c >= 60 && c <= 99) || (c >= 170 && c <= 179) || (c >= 270 && c <= 289) || (c >= 370 && c <= 389) ||
         (c >= 400 && c <= 409) || (c >= 1060 && c <= 1071);
}

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

struct PrescanResult {
  std::map<std::string, int> skipped_kinds;  // entity kinds we do not read
};

void prescan(const std::string& bytes, const std::string& name, PrescanResult* out) {
  auto fail_line = [&name](std::size_t line, const std::string& what) {
    throw file_error(name, "line " + std::to_string(line) + ": " + what);
  };
  if (bytes.empty()) throw file_error(name, "the file is empty");
  if (bytes.compare(0, 18, "AutoCAD Binary DXF") == 0)
    throw file_error(name, "binary DXF is not supported: save the drawing as ASCII DXF");
  std::vector<std::string> lines;
  {
    std::size_t start = 0, line_no = 1;
    for (std::size_t i = 0; i <= bytes.size(); ++i) {
      if (i == bytes.size() || bytes[i] == '\n') {
        std::string l = bytes.substr(start, i - start);
        if (!l.empty() && l.back() == '\r') l.pop_back();
        if (l.size() > 2048) fail_line(line_no, "line longer than 2048 characters (not a DXF file?)");
        lines.push_back(std::move(l));
        start = i + 1;
        ++line_no;
      } else if (bytes[i] == '\0') {
        fail_line(line_no, "binary data (NUL byte): not an ASCII DXF file");
      }
    }
    if (!lines.empty() && lines.back().empty()) lines.pop_back();
  }
  static const std::set<std::string> read_kinds = {"LINE",   "LWPOLYLINE", "POLYLINE", "VERTEX", "SEQEND",
                                                   "ARC",    "CIRCLE",     "ELLIPSE",  "SPLINE", "INSERT",
                                                   "TEXT",   "MTEXT",      "ATTRIB",   "ATTDEF", "POINT"};
  bool in_section = false, saw_eof = false, geometry_section = false, saw_section = false;
  std::string expect_section_name;
  for (std::size_t i = 0; i < lines.size(); i += 2) {
    const std::size_t line_no = i + 1;
    const std::string code_text = trim(lines[i]);
    if (code_text.empty() || code_text.size() > 6 ||
        !std::all_of(code_text.begin(), code_text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '-'; }))
      fail_line(line_no, "expected a group code (an integer), found '" + code_text.substr(0, 40) + "'");
    const int code = std::atoi(code_text.c_str());
    if (i + 1 >= lines.size())
      fail_line(line_no, "truncated: group code " + std::to_string(code) + " has no value");
    const std::string value = trim(lines[i + 1]);
    if (is_real_code(code) || is_int_code(code)) {
      char* end = nullptr;
      const double v = std::strtod(value.c_str(), &end);
      if (value.empty() || end == value.c_str() || *end != '\0')
        fail_line(line_no + 1, "group code " + std::to_string(code) + ": '" + value.substr(0, 40) + "' is not a number");
      if (!std::isfinite(v) || std::abs(v) > 1e15)
        fail_line(line_no + 1, "group code " + std::to_string(code) + ": absurd value " + value.substr(0, 40));
      // Counts drive dxflib's allocations (vertices, knots, control points).
      if (is_int_code(code) && code >= 70 && code <= 99 && std::abs(v) > 1e6)
        fail_line(line_no + 1, "group code " + std::to_string(code) + ": implausible count " + value.substr(0, 40));
      // dxflib sizes a SPLINE's knot, control and fit point lists from these counts.
      if ((code == 72 || code == 73 || code == 74) && std::abs(v) > 100000)
        fail_line(line_no + 1, "group code " + std::to_string(code) + ": implausible count " + value.substr(0, 40));
    }
    if (code == 0) {
      if (value == "SECTION") {
        if (in_section) fail_line(line_no + 1, "SECTION inside a section (missing ENDSEC)");
        in_section = true;
        saw_section = true;
        expect_section_name = "yes";
      } else if (value == "ENDSEC") {
        if (!in_section) fail_line(line_no + 1, "ENDSEC without SECTION");
        in_section = false;
        geometry_section = false;
      } else if (value == "EOF") {
        if (in_section) fail_line(line_no + 1, "EOF inside a section (missing ENDSEC)");
        saw_eof = true;
        break;
      } else if (geometry_section && !read_kinds.count(value) && value != "BLOCK" && value != "ENDBLK") {
        ++out->skipped_kinds[value.substr(0, 40)];
      }
    } else if (code == 2 && !expect_section_name.empty()) {
      geometry_section = value == "ENTITIES" || value == "BLOCKS";
      expect_section_name.clear();
    }
  }
  if (!saw_section) throw file_error(name, "no SECTION found: not a DXF file");
  if (!saw_eof) {
    if (in_section)
      throw file_error(name, "truncated: the file ends inside a section (line " + std::to_string(lines.size()) + ")");
    throw file_error(name, "truncated: no EOF marker after line " + std::to_string(lines.size()));
  }
}

// ---------------------------------------------------------------------------------------------------------
// Stage 2: dxflib callbacks into primitives per block.

struct Polyline {
  std::vector<Eigen::Vector2d> points;
  bool closed = false;
  bool whole = false;  // keep as an outline (polylines, circles, ellipses, splines)
  std::string layer;
};

struct Label {
  Eigen::Vector2d position;
  std::string text;
  double height = 0.0;
  std::string layer;
};

struct Insert {
  std::string block;
  std::string layer;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d scale = Eigen::Vector2d::Ones();
  double rotation = 0.0;  // radians
  int cols = 1, rows = 1;
  double col_spacing = 0.0, row_spacing = 0.0;
  bool mirrored_ocs = false;  // extrusion (0,0,-1)
};

struct Container {
  Eigen::Vector2d base = Eigen::Vector2d::Zero();
  std::vector<Polyline> polylines;
  std::vector<Label> labels;
  std::vector<Insert> inserts;
};

// Appends points of the arc (centre c, radius r, from angle a0 going CCW by sweep (may be negative)),
// excluding the first point, with chords no further than `tolerance` from the arc.
int append_arc(const Eigen::Vector2d& c, double r, double a0, double sweep, double tolerance,
               std::vector<Eigen::Vector2d>* out) {
  r = std::abs(r);
  int pieces = 1;
  if (r > tolerance) {
    const double step = 2.0 * std::acos(std::clamp(1.0 - tolerance / r, -1.0, 1.0));
    pieces = static_cast<int>(std::ceil(std::abs(sweep) / std::max(step, 1e-9)));
  }
  pieces = std::clamp(pieces, std::abs(sweep) > 1e-12 ? 2 : 1, kMaxArcPieces);
  for (int k = 1; k <= pieces; ++k) {
    const double a = a0 + sweep * k / pieces;
    out->push_back(c + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return pieces;
}

// Points of the bulged segment p -> q (bulge = tan(included angle / 4), positive = CCW), excluding p.
void append_bulge(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double bulge, double tolerance,
                  std::vector<Eigen::Vector2d>* out, int* arcs) {
  const double chord = (q - p).norm();
  if (std::abs(bulge) < 1e-9 || chord <= 0.0 || !std::isfinite(bulge)) {
    out->push_back(q);
    return;
  }
  bulge = std::clamp(bulge, -1e6, 1e6);
  const double sweep = 4.0 * std::atan(bulge);
  const double radius = chord / (2.0 * std::sin(std::abs(sweep) / 2.0));
  const Eigen::Vector2d mid = 0.5 * (p + q);
  const Eigen::Vector2d dir = (q - p) / chord;
  const Eigen::Vector2d left(-dir.y(), dir.x());
  // Distance from the chord's midpoint to the centre, signed towards the left for a CCW arc under pi.
  const double h = radius * std::cos(std::abs(sweep) / 2.0);
  const Eigen::Vector2d centre = mid + (sweep > 0 ? 1.0 : -1.0) * h * left;
  const double a0 = std::atan2(p.y() - centre.y(), p.x() - centre.x());
  append_arc(centre, radius, a0, sweep, tolerance, out);
  out->back() = q;  // exact end
  ++*arcs;
}

// A non-uniform rational B-spline evaluated with de Boor's algorithm.
Eigen::Vector2d eval_spline(const std::vector<Eigen::Vector3d>& ctrl_w, const std::vector<double>& knots,
                            int degree, double t) {
  const int n = static_cast<int>(ctrl_w.size());
  // The knot span holding t: knots[k] <= t < knots[k+1], degree <= k <= n-1.
  const auto span = std::upper_bound(knots.begin() + degree + 1, knots.begin() + n, t);
  const int k = static_cast<int>(span - knots.begin()) - 1;
  std::vector<Eigen::Vector3d> d(degree + 1);
  for (int j = 0; j <= degree; ++j) d[j] = ctrl_w[k - degree + j];
  for (int r = 1; r <= degree; ++r)
    for (int j = degree; j >= r; --j) {
      const int i = k - degree + j;
      const double denom = knots[i + degree + 1 - r] - knots[i];
      const double alpha = denom > 0.0 ? (t - knots[i]) / denom : 0.0;
      d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j];
    }
  const double w = std::abs(d[degree].z()) > 1e-300 ? d[degree].z() : 1.0;
  return {d[degree].x() / w, d[degree].y() / w};
}

class Collector : public DL_CreationAdapter {
 public:
  explicit Collector(double arc_tolerance) : arc_tolerance_(arc_tolerance) { current_ = &model_; }

  int insunits = -1;
  std::map<std::string, PlanLayer> layers;
  std::map<std::string, Container> blocks;
  Container model_;
  int model_entities = 0;
  int arcs = 0;
  std::vector<std::string> warnings;
  double arc_tolerance_;

  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") insunits = value;
  }
  void addLayer(const DL_LayerData& d) override {
    PlanLayer l;
    l.name = d.name;
    const int colour = attributes.getColor();
    l.color = std::abs(colour);
    l.visible = colour >= 0 && !(d.flags & 1) && !d.off;
    layers[d.name] = l;
  }
  void addBlock(const DL_BlockData& d) override {
    finish_polyline();
    current_ = &blocks[d.name];
    current_->base = {d.bpx, d.bpy};
  }
  void endBlock() override {
    finish_polyline();
    current_ = &model_;
  }
  void addLine(const DL_LineData& d) override {
    finish_polyline();
    Polyline p;  // LINE is in WCS: no OCS mirroring
    p.points = {{d.x1, d.y1}, {d.x2, d.y2}};
    add(std::move(p));
  }
  void addArc(const DL_ArcData& d) override {
    finish_polyline();
    Polyline p;
    double a0 = d.angle1 * M_PI / 180.0, a1 = d.angle2 * M_PI / 180.0;
    double sweep = a1 - a0;
    while (sweep <= 0.0) sweep += 2.0 * M_PI;
    if (sweep > 2.0 * M_PI) sweep = std::fmod(sweep, 2.0 * M_PI);
    const Eigen::Vector2d c(d.cx, d.cy);
    p.points.push_back(c + std::abs(d.radius) * Eigen::Vector2d(std::cos(a0), std::sin(a0)));
    append_arc(c, d.radius, a0, sweep, arc_tolerance_, &p.points);
    ++arcs;
    add(ocs(std::move(p)));
  }
  void addCircle(const DL_CircleData& d) override {
    finish_polyline();
    Polyline p;
    p.whole = true;
    p.closed = true;
    const Eigen::Vector2d c(d.cx, d.cy);
    p.points.push_back(c + Eigen::Vector2d(std::abs(d.radius), 0.0));
    append_arc(c, d.radius, 0.0, 2.0 * M_PI, arc_tolerance_, &p.points);
    p.points.pop_back();  // closed: the last equals the first
    ++arcs;
    add(ocs(std::move(p)));
  }
  void addEllipse(const DL_EllipseData& d) override {
    finish_polyline();
    Polyline p;
    p.whole = true;
    const Eigen::Vector2d c(d.cx, d.cy), major(d.mx, d.my);
    const double ratio = std::clamp(std::abs(d.ratio), 1e-9, 1.0);
    const Eigen::Vector2d minor = ratio * Eigen::Vector2d(-major.y(), major.x());
    double t0 = d.angle1, t1 = d.angle2;
    double sweep = t1 - t0;
    while (sweep <= 1e-12) sweep += 2.0 * M_PI;
    if (sweep > 2.0 * M_PI + 1e-9) sweep = std::fmod(sweep, 2.0 * M_PI);
    const bool full = std::abs(sweep - 2.0 * M_PI) < 1e-9;
    const double r = major.norm();
    int pieces = 2;
    if (r > arc_tolerance_)
      pieces = static_cast<int>(std::ceil(sweep / (2.0 * std::acos(std::clamp(1.0 - arc_tolerance_ / r, -1.0, 1.0)))));
    pieces = std::clamp(pieces, 4, kMaxArcPieces);
    for (int k = 0; k <= pieces; ++k) {
      const double t = t0 + sweep * k / pieces;
      p.points.push_back(c + std::cos(t) * major + std::sin(t) * minor);
    }
    if (full) {
      p.points.pop_back();
      p.closed = true;
    }
    ++arcs;
    // ELLIPSE is in WCS, but its minor axis follows the extrusion: mirrored when it points down.
    if (extrusion_down()) {
      for (auto& q : p.points) q = c + reflect_minor(q - c, major);
    }
    add(std::move(p));
  }
  void addPolyline(const DL_PolylineData& d) override {
    finish_polyline();
    pending_ = Polyline();
    pending_.closed = (d.flags & 1) != 0;
    pending_.whole = true;
    pending_.layer = attributes.getLayer();
    pending_mirrored_ = extrusion_down();
    pending_bulges_.clear();
    in_polyline_ = true;
    old_style_ = false;
  }
  void addVertex(const DL_VertexData& d) override {
    if (!in_polyline_) return;
    if (pending_.points.size() >= 1000000) return;
    pending_.points.emplace_back(d.x, d.y);
    pending_bulges_.push_back(d.bulge);
  }
  // LWPOLYLINE: addPolyline, its vertices, endEntity. Old-style POLYLINE: addPolyline, endEntity (no
  // vertices yet), then one VERTEX entity after another until SEQEND (endSequence).
  void endEntity() override {
    if (!in_polyline_) return;
    if (pending_.points.empty()) old_style_ = true;
    if (!old_style_) finish_polyline();
  }
  void endSequence() override { finish_polyline(); }
  void addSpline(const DL_SplineData& d) override {
    finish_polyline();
    spline_degree_ = static_cast<int>(d.degree);
    spline_closed_ = (d.flags & 1) != 0;
    spline_ctrl_.clear();
    spline_knots_.clear();
    spline_fit_.clear();
    spline_layer_ = attributes.getLayer();
    in_spline_ = true;
  }
  void addControlPoint(const DL_ControlPointData& d) override {
    if (in_spline_ && spline_ctrl_.size() < 100000) {
      const double w = (std::isfinite(d.w) && d.w > 0.0) ? d.w : 1.0;
      spline_ctrl_.emplace_back(d.x * w, d.y * w, w);
    }
  }
  void addKnot(const DL_KnotData& d) override {
    if (in_spline_ && spline_knots_.size() < 100000) spline_knots_.push_back(d.k);
  }
  void addFitPoint(const DL_FitPointData& d) override {
    if (in_spline_ && spline_fit_.size() < 100000) spline_fit_.emplace_back(d.x, d.y);
  }
  void addInsert(const DL_InsertData& d) override {
    finish_polyline();
    Insert ins;
    ins.block = d.name;
    ins.layer = attributes.getLayer();
    ins.position = {d.ipx, d.ipy};
    ins.scale = {std::isfinite(d.sx) && d.sx != 0.0 ? d.sx : 1.0, std::isfinite(d.sy) && d.sy != 0.0 ? d.sy : 1.0};
    ins.rotation = d.angle * M_PI / 180.0;
    ins.cols = std::max(1, d.cols);
    ins.rows = std::max(1, d.rows);
    ins.col_spacing = d.colSp;
    ins.row_spacing = d.rowSp;
    ins.mirrored_ocs = extrusion_down();
    if (static_cast<long long>(ins.cols) * ins.rows > kMaxArrayCells) {
      warnings.push_back("INSERT of block '" + d.name + "': array of " + std::to_string(ins.cols) + " x " +
                         std::to_string(ins.rows) + " reduced to one");
      ins.cols = ins.rows = 1;
    }
    if (current_ == &model_) ++model_entities;
    current_->inserts.push_back(ins);
  }
  void addText(const DL_TextData& d) override {
    finish_polyline();
    add_label({d.ipx, d.ipy}, d.text, d.height, extrusion_down());
  }
  void addMText(const DL_MTextData& d) override {
    finish_polyline();
    add_label({d.ipx, d.ipy}, mtext_chunks_ + d.text, d.height, false);
    mtext_chunks_.clear();
  }
  void addMTextChunk(const std::string& text) override {
    if (mtext_chunks_.size() < 100000) mtext_chunks_ += text;
  }

  void finish() { finish_polyline(); }

 private:
  bool extrusion_down() {
    const double* dir = getExtrusion() ? getExtrusion()->getDirection() : nullptr;
    return dir && dir[2] < 0.0;
  }
  // OCS with extrusion (0,0,-1) to WCS: x is mirrored.
  Polyline ocs(Polyline p) {
    if (extrusion_down())
      for (auto& q : p.points) q.x() = -q.x();
    return p;
  }
  static Eigen::Vector2d reflect_minor(const Eigen::Vector2d& v, const Eigen::Vector2d& major) {
    const double len = major.norm();
    if (len <= 0.0) return v;
    const Eigen::Vector2d u = major / len;
    return 2.0 * v.dot(u) * u - v;
  }
  void add(Polyline p) {
    if (p.layer.empty()) p.layer = attributes.getLayer();
    if (current_ == &model_) ++model_entities;
    current_->polylines.push_back(std::move(p));
  }
  void add_label(const Eigen::Vector2d& at, const std::string& text, double height, bool mirrored) {
    Label l;
    l.position = mirrored ? Eigen::Vector2d(-at.x(), at.y()) : at;
    l.text = text.substr(0, 1000);
    l.height = height;
    l.layer = attributes.getLayer();
    if (current_ == &model_) ++model_entities;
    current_->labels.push_back(l);
  }
  void finish_polyline() {
    if (in_spline_) finish_spline();
    if (!in_polyline_) return;
    in_polyline_ = false;
    Polyline p;
    p.closed = pending_.closed;
    p.whole = true;
    p.layer = pending_.layer;
    const auto& v = pending_.points;
    if (v.empty()) return;
    p.points.push_back(v[0]);
    const std::size_t n = v.size();
    const std::size_t spans = pending_.closed ? n : n - 1;
    for (std::size_t i = 0; i < spans; ++i) append_bulge(v[i], v[(i + 1) % n], pending_bulges_[i], arc_tolerance_, &p.points, &arcs);
    if (pending_.closed && p.points.size() > 1) p.points.pop_back();  // the closing point repeats the first
    if (pending_mirrored_)
      for (auto& q : p.points) q.x() = -q.x();
    if (current_ == &model_) ++model_entities;
    current_->polylines.push_back(std::move(p));
  }
  void finish_spline() {
    in_spline_ = false;
    Polyline p;
    p.whole = true;
    p.closed = spline_closed_;
    p.layer = spline_layer_;
    const int n = static_cast<int>(spline_ctrl_.size());
    const int degree = spline_degree_;
    bool ok = degree >= 1 && degree <= 10 && n > degree;
    std::vector<double> knots = spline_knots_;
    if (ok && static_cast<int>(knots.size()) != n + degree + 1) {
      // Missing or inconsistent knots: a clamped uniform vector.
      knots.clear();
      for (int i = 0; i < n + degree + 1; ++i)
        knots.push_back(std::clamp(static_cast<double>(i - degree), 0.0, static_cast<double>(n - degree)));
    }
    for (std::size_t i = 1; ok && i < knots.size(); ++i)
      if (!(knots[i] >= knots[i - 1]) || !std::isfinite(knots[i])) ok = false;
    if (ok) {
      const double t0 = knots[degree], t1 = knots[n];
      if (!(t1 > t0)) ok = false;
      if (ok) {
        // Adaptive: split a parameter interval until its chord is within the tolerance of the curve.
        const Eigen::Vector2d first = eval_spline(spline_ctrl_, knots, degree, t0);
        p.points.push_back(first);
        const int initial = std::clamp(n * 4, 8, 20000);
        double prev_t = t0;
        Eigen::Vector2d prev_p = first;
        for (int k = 1; k <= initial; ++k) {
          const double t = k == initial ? t1 - 1e-12 * (t1 - t0) : t0 + (t1 - t0) * k / initial;
          refine(knots, degree, prev_t, prev_p, t, eval_spline(spline_ctrl_, knots, degree, t), 0, &p.points);
          prev_t = t;
          prev_p = p.points.back();
        }
      }
    }
    if (!ok) {
      if (spline_fit_.size() >= 2) {
        p.points = spline_fit_;
      } else if (n >= 2) {
        for (const auto& c : spline_ctrl_) p.points.emplace_back(c.x() / c.z(), c.y() / c.z());
        warnings.push_back("SPLINE with an invalid degree or knot vector drawn through its control points");
      } else {
        return;
      }
    }
    ++arcs;
    add(std::move(p));
  }
  void refine(const std::vector<double>& knots, int degree, double ta, const Eigen::Vector2d& pa, double tb,
              const Eigen::Vector2d& pb, int depth, std::vector<Eigen::Vector2d>* out) {
    const double tm = 0.5 * (ta + tb);
    const Eigen::Vector2d pm = eval_spline(spline_ctrl_, knots, degree, tm);
    if (depth < 12 && out->size() < 200000 && distance_to_chord(pm, pa, pb) > arc_tolerance_) {
      refine(knots, degree, ta, pa, tm, pm, depth + 1, out);
      refine(knots, degree, tm, pm, tb, pb, depth + 1, out);
    } else {
      out->push_back(pb);
    }
  }
  static double distance_to_chord(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    if (len2 <= 0.0) return (p - a).norm();
    const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
    return (p - (a + t * ab)).norm();
  }

  Container* current_ = nullptr;
  Polyline pending_;
  std::vector<double> pending_bulges_;
  bool pending_mirrored_ = false;
  bool in_polyline_ = false;
  bool old_style_ = false;
  bool in_spline_ = false;
  int spline_degree_ = 3;
  bool spline_closed_ = false;
  std::vector<Eigen::Vector3d> spline_ctrl_;
  std::vector<double> spline_knots_;
  std::vector<Eigen::Vector2d> spline_fit_;
  std::string spline_layer_;
  std::string mtext_chunks_;
};

// ---------------------------------------------------------------------------------------------------------
// Stage 3: block expansion into world polylines and labels (drawing units).

struct Affine {
  Eigen::Matrix2d m = Eigen::Matrix2d::Identity();
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const { return m * p + t; }
  Affine then(const Affine& outer) const { return {outer.m * m, outer.m * t + outer.t}; }
};

struct Expander {
  const std::map<std::string, Container>& blocks;
  const std::string& name;
  std::size_t max_segments;
  std::vector<Polyline> polylines;
  std::vector<Label> labels;
  std::size_t segments = 0;
  int expanded = 0;
  std::set<std::string> missing_blocks;
  std::vector<std::string> stack;

  void expand(const Container& c, const Affine& world_from_local, const std::string& inherited_layer, int depth) {
    auto layer_of = [&](const std::string& l) { return (l == "0" && !inherited_layer.empty()) ? inherited_layer : l; };
    for (const auto& p : c.polylines) {
      Polyline q = p;
      q.layer = layer_of(p.layer);
      for (auto& pt : q.points) pt = world_from_local(pt);
      segments += q.points.size();
      if (segments > max_segments)
        throw file_error(name, "more than " + std::to_string(max_segments) +
                                   " segments after expanding blocks (nested arrays?)");
      polylines.push_back(std::move(q));
    }
    for (const auto& l : c.labels) {
      Label q = l;
      q.layer = layer_of(l.layer);
      q.position = world_from_local(l.position);
      q.height = l.height * std::sqrt(std::abs(world_from_local.m(0, 0) * world_from_local.m(1, 1) - world_from_local.m(0, 1) * world_from_local.m(1, 0)));
      labels.push_back(q);
    }
    for (const auto& ins : c.inserts) {
      auto it = blocks.find(ins.block);
      if (it == blocks.end()) {
        missing_blocks.insert(ins.block);
        continue;
      }
      if (std::find(stack.begin(), stack.end(), ins.block) != stack.end())
        throw file_error(name, "block '" + ins.block + "' contains itself (INSERT cycle)");
      if (depth >= kMaxBlockDepth)
        throw file_error(name, "blocks nested deeper than " + std::to_string(kMaxBlockDepth) + " levels");
      const Container& block = it->second;
      const double c0 = std::cos(ins.rotation), s0 = std::sin(ins.rotation);
      Eigen::Matrix2d rot;
      rot << c0, -s0, s0, c0;
      for (int r = 0; r < ins.rows; ++r)
        for (int col = 0; col < ins.cols; ++col) {
          // Block point p -> position + R * (S * (p - base) + array offset); then the INSERT's OCS mirror.
          Affine local;
          local.m = rot * ins.scale.asDiagonal();
          const Eigen::Vector2d offset(col * ins.col_spacing, r * ins.row_spacing);
          local.t = ins.position + rot * offset - local.m * block.base;
          if (ins.mirrored_ocs) {
            local.m.row(0) *= -1.0;
            local.t.x() = -local.t.x();
          }
          ++expanded;
          stack.push_back(ins.block);
          expand(block, local.then(world_from_local), layer_of(ins.layer), depth + 1);
          stack.pop_back();
        }
    }
  }
};

}  // namespace

FloorPlan import_dxf_from_memory(const std::string& bytes, const std::string& name, const DxfImportOptions& options,
                                 DxfImportReport* report_out) {
  options.check();
  DxfImportReport report;
  PrescanResult scan;
  prescan(bytes, name, &scan);

  // Units first: the chord tolerance is given in metres.
  // $INSUNITS is read by a light look-up so tessellation can use drawing units.
  int insunits = -1;
  {
    const std::size_t at = bytes.find("$INSUNITS");
    if (at != std::string::npos) {
      std::istringstream rest(bytes.substr(at, 200));
      std::string key, code, value;
      std::getline(rest, key);
      std::getline(rest, code);
      std::getline(rest, value);
      if (trim(code) == "70") insunits = std::atoi(trim(value).c_str());
    }
  }
  std::string units = options.units_override;
  if (units.empty()) {
    units = units_of_insunits(insunits);
    report.units_from_header = !units.empty();
    if (units.empty()) {
      units = "m";
      report.warnings.push_back(insunits < 0 ? "no $INSUNITS in the header: assuming metres"
                                             : "$INSUNITS " + std::to_string(insunits) + " is unitless or unknown: assuming metres");
    }
  }
  const double scale = metres_per_unit(units);
  report.units = units;

  Collector collector(options.chord_tolerance_m / scale);
  {
    std::istringstream stream(bytes);
    DL_Dxf dxf;
    try {
      if (!dxf.in(stream, &collector)) throw file_error(name, "dxflib could not read the file");
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw file_error(name, std::string("unreadable DXF: ") + e.what());
    }
    collector.finish();
  }
  for (const auto& w : collector.warnings) report.warnings.push_back(w);

  Expander expander{collector.blocks, name, options.max_segments, {}, {}, 0, 0, {}, {}};
  expander.expand(collector.model_, Affine(), "", 0);
  for (const auto& b : expander.missing_blocks) report.warnings.push_back("INSERT of undefined block '" + b + "'");
  report.blocks_expanded = expander.expanded;
  report.arcs_tessellated = collector.arcs;
  report.entities_read = collector.model_entities;
  for (const auto& [kind, count] : scan.skipped_kinds) {
    report.entities_skipped += count;
    report.warnings.push_back(std::to_string(count) + " " + kind + " entit" + (count == 1 ? "y" : "ies") + " ignored");
  }

  auto wanted = [&](const std::string& layer) {
    return options.layers.empty() || std::find(options.layers.begin(), options.layers.end(), layer) != options.layers.end();
  };
  auto occludes = [&](const std::string& layer) {
    if (options.occluder_layers.empty()) return guess_layer_is_occluder(layer);
    return std::find(options.occluder_layers.begin(), options.occluder_layers.end(), layer) != options.occluder_layers.end();
  };

  FloorPlan plan;
  plan.source_file = name;
  plan.units = units;
  plan.metres_per_unit = scale;
  std::map<std::string, PlanLayer> layers = collector.layers;
  auto touch_layer = [&](const std::string& l) -> PlanLayer& {
    PlanLayer& layer = layers[l];
    layer.name = l;
    return layer;
  };
  auto to_metres = [&](const Eigen::Vector2d& p, const std::string& what) {
    const Eigen::Vector2d m = p * scale;
    if (!m.allFinite() || m.cwiseAbs().maxCoeff() > options.max_coordinate_m) {
      std::ostringstream msg;
      msg << "absurd coordinate (" << p.x() << ", " << p.y() << ") " << units << " in " << what
          << " (beyond " << options.max_coordinate_m << " m)";
      throw file_error(name, msg.str());
    }
    return m;
  };
  std::vector<PlanSegment> raw_segments;
  for (const auto& p : expander.polylines) {
    ++touch_layer(p.layer).entity_count;
    if (!wanted(p.layer)) {
      ++report.entities_skipped;
      continue;
    }
    std::vector<Eigen::Vector2d> pts;
    for (const auto& q : p.points) pts.push_back(to_metres(q, "layer '" + p.layer + "'"));
    const std::size_t n = pts.size();
    if (n < 2) continue;
    const std::size_t spans = p.closed && n > 2 ? n : n - 1;
    for (std::size_t i = 0; i < spans; ++i) {
      PlanSegment s;
      s.a = pts[i];
      s.b = pts[(i + 1) % n];
      s.layer = p.layer;
      raw_segments.push_back(s);
    }
    if (p.whole) plan.outlines.push_back({pts, p.layer, p.closed});
  }
  for (const auto& l : expander.labels) {
    ++touch_layer(l.layer).entity_count;
    if (!wanted(l.layer)) continue;
    plan.labels.push_back({to_metres(l.position, "a label"), l.text, l.height * scale, l.layer});
  }

  CleanupCounts counts;
  plan.segments = clean_segments(raw_segments, options.snap_tolerance_m, &counts);
  report.snapped_endpoints = counts.snapped_endpoints;
  report.zero_length_dropped = counts.zero_length_dropped;
  report.duplicates_dropped = counts.duplicates_dropped;
  report.collinear_merged = counts.collinear_merged;
  report.intersections_split = counts.intersections_split;

  for (auto& [layer_name, layer] : layers) {
    if (!wanted(layer_name)) continue;
    layer.occluder = occludes(layer_name);
    plan.layers.push_back(layer);
  }
  for (auto& s : plan.segments) {
    const PlanLayer* l = plan.find_layer(s.layer);
    s.occluder = l && l->occluder;
  }
  if (plan.segments.empty() && plan.labels.empty()) {
    std::string what = "no usable geometry (no lines, arcs, polylines or blocks";
    what += options.layers.empty() ? ")" : " on the chosen layers)";
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
