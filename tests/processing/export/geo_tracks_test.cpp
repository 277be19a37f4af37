// KML and GPX of the path, read by the real reader (gpsbabel) and compared with positions computed by hand.
#include "processing/export/geo_tracks.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "model/error.h"
#include "tests/processing/export/interop_test_util.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;
using interop_test::kMetresPerMilliDegreeLat;
using interop_test::kMetresPerMilliDegreeLon;

struct CsvPoint {
  double latitude = 0, longitude = 0, altitude = 0;
  std::string name;
};

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else if (c != '\r') {
      out.back() += c;
    }
  }
  return out;
}

// gpsbabel's universal CSV of a file's waypoints (kind "-w") or track points ("-t"), its header naming the
// columns. It writes 6 decimals of a degree (0.1 m) and altitudes to 0.1 m.
std::vector<CsvPoint> gpsbabel_points(const std::string& kind, const std::string& format,
                                      const fs::path& file) {
  const fs::path csv = file.string() + kind + ".csv";
  const std::string cmd = "gpsbabel " + kind + " -i " + format + " -f '" + file.string() +
                          "' -o unicsv -F '" + csv.string() + "' 2>&1";
  const interop_test::CommandResult r = interop_test::run_command(cmd);
  EXPECT_EQ(r.exit_code, 0) << cmd << "\n" << r.output;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_line(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  EXPECT_TRUE(column.count("Latitude") && column.count("Longitude") && column.count("Altitude")) << line;
  std::vector<CsvPoint> points;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split_csv_line(line);
    CsvPoint p;
    p.latitude = std::stod(cells.at(column["Latitude"]));
    p.longitude = std::stod(cells.at(column["Longitude"]));
    p.altitude = std::stod(cells.at(column["Altitude"]));
    if (column.count("Name") && column["Name"] < cells.size()) p.name = cells[column["Name"]];
    points.push_back(p);
  }
  return points;
}

class GeoTracksTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!interop_test::have_program("gpsbabel")) GTEST_SKIP() << "gpsbabel is not installed";
    dir_ = fs::temp_directory_path() / ("plenopath_geo_tracks_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }

  // The three path frames of hand_made_project(), as gpsbabel must read them: the anchor, 1/1000 deg north,
  // 1/1000 deg east; 35 m + the camera's 1.6 m (LocalCartesian's plane rises 1 mm over 111 m).
  // 1e-6 deg: gpsbabel's rounding (5e-7) and the hand computation's (2e-7).
  void expect_path(const std::vector<CsvPoint>& p) {
    ASSERT_EQ(p.size(), 3u);
    EXPECT_NEAR(p[0].latitude, 48.0, 1e-6);
    EXPECT_NEAR(p[0].longitude, 2.0, 1e-6);
    EXPECT_NEAR(p[1].latitude, 48.001, 1e-6);
    EXPECT_NEAR(p[1].longitude, 2.0, 1e-6);
    EXPECT_NEAR(p[2].latitude, 48.0, 1e-6);
    EXPECT_NEAR(p[2].longitude, 2.001, 1e-6);
    for (const CsvPoint& q : p) EXPECT_NEAR(q.altitude, 36.6, 0.051);
  }
  void expect_keyframes(const std::vector<CsvPoint>& p) {
    ASSERT_EQ(p.size(), 2u);
    EXPECT_EQ(p[0].name, "Keyframe 0");
    EXPECT_NEAR(p[0].latitude, 48.0, 1e-6);
    EXPECT_NEAR(p[0].longitude, 2.0, 1e-6);
    EXPECT_EQ(p[1].name, "Keyframe 2");
    EXPECT_NEAR(p[1].latitude, 48.0, 1e-6);
    EXPECT_NEAR(p[1].longitude, 2.001, 1e-6);
    for (const CsvPoint& q : p) EXPECT_NEAR(q.altitude, 36.6, 0.051);
  }

  fs::path dir_;
};

TEST_F(GeoTracksTest, GpsbabelReadsTheKmlPathAndKeyframes) {
  const Project p = interop_test::hand_made_project();
  const fs::path file = write("path.kml", path_kml(p));
  expect_keyframes(gpsbabel_points("-w", "kml", file));
  expect_path(gpsbabel_points("-t", "kml", file));
}

TEST_F(GeoTracksTest, GpsbabelReadsTheGpxWaypointsAndTrack) {
  const Project p = interop_test::hand_made_project();
  const fs::path file = write("path.gpx", path_gpx(p));
  expect_keyframes(gpsbabel_points("-w", "gpx", file));
  expect_path(gpsbabel_points("-t", "gpx", file));
}

TEST_F(GeoTracksTest, PiecesAreSeparateSegmentsAndTheTitleIsEscaped) {
  Project p = interop_test::hand_made_project();
  p.path.frames[2].piece = 1;
  const std::string gpx = path_gpx(p);
  // gpsbabel names each track segment it reads apart: its track listing shows two segments.
  const fs::path file = write("pieces.gpx", gpx);
  const interop_test::CommandResult r = interop_test::run_command("gpsbabel -t -i gpx -f '" + file.string() +
                                                                  "' -x track,seg2trk -o gpx -F - 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::size_t tracks = 0;
  for (std::size_t at = r.output.find("<trk>"); at != std::string::npos; at = r.output.find("<trk>", at + 1))
    ++tracks;
  EXPECT_EQ(tracks, 2u) << r.output;
  EXPECT_NE(gpx.find("Hand &lt;made&gt; &amp; placed"), std::string::npos);
  EXPECT_EQ(gpx.find("<made>"), std::string::npos);
}

TEST(GeoTracks, CompassHeadingFromTheAnchorsNorth) {
  GeoAnchor geo{true, 48.0, 2.0, 35.0, 0.0, 1.0, {0.0, 0.0}};
  // Plan +X is east: heading 0 faces east (90), 90 deg faces north (0), 200 deg faces 250.
  EXPECT_NEAR(compass_heading_deg(geo, 0.0), 90.0, 1e-9);
  EXPECT_NEAR(compass_heading_deg(geo, M_PI / 2), 0.0, 1e-9);
  EXPECT_NEAR(compass_heading_deg(geo, 200.0 * M_PI / 180), 250.0, 1e-9);
  // Plan rotated 90 deg CCW from east: plan +X points north.
  geo.plan_rotation = M_PI / 2;
  EXPECT_NEAR(compass_heading_deg(geo, 0.0), 0.0, 1e-9);
  EXPECT_NEAR(compass_heading_deg(geo, -M_PI / 2), 90.0, 1e-9);
  // Without an anchor, plan +Y is north whatever rotation is stored.
  geo.valid = false;
  EXPECT_NEAR(compass_heading_deg(geo, M_PI / 2), 0.0, 1e-9);
  EXPECT_NEAR(compass_heading_deg(geo, 0.0), 90.0, 1e-9);
}

TEST(GeoTracks, WithoutAnAnchorTheyAreAnErrorOnlyWhenAskedFor) {
  Project p = interop_test::hand_made_project();
  EXPECT_TRUE(wants_geo_tracks(GeoTrackFiles::kAuto, p));
  EXPECT_TRUE(wants_geo_tracks(GeoTrackFiles::kOn, p));
  EXPECT_FALSE(wants_geo_tracks(GeoTrackFiles::kOff, p));
  p.geo.valid = false;
  EXPECT_FALSE(wants_geo_tracks(GeoTrackFiles::kAuto, p));
  EXPECT_FALSE(wants_geo_tracks(GeoTrackFiles::kOff, p));
  try {
    wants_geo_tracks(GeoTrackFiles::kOn, p);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("geo-anchor"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("KML"), std::string::npos) << e.what();
  }
  EXPECT_THROW(path_kml(p), Error);
  EXPECT_THROW(path_gpx(p), Error);
}

}  // namespace
}  // namespace plenopath
