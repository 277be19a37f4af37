// The DXF reader's pieces against hand-made input: binary tags written byte by byte, code pages decoded
// by hand-looked-up code points, curves against their closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "model/error.h"
#include "processing/plan/dxf_curves.h"
#include "processing/plan/dxf_import.h"
#include "processing/plan/dxf_tags.h"
#include "processing/plan/dxf_text.h"

namespace plenopath {
namespace {

// A binary DXF: the sentinel, then (code, value) pairs with 2-byte (R13+) or 1-byte (R12) group codes.
class BinaryDxf {
 public:
  explicit BinaryDxf(bool one_byte_codes) : one_byte_(one_byte_codes) {
    bytes_.assign("AutoCAD Binary DXF\r\n\x1a", 21);
    bytes_.push_back('\0');
  }
  void code(int c) {
    if (one_byte_) {
      if (c < 255) {
        bytes_.push_back(static_cast<char>(c));
      } else {
        bytes_.push_back(static_cast<char>(255));
        bytes_.push_back(static_cast<char>(c & 0xFF));
        bytes_.push_back(static_cast<char>(c >> 8));
      }
    } else {
      bytes_.push_back(static_cast<char>(c & 0xFF));
      bytes_.push_back(static_cast<char>((c >> 8) & 0xFF));
    }
  }
  void text(int c, const std::string& v) {
    code(c);
    bytes_ += v;
    bytes_.push_back('\0');
  }
  void real(int c, double v) {
    code(c);
    char raw[8];
    std::memcpy(raw, &v, 8);
    bytes_.append(raw, 8);
  }
  void int16(int c, int v) {
    code(c);
    bytes_.push_back(static_cast<char>(v & 0xFF));
    bytes_.push_back(static_cast<char>((v >> 8) & 0xFF));
  }
  const std::string& bytes() const { return bytes_; }

 private:
  bool one_byte_;
  std::string bytes_;
};

std::string binary_square(bool one_byte_codes) {
  BinaryDxf b(one_byte_codes);
  b.text(0, "SECTION");
  b.text(2, "HEADER");
  b.text(9, "$INSUNITS");
  b.int16(70, 6);
  b.text(0, "ENDSEC");
  b.text(0, "SECTION");
  b.text(2, "ENTITIES");
  const double pts[5][2] = {{0, 0}, {4, 0}, {4, 3}, {0, 3}, {0, 0}};
  for (int i = 0; i < 4; ++i) {
    b.text(0, "LINE");
    b.text(8, "WALL");
    b.real(10, pts[i][0]);
    b.real(20, pts[i][1]);
    b.real(30, 0.0);
    b.real(11, pts[i + 1][0]);
    b.real(21, pts[i + 1][1]);
    b.real(31, 0.0);
  }
  b.text(0, "ENDSEC");
  b.text(0, "EOF");
  return b.bytes();
}

TEST(DxfTags, BinaryWithTwoAndOneByteCodesReadsTheSameTags) {
  for (bool one_byte : {false, true}) {
    const DxfTags tags = read_dxf_tags(binary_square(one_byte), "square.dxf");
    EXPECT_TRUE(tags.binary);
    EXPECT_TRUE(tags.reached_eof);
    ASSERT_EQ(tags.tags.size(), 5u + 2u + 4u * 8u + 2u) << one_byte;
    EXPECT_EQ(tags.tags[3].code, 70);
    EXPECT_EQ(tags.tags[3].value, "6");
    double v = 0.0;
    ASSERT_TRUE(dxf_number(tags.tags[9], &v));  // the first LINE's 10
    EXPECT_EQ(tags.tags[9].code, 10);
    EXPECT_EQ(v, 0.0);
    EXPECT_EQ(tags.tags[12].code, 11);
    ASSERT_TRUE(dxf_number(tags.tags[12], &v));  // its 11
    EXPECT_EQ(v, 4.0);
  }
}

TEST(DxfTags, BinaryPlanImportsLikeItsAsciiTwin) {
  DxfImportReport report;
  const FloorPlan plan = import_dxf_from_memory(binary_square(false), "square.dxf", {}, &report);
  EXPECT_TRUE(report.binary);
  EXPECT_EQ(plan.segments.size(), 4u);
  EXPECT_NEAR(plan.extents().size().x(), 4.0, 1e-12);
  EXPECT_NEAR(plan.extents().size().y(), 3.0, 1e-12);
  EXPECT_EQ(report.entities_by_layer["WALL"]["LINE"], 4);
  // A binary file cut in the middle of a value keeps what came before.
  const std::string cut = binary_square(false).substr(0, binary_square(false).size() - 60);
  DxfImportReport cut_report;
  const FloorPlan part = import_dxf_from_memory(cut, "cut.dxf", {}, &cut_report);
  EXPECT_GE(part.segments.size(), 2u);
  ASSERT_FALSE(cut_report.warnings.empty());
  EXPECT_NE(cut_report.warnings.front().find("byte "), std::string::npos) << cut_report.warnings.front();
}

TEST(DxfTags, AsciiResynchronisesAfterAGarbledGroupCode) {
  const std::string text =
      "0\nSECTION\n2\nENTITIES\n0\nLINE\n8\nW\nxx\n0\n20\n0\n11\n5\n21\n0\n"
      "0\nLINE\n8\nW\n10\n0\n20\n0\n11\n0\n21\n5\n0\nENDSEC\n0\nEOF\n";
  const DxfTags tags = read_dxf_tags(text, "garbled.dxf");
  ASSERT_EQ(tags.warnings.size(), 1u);
  EXPECT_NE(tags.warnings[0].find("line 9"), std::string::npos) << tags.warnings[0];
  EXPECT_NE(tags.warnings[0].find("skipped to line 17"), std::string::npos) << tags.warnings[0];
  DxfImportReport report;
  const FloorPlan plan = import_dxf_from_memory(text, "garbled.dxf", {}, &report);
  EXPECT_EQ(plan.segments.size(), 1u);    // the second LINE
  EXPECT_EQ(report.entities_skipped, 1);  // the first, which lost its start point
  EXPECT_NE(report.skipped[0].why.find("start point"), std::string::npos) << report.skipped[0].why;
}

TEST(DxfTags, NotDxfAtAll) {
  EXPECT_THROW(read_dxf_tags("", "empty.dxf"), Error);
  EXPECT_THROW(read_dxf_tags("hello world\nthis is not\n", "words.dxf"), Error);
  EXPECT_THROW(read_dxf_tags(std::string("AC1018\0\0\0binary", 16), "drawing.dxf"), Error);
  try {
    read_dxf_tags(std::string("AC1027\0\0\x01", 9), "house.dxf");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("DWG"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("house.dxf"), std::string::npos) << e.what();
  }
}

TEST(DxfText, CodePagesToUtf8) {
  EXPECT_EQ(dxf_string_encoding("AC1015", "ANSI_1252"), "CP1252");
  EXPECT_EQ(dxf_string_encoding("AC1015", "ansi_936"), "GBK");
  EXPECT_EQ(dxf_string_encoding("AC1021", "ANSI_1252"), "UTF-8");  // R2007+: always UTF-8
  EXPECT_EQ(dxf_string_encoding("AC1009", ""), "CP1252");
  // "Wände" in CP1252: a-umlaut is 0xE4 -> U+00E4 = C3 A4 in UTF-8.
  EXPECT_EQ(dxf_to_utf8("W\xE4nde", "CP1252"), "W\xC3\xA4nde");
  // GBK 0xC7BD is U+5899 (wall) -> E5 A2 99.
  EXPECT_EQ(dxf_to_utf8("\xC7\xBD", "GBK"), "\xE5\xA2\x99");
  // A UTF-8 file with a stray CP1252 byte: read as CP1252 rather than broken.
  EXPECT_EQ(dxf_to_utf8("caf\xE9", "UTF-8"), "caf\xC3\xA9");
  // A byte CP1252 leaves undefined (0x81) becomes U+FFFD, never invalid UTF-8.
  EXPECT_EQ(valid_utf8(dxf_to_utf8("a\x81z", "CP1252")), dxf_to_utf8("a\x81z", "CP1252"));
  EXPECT_EQ(valid_utf8("ok\xFF"), "ok\xEF\xBF\xBD");
}

TEST(DxfText, EscapesAndMtextFormatting) {
  EXPECT_EQ(dxf_decode_escapes("90%%d"), "90\xC2\xB0");
  EXPECT_EQ(dxf_decode_escapes("%%c50 %%p1"),
            "\xE2\x8C\x80"
            "50 \xC2\xB1"
            "1");
  EXPECT_EQ(dxf_decode_escapes("\\U+00B0C"),
            "\xC2\xB0"
            "C");
  EXPECT_EQ(dxf_decode_escapes("\\U+4F1A\\U+8BAE"), "\xE4\xBC\x9A\xE8\xAE\xAE");
  EXPECT_EQ(dxf_decode_escapes("100%%%"), "100%");
  EXPECT_EQ(dxf_decode_escapes("a^Ib"), "a b");
  EXPECT_EQ(dxf_decode_escapes("x^ y"), "x^y");
  EXPECT_EQ(dxf_plain_mtext("{\\fArial|b1|i0|c0|p34;Room}\\P\\H2.5x;{\\C1;red} 1\\S1^2;"), "Room\nred 11/2");
  EXPECT_EQ(dxf_plain_mtext("a\\~b \\\\ \\{c\\}"), "a b \\ {c}");
  EXPECT_EQ(dxf_decode_escapes(dxf_plain_mtext("\\A1;\\U+00E9t\\LE\\l")), "\xC3\xA9tE");
}

TEST(DxfCurves, ArcChordsStayWithinTheTolerance) {
  DxfCurve arc;
  arc.kind = DxfCurve::Kind::arc;
  arc.centre = {2, 1, 0};
  arc.radius = 3.0;
  arc.start = 0.3;
  arc.sweep = 2.0;
  bool closed = true;
  int arcs = 0;
  const double tol = 0.01;
  const auto pts = tessellate(arc, Eigen::Affine3d::Identity(), tol, &closed, &arcs);
  EXPECT_FALSE(closed);
  EXPECT_EQ(arcs, 1);
  ASSERT_GE(pts.size(), 3u);
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    EXPECT_NEAR((pts[i] - Eigen::Vector2d(2, 1)).norm(), 3.0, 1e-12);
    const Eigen::Vector2d mid = 0.5 * (pts[i] + pts[i + 1]);
    EXPECT_LE(3.0 - (mid - Eigen::Vector2d(2, 1)).norm(), tol + 1e-12);  // sagitta
  }
  EXPECT_NEAR((pts.back() - Eigen::Vector2d(2 + 3 * std::cos(2.3), 1 + 3 * std::sin(2.3))).norm(), 0.0,
              1e-12);
  // Scaled by 1000 (a block in mm placed in a drawing of metres): the tolerance holds in the output.
  Eigen::Affine3d scaled = Eigen::Affine3d::Identity();
  scaled.scale(1000.0);
  const auto big = tessellate(arc, scaled, tol, &closed, &arcs);
  EXPECT_GT(big.size(), 10 * pts.size());
  for (std::size_t i = 0; i + 1 < big.size(); ++i)
    EXPECT_LE(3000.0 - (0.5 * (big[i] + big[i + 1]) - Eigen::Vector2d(2000, 1000)).norm(), tol + 1e-9);
}

TEST(DxfCurves, ObjectCoordinatesWithDownwardExtrusionMirrorX) {
  // Arbitrary axis algorithm for N = (0, 0, -1): Ax = (0, 1, 0) x N = (-1, 0, 0), Ay = N x Ax = (0, 1, 0).
  const Eigen::Affine3d t = world_from_ocs({0, 0, -1});
  EXPECT_NEAR((t * Eigen::Vector3d(1, 2, 0) - Eigen::Vector3d(-1, 2, 0)).norm(), 0.0, 1e-15);
  // N = (1, 0, 0) (a vertical plane): Ax = (0, 0, 1) x N = (0, 1, 0), Ay = N x Ax = (0, 0, 1).
  const Eigen::Affine3d v = world_from_ocs({1, 0, 0});
  EXPECT_NEAR((v * Eigen::Vector3d(1, 2, 3) - Eigen::Vector3d(3, 1, 2)).norm(), 0.0, 1e-15);
}

TEST(DxfCurves, EllipsePointsLieOnTheEllipse) {
  DxfCurve e;
  e.kind = DxfCurve::Kind::ellipse;
  e.centre = {1, 1, 0};
  e.major = {4 * std::cos(0.5), 4 * std::sin(0.5), 0};
  e.minor = {-1.5 * std::sin(0.5), 1.5 * std::cos(0.5), 0};
  e.start = 0.0;
  e.sweep = 2 * M_PI;
  bool closed = false;
  int arcs = 0;
  const auto pts = tessellate(e, Eigen::Affine3d::Identity(), 0.001, &closed, &arcs);
  EXPECT_TRUE(closed);
  for (const auto& p : pts) {
    const Eigen::Vector2d d = p - Eigen::Vector2d(1, 1);
    const double u = d.dot(Eigen::Vector2d(std::cos(0.5), std::sin(0.5))) / 4.0;
    const double w = d.dot(Eigen::Vector2d(-std::sin(0.5), std::cos(0.5))) / 1.5;
    EXPECT_NEAR(u * u + w * w, 1.0, 1e-12);
  }
  for (std::size_t i = 0; i < pts.size(); ++i) {  // chord midpoints within the tolerance (inside the curve)
    const Eigen::Vector2d m = 0.5 * (pts[i] + pts[(i + 1) % pts.size()]) - Eigen::Vector2d(1, 1);
    const double u = m.dot(Eigen::Vector2d(std::cos(0.5), std::sin(0.5))) / 4.0;
    const double w = m.dot(Eigen::Vector2d(-std::sin(0.5), std::cos(0.5))) / 1.5;
    EXPECT_GT(std::sqrt(u * u + w * w), 1.0 - 0.001 / 1.5);
  }
}

double polygon_area(const std::vector<Eigen::Vector2d>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& q = p[i];
    const auto& r = p[(i + 1) % p.size()];
    a += q.x() * r.y() - r.x() * q.y();
  }
  return 0.5 * std::abs(a);
}

TEST(DxfCurves, WidePolylineBecomesItsMitredOutline) {
  // An L-shaped wall drawn as a polyline 0.2 wide: the mitred band's area is width x centreline length.
  DxfCurve wall;
  wall.points = {{0, 0, 0}, {5, 0, 0}, {5, 3, 0}};
  wall.bulges = {0, 0, 0};
  wall.widths = {{0.2, 0.2}, {0.2, 0.2}, {0.2, 0.2}};
  bool closed = false;
  int arcs = 0;
  const auto outline = tessellate(wall, Eigen::Affine3d::Identity(), 0.001, &closed, &arcs);
  EXPECT_TRUE(closed);
  EXPECT_NEAR(polygon_area(outline), 0.2 * 8.0, 1e-12);
  double max_x = -1e9, min_y = 1e9;
  for (const auto& p : outline) max_x = std::max(max_x, p.x()), min_y = std::min(min_y, p.y());
  EXPECT_NEAR(max_x, 5.1, 1e-12);  // the mitred outer corner
  EXPECT_NEAR(min_y, -0.1, 1e-12);
}

}  // namespace
}  // namespace plenopath
