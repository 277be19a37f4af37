#include "processing/capture/gps_track.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "model/error.h"
#include "tests/processing/capture/capture_test_util.h"

namespace plenopath {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Metres per degree on WGS84 at latitude phi, from the standard series (independent of GeographicLib):
// along the meridian 111132.954 - 559.822 cos 2phi + 1.175 cos 4phi, along the parallel
// 111412.84 cos phi - 93.5 cos 3phi + 0.118 cos 5phi.
double metres_per_degree_north(double phi_deg) {
  const double p = phi_deg * kPi / 180.0;
  return 111132.954 - 559.822 * std::cos(2 * p) + 1.175 * std::cos(4 * p);
}
double metres_per_degree_east(double phi_deg) {
  const double p = phi_deg * kPi / 180.0;
  return 111412.84 * std::cos(p) - 93.5 * std::cos(3 * p) + 0.118 * std::cos(5 * p);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Iso8601, ParsesUtcAndOffsets) {
  EXPECT_DOUBLE_EQ(parse_iso8601_utc("2024-05-01T10:20:30Z"), 1714558830.0);  // `date -u -d ... +%s`
  EXPECT_DOUBLE_EQ(parse_iso8601_utc("2024-02-29T23:59:59.25+02:00"), 1709243999.25);
  EXPECT_DOUBLE_EQ(parse_iso8601_utc("1970-01-01T00:00:00Z"), 0.0);
  EXPECT_DOUBLE_EQ(parse_iso8601_utc("2024-05-01T10:20:30"), 1714558830.0);  // no zone: UTC
  EXPECT_THROW(parse_iso8601_utc("yesterday"), Error);
  EXPECT_THROW(parse_iso8601_utc("2024-13-01T00:00:00Z"), Error);
}

const char* kGpx = R"(<?xml version="1.0" encoding="UTF-8"?>
<!-- written by the test -->
<gpx version="1.1" creator="test" xmlns="http://www.topografix.com/GPX/1/1">
  <metadata><time>2024-05-01T10:00:00Z</time></metadata>
  <trk><name>Walk &amp; talk</name>
    <trkseg>
      <trkpt lat="47.00002" lon="8.5"><ele>402.0</ele><time>2024-05-01T10:20:32Z</time></trkpt>
      <trkpt lat="47.0" lon="8.5"><ele>400.0</ele><time>2024-05-01T10:20:30Z</time></trkpt>
      <trkpt lat='47.00001' lon='8.5'><ele>401.0</ele><time>2024-05-01T10:20:31Z</time></trkpt>
    </trkseg>
    <trkseg>
      <trkpt lat="47.00002" lon="8.50001"><time>2024-05-01T10:20:33Z</time></trkpt>
      <trkpt lat="47.00003" lon="8.50001"/>
    </trkseg>
  </trk>
</gpx>
)";

TEST(Gpx, ReadsTrackPointsSortedByTime) {
  const GpxTrack track = parse_gpx(kGpx, "walk.gpx");
  EXPECT_EQ(track.name, "Walk & talk");
  ASSERT_EQ(track.samples.size(), 4u);
  EXPECT_EQ(track.samples_without_time, 1);
  EXPECT_DOUBLE_EQ(track.epoch_unix_s, 1714558830.0);
  EXPECT_DOUBLE_EQ(track.samples[0].time_s, 0.0);
  EXPECT_DOUBLE_EQ(track.samples[0].latitude_deg, 47.0);
  EXPECT_DOUBLE_EQ(track.samples[1].time_s, 1.0);
  EXPECT_DOUBLE_EQ(track.samples[1].altitude_m, 401.0);
  EXPECT_DOUBLE_EQ(track.samples[3].longitude_deg, 8.50001);
}

TEST(Gpx, MapsFramesToPlanPositions) {
  test::TempFolder dir;
  const std::string file = dir / "walk.gpx";
  std::ofstream(file) << kGpx;
  const GpxTrack track = read_gpx(file);

  GeoAnchor anchor;
  anchor.valid = true;
  anchor.latitude_deg = 47.0;
  anchor.longitude_deg = 8.5;
  anchor.altitude_m = 400.0;
  anchor.plan_origin = Eigen::Vector2d(10.0, 20.0);
  const double north_per_step = 1e-5 * metres_per_degree_north(47.0);  // about 1.1117 m
  const double east_per_step = 1e-5 * metres_per_degree_east(47.0);    // about 0.7606 m

  // Frames at 2 fps; the capture started 0.5 s after the first GPS fix.
  GpsMatchOptions options;
  options.time_offset_s = 0.5;
  const std::vector<double> frame_times = {0.0, 0.5, 1.0, 2.0, 3.5, 10.0};
  const std::vector<FrameGps> matched = match_gps_to_frames(track.samples, frame_times, options);
  ASSERT_EQ(matched.size(), 6u);
  EXPECT_TRUE(matched[0].valid);
  EXPECT_NEAR(matched[0].latitude_deg, 47.000005, 1e-12);  // halfway between the first two fixes
  EXPECT_NEAR(matched[0].altitude_m, 400.5, 1e-9);
  EXPECT_FALSE(matched[4].valid);  // 4.0 s: past the last fix by more than max_extrapolation_s
  EXPECT_FALSE(matched[5].valid);

  const std::vector<GpsPrior> priors = gps_priors(track.samples, frame_times, anchor, options, 3.0);
  ASSERT_EQ(priors.size(), 4u);
  // Expected plan positions by hand: plan = origin + (east, north) for an unrotated, unscaled anchor.
  const std::vector<Eigen::Vector2d> expected = {
      {10.0, 20.0 + 0.5 * north_per_step},
      {10.0, 20.0 + 1.0 * north_per_step},
      {10.0, 20.0 + 1.5 * north_per_step},
      {10.0 + 0.5 * east_per_step, 20.0 + 2.0 * north_per_step},
  };
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(priors[k].frame, k);
    EXPECT_NEAR(priors[k].plan_xy.x(), expected[k].x(), 2e-3) << "frame " << k;
    EXPECT_NEAR(priors[k].plan_xy.y(), expected[k].y(), 2e-3) << "frame " << k;
    EXPECT_DOUBLE_EQ(priors[k].sigma_m, 3.0);
  }

  // A rotated, scaled anchor: plan +X points north, 2 ground metres per plan metre.
  anchor.plan_rotation = kPi / 2;
  anchor.scale = 2.0;
  const Eigen::Vector2d north_point = plan_from_wgs84(anchor, 47.00001, 8.5, 400.0);
  EXPECT_NEAR(north_point.x(), 10.0 + north_per_step / 2.0, 1e-3);
  EXPECT_NEAR(north_point.y(), 20.0, 1e-3);
  const Eigen::Vector2d east_point = plan_from_wgs84(anchor, 47.0, 8.50001, 400.0);
  EXPECT_NEAR(east_point.x(), 10.0, 1e-3);
  EXPECT_NEAR(east_point.y(), 20.0 - east_per_step / 2.0, 1e-3);  // east is plan -Y when +X is north

  GeoAnchor none;
  EXPECT_NE(error_of([&] { plan_from_wgs84(none, 47.0, 8.5); }).find("geo-anchor"), std::string::npos);
}

TEST(Gpx, GapsAreNotBridged) {
  std::vector<GpsSample> samples(2);
  samples[1].time_s = 60.0;
  samples[1].latitude_deg = 1.0;
  GpsMatchOptions options;
  options.max_gap_s = 5.0;
  EXPECT_FALSE(gps_at_time(samples, 30.0, options).valid);
  // Next to a sample at a gap's edge (a tripod still's own fix), the sample itself.
  EXPECT_TRUE(gps_at_time(samples, 0.2, options).valid);
  EXPECT_NEAR(gps_at_time(samples, 59.8, options).latitude_deg, 1.0, 1e-12);
  EXPECT_FALSE(gps_at_time(samples, 0.6, options).valid);
  options.max_gap_s = 100.0;
  const FrameGps mid = gps_at_time(samples, 30.0, options);
  EXPECT_TRUE(mid.valid);
  EXPECT_NEAR(mid.latitude_deg, 0.5, 1e-12);
}

TEST(Gpx, BadFilesGiveErrorsNamingFileAndLine) {
  EXPECT_NE(error_of([] { parse_gpx("<kml></kml>", "x.gpx"); }).find("not a GPX file"), std::string::npos);
  const std::string bad_lat = error_of([] {
    parse_gpx(
        "<gpx>\n<trk><trkseg>\n<trkpt lat=\"95\" lon=\"1\"><time>2024-01-01T00:00:00Z</time></trkpt>"
        "</trkseg></trk></gpx>",
        "bad.gpx");
  });
  EXPECT_NE(bad_lat.find("bad.gpx: line 3"), std::string::npos) << bad_lat;
  EXPECT_NE(bad_lat.find("latitude"), std::string::npos) << bad_lat;
  const std::string truncated =
      error_of([] { parse_gpx("<gpx><trk><trkseg><trkpt lat=\"1\" lon=\"2\">", "t.gpx"); });
  EXPECT_NE(truncated.find("t.gpx"), std::string::npos) << truncated;
  EXPECT_NE(error_of([] { parse_gpx("<gpx></gpx>", "e.gpx"); }).find("no track points"), std::string::npos);
  EXPECT_NE(error_of([] { read_gpx("/nonexistent/track.gpx"); }).find("/nonexistent/track.gpx"),
            std::string::npos);
  const std::string no_time = error_of(
      [] { parse_gpx("<gpx><trk><trkseg><trkpt lat=\"1\" lon=\"2\"/></trkseg></trk></gpx>", "n.gpx"); });
  EXPECT_NE(no_time.find("no <time>"), std::string::npos) << no_time;
}

}  // namespace
}  // namespace plenopath
