// The GPS track readers (GPX through expat, NMEA 0183, GeoJSON) against hand-computed values and against
// gpsbabel, an independent converter: one GPX written by hand, converted by gpsbabel to NMEA, read by both
// readers, must give the same track.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>

#include "model/error.h"
#include "processing/capture/gps_track.h"
#include "tests/processing/capture/capture_test_util.h"

namespace plenopath {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kTwoPoints =
    "<trkseg>\n"
    "<trkpt lat=\"47.3769\" lon=\"8.5417\"><ele>408.5</ele><time>2024-05-01T10:20:30Z</time></trkpt>\n"
    "<trkpt lat=\"47.37695\" lon=\"8.54178\"><ele>409.0</ele><time>2024-05-01T10:20:31Z</time></trkpt>\n"
    "</trkseg>";

TEST(GpxReader, CharacterReferencesBecomeUtf8AndCdataStaysLiteral) {
  const GpsTrack t = parse_gpx(std::string("<gpx><trk><name>Caf&#xE9; &#8364; <![CDATA[a&amp;b]]></name>") +
                                   kTwoPoints + "</trk></gpx>",
                               "r.gpx");
  EXPECT_EQ(t.name, "Caf\xC3\xA9 \xE2\x82\xAC a&amp;b");
  ASSERT_EQ(t.samples.size(), 2u);
  EXPECT_DOUBLE_EQ(t.epoch_unix_s, 1714558830.0);
  EXPECT_DOUBLE_EQ(t.samples[1].time_s, 1.0);
  EXPECT_DOUBLE_EQ(t.samples[1].altitude_m, 409.0);
}

TEST(GpxReader, HonoursTheEncodingDeclaration) {
  // The same name in three encodings: ISO-8859-1 and windows-1252 single bytes, and UTF-16 with a BOM.
  const std::string body = std::string("<gpx><trk><name>Caf\xE9 \x80</name>") + kTwoPoints + "</trk></gpx>";
  const GpsTrack cp1252 = parse_gpx("<?xml version=\"1.0\" encoding=\"windows-1252\"?>" + body, "w.gpx");
  EXPECT_EQ(cp1252.name, "Caf\xC3\xA9 \xE2\x82\xAC");
  const std::string latin1_body = std::string("<gpx><trk><name>Caf\xE9</name>") + kTwoPoints + "</trk></gpx>";
  EXPECT_EQ(parse_gpx("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>" + latin1_body, "l.gpx").name,
            "Caf\xC3\xA9");

  const std::string ascii =
      std::string("<?xml version=\"1.0\" encoding=\"UTF-16\"?><gpx><trk><name>Caf&#233;</name>") +
      kTwoPoints + "</trk></gpx>";
  std::string utf16 = "\xFF\xFE";
  for (char c : ascii) utf16 += std::string{c, '\0'};
  const GpsTrack wide = parse_gps_track(utf16, "u.gpx");
  EXPECT_EQ(wide.name, "Caf\xC3\xA9");
  EXPECT_EQ(wide.samples.size(), 2u);

  EXPECT_NE(error_of([&] {
              parse_gpx("<?xml version=\"1.0\" encoding=\"EBCDIC-XYZ\"?>" + body, "e.gpx");
            }).find("e.gpx: line 1"),
            std::string::npos);
}

TEST(GpxReader, NamespacesAndPrefixesReadAlike) {
  const GpsTrack plain = parse_gpx(
      std::string("<gpx xmlns=\"http://www.topografix.com/GPX/1/1\"><trk>") + kTwoPoints + "</trk></gpx>",
      "a.gpx");
  const std::string prefixed =
      "<g:gpx xmlns:g=\"http://www.topografix.com/GPX/1/0\"><g:trk><g:trkseg>\n"
      "<g:trkpt lat=\"47.3769\" "
      "lon=\"8.5417\"><g:ele>408.5</g:ele><g:time>2024-05-01T10:20:30Z</g:time></g:trkpt>\n"
      "<g:trkpt lat=\"47.37695\" lon=\"8.54178\"><g:ele>409.0</g:ele><g:time>2024-05-01T10:20:31Z</g:time>"
      "</g:trkpt>\n</g:trkseg></g:trk></g:gpx>";
  const GpsTrack pre = parse_gpx(prefixed, "b.gpx");
  ASSERT_EQ(pre.samples.size(), plain.samples.size());
  EXPECT_DOUBLE_EQ(pre.samples[1].latitude_deg, plain.samples[1].latitude_deg);
  EXPECT_DOUBLE_EQ(pre.samples[1].altitude_m, 409.0);
  EXPECT_DOUBLE_EQ(pre.samples[1].time_s, 1.0);
}

TEST(GpxReader, ExternalEntitiesAreNeverFetched) {
  test::TempFolder dir;
  const std::string secret = dir / "secret.txt";
  std::ofstream(secret) << "SECRET";
  const std::string doc = "<?xml version=\"1.0\"?><!DOCTYPE gpx [<!ENTITY x SYSTEM \"file://" + secret +
                          "\">]><gpx><trk><name>n&x;</name>" + kTwoPoints + "</trk></gpx>";
  std::string name;
  try {
    name = parse_gpx(doc, "x.gpx").name;
  } catch (const Error& e) {
    name = e.what();
  }
  EXPECT_EQ(name.find("SECRET"), std::string::npos) << name;
}

TEST(GpxReader, MalformedXmlNamesFileAndLine) {
  const std::string mismatched = error_of([] { parse_gpx("<gpx>\n<trk>\n</trkseg></gpx>", "m.gpx"); });
  EXPECT_NE(mismatched.find("m.gpx: line 3"), std::string::npos) << mismatched;
  const std::string truncated =
      error_of([] { parse_gpx("<gpx><trk><trkseg><trkpt lat=\"1\" lon=\"2\">", "t.gpx"); });
  EXPECT_NE(truncated.find("t.gpx"), std::string::npos) << truncated;
  EXPECT_NE(error_of([] { parse_gpx("", "empty.gpx"); }).find("empty.gpx"), std::string::npos);
}

TEST(NmeaReader, ReadsTheReferenceSentences) {
  // The NMEA 0183 reference example: 12:35:19 UTC on 23 March 1994 at 48 deg 07.038' N, 11 deg 31.000' E,
  // 545.4 m (Unix time 764426119 by `date -u -d '1994-03-23 12:35:19' +%s`).
  const GpsTrack t = parse_nmea(
      "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\r\n"
      "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n",
      "ref.nmea");
  ASSERT_EQ(t.samples.size(), 1u);
  EXPECT_DOUBLE_EQ(t.epoch_unix_s, 764426119.0);
  EXPECT_NEAR(t.samples[0].latitude_deg, 48.0 + 7.038 / 60.0, 1e-12);
  EXPECT_NEAR(t.samples[0].longitude_deg, 11.0 + 31.0 / 60.0, 1e-12);
  EXPECT_DOUBLE_EQ(t.samples[0].altitude_m, 545.4);
  EXPECT_TRUE(t.notes.empty());
}

TEST(NmeaReader, SkipsBadSentencesAndSaysSo) {
  const GpsTrack t = parse_nmea(
      "garbage line\n"
      "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6B\n"  // checksum off by one
      "$GPRMC,123520,V,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W\n"     // no fix
      "$GNRMC,123521,A,4807.038,S,01131.000,W,022.4,084.4,230394,003.1,W\n"     // no checksum: allowed
      "$GPRMC,123522,A,48x7.038,N,01131.000,E,022.4,084.4,230394,003.1,W\n",    // bad latitude
      "bad.nmea");
  ASSERT_EQ(t.samples.size(), 1u);
  EXPECT_NEAR(t.samples[0].latitude_deg, -(48.0 + 7.038 / 60.0), 1e-12);
  EXPECT_NEAR(t.samples[0].longitude_deg, -(11.0 + 31.0 / 60.0), 1e-12);
  ASSERT_EQ(t.notes.size(), 3u);
  EXPECT_NE(t.notes[0].find("1 sentences with a bad checksum"), std::string::npos) << t.notes[0];
  const std::string none = error_of([] { parse_nmea("$GPGSA,A,3,,,,,,,,,,,,,0.0,0.0,0.0*32\n", "n.nmea"); });
  EXPECT_NE(none.find("n.nmea"), std::string::npos) << none;
  EXPECT_NE(none.find("no position"), std::string::npos) << none;
}

TEST(NmeaReader, GgaAloneCountsDaysAcrossMidnight) {
  const GpsTrack t = parse_nmea(
      "$GPGGA,235959,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,\n"
      "$GPGGA,000001,4807.038,N,01131.000,E,1,08,0.9,546.0,M,46.9,M,,\n",
      "gga.nmea");
  ASSERT_EQ(t.samples.size(), 2u);
  EXPECT_DOUBLE_EQ(t.samples[1].time_s, 2.0);
  EXPECT_DOUBLE_EQ(t.samples[1].altitude_m, 546.0);
  ASSERT_FALSE(t.notes.empty());
  EXPECT_NE(t.notes[0].find("date is unknown"), std::string::npos);
}

TEST(GpsReaders, GpsbabelsNmeaOfAGpxReadsBackAsTheSameTrack) {
  test::TempFolder dir;
  const std::string gpx = dir / "walk.gpx", nmea = dir / "walk.nmea";
  std::ofstream out(gpx);
  out << "<?xml version=\"1.0\"?>\n<gpx version=\"1.1\" creator=\"test\" "
         "xmlns=\"http://www.topografix.com/GPX/1/1\"><trk><trkseg>\n";
  for (int i = 0; i < 20; ++i) {
    // One sample a second from 23:59:50, across midnight.
    const std::string time =
        i < 10 ? "2024-05-01T23:59:5" + std::to_string(i) : "2024-05-02T00:00:0" + std::to_string(i - 10);
    out << "<trkpt lat=\"" << 47.3769 + 1e-5 * i << "\" lon=\"" << 8.5417 + 2e-5 * i * (i % 3) << "\"><ele>"
        << 400 + 0.5 * i << "</ele><time>" << time << "Z</time><fix>3d</fix><sat>7</sat></trkpt>\n";
  }
  out << "</trkseg></trk></gpx>\n";
  out.close();
  const std::string command = "gpsbabel -i gpx -f '" + gpx + "' -o nmea -F '" + nmea + "'";
  ASSERT_EQ(std::system(command.c_str()), 0)
      << command << " (gpsbabel is installed by cmake/install-deps.sh)";

  const GpsTrack a = read_gps_track(gpx), b = read_gps_track(nmea);
  ASSERT_EQ(a.samples.size(), 20u);
  ASSERT_EQ(b.samples.size(), 20u);
  EXPECT_DOUBLE_EQ(a.epoch_unix_s, b.epoch_unix_s);
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    EXPECT_DOUBLE_EQ(a.samples[i].time_s, b.samples[i].time_s) << i;
    // NMEA keeps thousandths of a minute: 1/60000 deg.
    EXPECT_NEAR(a.samples[i].latitude_deg, b.samples[i].latitude_deg, 1.0 / 60000.0) << i;
    EXPECT_NEAR(a.samples[i].longitude_deg, b.samples[i].longitude_deg, 1.0 / 60000.0) << i;
    EXPECT_NEAR(a.samples[i].altitude_m, b.samples[i].altitude_m, 1e-3) << i;
  }
  EXPECT_DOUBLE_EQ(b.samples[19].time_s, 19.0) << "across midnight, on the RMC dates";
}

TEST(GeoJsonReader, ReadsCoordTimesAndPointFeatures) {
  const GpsTrack line = parse_gps_track(
      R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"walk",
      "coordTimes":["2024-05-01T10:20:30Z","2024-05-01T10:20:32.5Z"]},
      "geometry":{"type":"LineString","coordinates":[[8.5417,47.3769,408.5],[8.5418,47.3770]]}}]})",
      "line.geojson");
  EXPECT_EQ(line.name, "walk");
  ASSERT_EQ(line.samples.size(), 2u);
  EXPECT_DOUBLE_EQ(line.epoch_unix_s, 1714558830.0);
  EXPECT_DOUBLE_EQ(line.samples[1].time_s, 2.5);
  EXPECT_DOUBLE_EQ(line.samples[0].longitude_deg, 8.5417) << "GeoJSON is [longitude, latitude]";
  EXPECT_DOUBLE_EQ(line.samples[0].altitude_m, 408.5);

  const GpsTrack points = parse_geojson_track(
      R"({"type":"FeatureCollection","features":[
      {"type":"Feature","properties":{"time":1714558831000},"geometry":{"type":"Point","coordinates":[8.6,47.4]}},
      {"type":"Feature","properties":{"time":"2024-05-01T10:20:30Z"},"geometry":{"type":"Point","coordinates":[8.5,47.3]}},
      {"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[8.7,47.5]}}]})",
      "p.json");
  ASSERT_EQ(points.samples.size(), 2u);
  EXPECT_DOUBLE_EQ(points.samples[0].latitude_deg, 47.3) << "sorted by time";
  EXPECT_DOUBLE_EQ(points.samples[1].time_s, 1.0);
  EXPECT_EQ(points.samples_without_time, 1);

  const std::string swapped = error_of([] {
    parse_geojson_track(R"({"type":"Feature","properties":{"time":0},
      "geometry":{"type":"Point","coordinates":[47.3,100.5]}})",
                        "s.geojson");
  });
  EXPECT_NE(swapped.find("s.geojson"), std::string::npos) << swapped;
  EXPECT_NE(swapped.find("latitude"), std::string::npos) << swapped;
  EXPECT_NE(error_of([] { parse_gps_track("PK\x03\x04", "z.gpx"); }).find("not a GPS track"),
            std::string::npos);
}

}  // namespace
}  // namespace plenopath
