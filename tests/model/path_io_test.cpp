#include "model/path_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "model/error.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

std::string temp_file(const std::string& name) {
  return (fs::temp_directory_path() / ("plenopath_path_io_" + name)).string();
}

TEST(PathIo, ReadsTheDocumentedSchema) {
  const std::string f = temp_file("schema.json");
  std::ofstream(f) << R"({"units":"m","frames":[)"
                      R"({"index":1,"file":"frames/000001.jpg","x":1.5,"y":-2.0,"heading_deg":90.0},)"
                      R"({"index":0,"file":"frames/000000.jpg","x":1.0,"y":2.0,"heading_deg":35.0}]})";
  const CameraPath p = read_path_file(f);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p.frames[0].index, 0);  // sorted by index
  EXPECT_EQ(p.frames[0].file, "frames/000000.jpg");
  EXPECT_DOUBLE_EQ(p.frames[0].x, 1.0);
  EXPECT_DOUBLE_EQ(p.frames[0].y, 2.0);
  EXPECT_NEAR(p.frames[0].heading, 35.0 * M_PI / 180.0, 1e-15);
  EXPECT_NEAR(p.frames[1].heading, M_PI / 2, 1e-15);
  EXPECT_NEAR(p.length(), std::hypot(0.5, 4.0), 1e-12);
  EXPECT_NE(p.find_frame(1), nullptr);
  EXPECT_EQ(p.find_frame(7), nullptr);
  fs::remove(f);
}

TEST(PathIo, ConvertsUnitsToMetres) {
  const std::string f = temp_file("mm.json");
  std::ofstream(f) << R"({"units":"mm","frames":[{"index":0,"x":1500,"y":-250,"heading_deg":0}]})";
  const CameraPath p = read_path_file(f);
  EXPECT_DOUBLE_EQ(p.frames[0].x, 1.5);
  EXPECT_DOUBLE_EQ(p.frames[0].y, -0.25);
  std::ofstream(f) << R"({"units":"furlong","frames":[]})";
  EXPECT_THROW(read_path_file(f), Error);
  fs::remove(f);
}

TEST(PathIo, RoundTripsFlagsAndConfidence) {
  CameraPath p;
  p.scale_source = "camera_height";
  for (int i = 0; i < 50; ++i) {
    PathFrame f;
    f.index = i;
    f.x = std::sin(i * 0.1) * 3;
    f.y = i * 0.08;
    f.heading = wrap_angle(i * 0.37);
    f.confidence = 1.0 / (1 + i);
    f.flags = static_cast<std::uint32_t>(i % 4);
    f.reason = i % 4 ? "flag " + std::to_string(i) : "";
    p.frames.push_back(f);
  }
  const std::string f = temp_file("rt.json");
  write_path_file(p, f);
  const CameraPath q = read_path_file(f);
  ASSERT_EQ(q.size(), p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_NEAR(q.frames[i].heading, p.frames[i].heading, 1e-13);
  }
  CameraPath q2 = q;
  for (std::size_t i = 0; i < p.size(); ++i) q2.frames[i].heading = p.frames[i].heading;
  EXPECT_EQ(q2, p);
  fs::remove(f);
}

TEST(PathIo, ErrorsNameFileAndField) {
  const std::string f = temp_file("bad.json");
  std::ofstream(f) << R"({"frames":[{"index":0,"x":1,"y":2}]})";
  try {
    read_path_file(f);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json: /frames/0: missing field 'heading_deg'"),
              std::string::npos)
        << e.what();
  }
  fs::remove(f);
}

// A path in pieces, written by hand as the format documents it: frames carry their piece, the pieces their
// range, placement and why the one before ended; lengths do not count the jump from one piece to the next.
TEST(PathIo, ReadsPiecesAndKeepsThemApart) {
  const std::string f = temp_file("pieces.json");
  std::ofstream(f)
      << R"({"units":"m","frames":[)"
         R"({"index":0,"x":0,"y":0,"heading_deg":0},{"index":1,"x":3,"y":4,"heading_deg":0},)"
         R"({"index":5,"x":0,"y":0,"heading_deg":0,"piece":1},)"
         R"({"index":6,"x":1,"y":0,"heading_deg":0,"piece":1}],)"
         R"("pieces":[{"first_index":0,"last_index":1,"placed":true,"scale_source":"camera_height"},)"
         R"({"first_index":5,"last_index":6,"placed":false,"scale_factor":0.5,)"
         R"("break_reason":"nothing connects"}]})";
  const CameraPath p = read_path_file(f);
  ASSERT_EQ(p.piece_count(), 2);
  EXPECT_TRUE(p.piece_placed(0));
  EXPECT_FALSE(p.piece_placed(1));
  EXPECT_EQ(p.pieces[1].first_index, 5);
  EXPECT_EQ(p.pieces[1].break_reason, "nothing connects");
  EXPECT_EQ(p.pieces[1].scale_factor, 0.5);
  EXPECT_EQ(p.frames[2].piece, 1);
  EXPECT_DOUBLE_EQ(p.length(), 5.0 + 1.0);  // 3-4-5 in piece 0, 1 m in piece 1, nothing between
  const CameraPath second = p.piece_path(1);
  ASSERT_EQ(second.size(), 2u);
  EXPECT_EQ(second.frames[0].index, 5);
  EXPECT_EQ(second.frames[0].piece, 0);
  // Round trip.
  write_path_file(p, f);
  EXPECT_EQ(read_path_file(f), p);
  // Renumbering tracker frames 0..3 to capture positions moves the pieces' ranges with them.
  CameraPath tracked = p;
  for (int i = 0; i < 4; ++i) tracked.frames[i].index = i;
  tracked.pieces[0] = {0, 1, true, "", 1.0, ""};
  tracked.pieces[1] = {2, 3, false, "", 1.0, "x"};
  renumber_frames(&tracked, {10, 12, 20, 22});
  EXPECT_EQ(tracked.frames[3].index, 22);
  EXPECT_EQ(tracked.pieces[1].first_index, 20);
  EXPECT_EQ(tracked.pieces[0].last_index, 12);
  EXPECT_THROW(renumber_frames(&tracked, {1, 2}), Error);
}

TEST(PathIo, PiecesThatDoNotAddUpAreRefused) {
  const std::string f = temp_file("bad_pieces.json");
  std::ofstream(f) << R"({"units":"m","frames":[{"index":0,"x":0,"y":0,"heading_deg":0,"piece":2}],)"
                      R"("pieces":[{"first_index":0,"last_index":0}]})";
  try {
    read_path_file(f);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(f), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("piece 2"), std::string::npos);
  }
  std::ofstream(f) << R"({"units":"m","frames":[{"index":0,"x":0,"y":0,"heading_deg":0,"piece":1},)"
                      R"({"index":1,"x":0,"y":0,"heading_deg":0,"piece":0}],)"
                      R"("pieces":[{"first_index":0,"last_index":0},{"first_index":1,"last_index":1}]})";
  EXPECT_THROW(read_path_file(f), Error);
}

TEST(Angles, WrapIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrap_angle(M_PI), M_PI);
  EXPECT_DOUBLE_EQ(wrap_angle(-M_PI), M_PI);
  EXPECT_NEAR(wrap_angle(3 * M_PI + 0.1), -M_PI + 0.1, 1e-12);
  EXPECT_NEAR(wrap_angle(-0.2), -0.2, 1e-15);
}

}  // namespace
}  // namespace plenopath
