// The interop files of an export with cube tiles (pannellum.json, marzipano-data.js, psv.json, tour.json's
// "tiles") against hand-computed values: every tile the description names is in the package and no other,
// north offsets and map positions from the poses, hotspots only where the plan lets them be seen, and
// tour.json valid against its schema (python3-jsonschema). The real readers: tests/app/viewer_check.py.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>

#include "model/json_reader.h"
#include "processing/export/psv_export.h"
#include "processing/export/tour_export.h"
#include "processing/export/tour_interop.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

// Three keyframes in a 4 m x 3 m room with a short wall at y = 1.8 between x = 2 and 3.5; headings 0, 90, 30
// degrees; a note on the north wall at (0.5, 3.0), 1.6 m up, which the wall hides from keyframe 2.
Project make_project(const fs::path& dir) {
  Project p;
  p.plan.segments = {{{0, 0}, {4, 0}, "WALLS", true},
                     {{4, 0}, {4, 3}, "WALLS", true},
                     {{4, 3}, {0, 3}, "WALLS", true},
                     {{0, 3}, {0, 0}, "WALLS", true},
                     {{2.0, 1.8}, {3.5, 1.8}, "WALLS", true}};
  fs::create_directories(dir / "frames");
  const double headings[] = {0.0, 90.0, 30.0};
  for (int i = 0; i < 3; ++i) {
    cv::Mat image(256, 512, CV_8UC3);
    cv::randu(image, 0, 255);
    char name[32];
    std::snprintf(name, sizeof name, "%06d.png", i);
    cv::imwrite((dir / "frames" / name).string(), image);
    p.capture.frame_names.push_back(name);
    p.path.frames.push_back(
        {i, std::string("frames/") + name, 1.0 + i, 1.5, radians(headings[i]), 1.0, 0, ""});
  }
  p.capture.kind = CaptureKind::kImageFolder;
  p.capture.source = (dir / "frames").string();
  p.capture.frame_count = 3;
  p.capture.width = 512;
  p.capture.height = 256;
  p.capture.camera_height_m = 1.6;
  p.keyframes.indices = {0, 1, 2};
  p.keyframes.rank = {0, 2, 1};
  Hotspot note;
  note.id = "note";
  note.kind = HotspotKind::kEvent;
  note.title = "Note";
  note.frame = 0;
  note.world_corners = {{0.4, 3.0, 1.7}, {0.6, 3.0, 1.7}, {0.6, 3.0, 1.5}, {0.4, 3.0, 1.5}};
  note.action = HotspotAction::kOpenUrl;
  note.action_target = "https://example.org/";
  p.hotspots = {note};
  p.tour.title = "Interop";
  return p;
}

nlohmann::json read_script_json(const fs::path& file, const std::string& prefix) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  EXPECT_EQ(text.compare(0, prefix.size(), prefix), 0) << file;
  text = text.substr(prefix.size());
  return nlohmann::json::parse(text.substr(0, text.rfind(';')));
}

class InteropExport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("plenopath_interop_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    const Project p = make_project(*dir_);
    TourExportOptions options;
    options.output = (*dir_ / "tour").string();
    options.max_size = 512;
    options.preview_size = 256;
    options.tile_size = 64;  // faces of 128: levels 32 (fallback), 64, 128
    options.multires = options.pannellum = options.marzipano = options.psv = true;
    export_tour(p, options);
  }
  static void TearDownTestSuite() {
    if (!std::getenv("PLENOPATH_KEEP_TEST_OUTPUT")) fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path out() { return *dir_ / "tour"; }
  static fs::path* dir_;
};
fs::path* InteropExport::dir_ = nullptr;

TEST_F(InteropExport, EveryDescribedTileIsThereAndNoOther) {
  const nlohmann::json tour = read_json_file((out() / "tour.json").string());
  const auto& tiles = tour["tiles"];
  ASSERT_EQ(tiles["levels"].size(), 3u);
  EXPECT_EQ(tiles["levels"][0]["size"], 32);
  EXPECT_EQ(tiles["levels"][2]["size"], 128);
  EXPECT_EQ(tiles["levels"][2]["tile_size"], 64);
  std::set<std::string> described, written;
  for (const auto& k : tour["keyframes"])
    for (std::size_t level = 0; level < tiles["levels"].size(); ++level) {
      const int n =
          tiles["levels"][level]["size"].get<int>() / tiles["levels"][level]["tile_size"].get<int>();
      for (const auto& face : tiles["faces"])
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x)
            described.insert(k["tiles"].get<std::string>() + "/" + std::to_string(level) + "/" +
                             face["name"].get<std::string>() + "/" + std::to_string(y) + "_" +
                             std::to_string(x) + ".jpg");
    }
  for (const auto& e : fs::recursive_directory_iterator(out() / "tiles"))
    if (e.is_regular_file()) written.insert(fs::relative(e.path(), out()).generic_string());
  EXPECT_EQ(described.size(), 3u * 6u * (1 + 1 + 4));
  EXPECT_EQ(written, described);
}

TEST_F(InteropExport, TourJsonWithTilesValidatesAgainstTheSchema) {
  const std::string cmd =
      "/usr/bin/python3 -c \"import json,jsonschema,sys; "
      "jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))\" '" +
      (out() / "tour.json").string() + "' '" + (out() / "tour.schema.json").string() + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

TEST_F(InteropExport, PannellumHasNorthMultiresAndTheNote) {
  const nlohmann::json config = read_json_file((out() / "pannellum.json").string());
  const auto& scenes = config["scenes"];
  // No geo-anchor: north is the plan's +Y, so the bearing of the image centre is 90 deg - heading.
  EXPECT_NEAR(scenes["k0"]["northOffset"].get<double>(), 90.0, 1e-9);
  EXPECT_NEAR(scenes["k1"]["northOffset"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(scenes["k2"]["northOffset"].get<double>(), 60.0, 1e-9);
  EXPECT_EQ(scenes["k1"]["type"], "multires");
  EXPECT_EQ(scenes["k1"]["multiRes"]["path"], "tiles/k000001/%l/%s/%y_%x");
  EXPECT_EQ(scenes["k1"]["multiRes"]["maxLevel"], 2);
  EXPECT_EQ(scenes["k1"]["multiRes"]["cubeResolution"], 128);
  EXPECT_EQ(scenes["k1"]["multiRes"]["tileResolution"], 64);
  auto info = [&](const char* scene) {
    for (const auto& h : scenes[scene]["hotSpots"])
      if (h["type"] == "info") return h;
    return nlohmann::json();
  };
  // From k0 at (1, 1.5) facing +X, the note at (0.5, 3.0) lies at world angle atan2(1.5, -0.5) = 108.43 deg,
  // azimuth 0 - 108.43; at camera height, pitch 0. From k1 (facing +Y): atan2(1.5, -1.5) = 135, azimuth -45.
  ASSERT_FALSE(info("k0").is_null());
  EXPECT_NEAR(info("k0")["yaw"].get<double>(), -108.43494882, 1e-6);
  EXPECT_NEAR(info("k0")["pitch"].get<double>(), 0.0, 1e-9);
  EXPECT_EQ(info("k0")["URL"], "https://example.org/");
  EXPECT_NEAR(info("k1")["yaw"].get<double>(), -45.0, 1e-6);
  EXPECT_TRUE(info("k2").is_null()) << "the wall at y = 1.8 hides the note from k2";
  // Links keep the world direction: targetYaw sameAzimuth in every scene hotspot.
  for (const auto& [id, scene] : scenes.items())
    for (const auto& h : scene["hotSpots"]) {
      if (h["type"] == "scene") {
        EXPECT_EQ(h["targetYaw"], "sameAzimuth") << id;
      }
    }
}

TEST_F(InteropExport, MarzipanoDataOnTheSameTiles) {
  const nlohmann::json data = read_script_json(out() / "marzipano-data.js", "var APP_DATA = ");
  ASSERT_EQ(data["scenes"].size(), 3u);
  const auto& k0 = data["scenes"][0];
  EXPECT_EQ(k0["id"], "k0");
  EXPECT_EQ(k0["tiles"], "tiles/k000000");
  EXPECT_EQ(k0["faceSize"], 128);
  ASSERT_EQ(k0["levels"].size(), 3u);
  EXPECT_EQ(k0["levels"][1], (nlohmann::json{{"tileSize", 64}, {"size", 64}}));
  // k1 stands 1 m along +X: straight ahead of k0, on the floor 1.6 m down (clamped to 35 deg), and
  // Marzipano's pitch grows downwards.
  ASSERT_EQ(k0["linkHotspots"].size(), 1u);
  EXPECT_NEAR(k0["linkHotspots"][0]["yaw"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(k0["linkHotspots"][0]["pitch"].get<double>(), 35.0 * M_PI / 180, 1e-9);
  EXPECT_EQ(k0["linkHotspots"][0]["target"], "k1");
  EXPECT_EQ(k0["infoHotspots"][0]["url"], "https://example.org/");
  for (const char* f : {"marzipano.html", "marzipano-app.js"})
    EXPECT_TRUE(fs::is_regular_file(out() / f)) << f;
}

TEST_F(InteropExport, PsvNodesOnTheMap) {
  const nlohmann::json psv = read_json_file((out() / "psv.json").string());
  ASSERT_EQ(psv["nodes"].size(), 3u);
  const auto& k1 = psv["nodes"][1];
  EXPECT_EQ(k1["id"], "k1");
  EXPECT_EQ(k1["panorama"], "images/k000001_full.jpg");
  // Yaw is the compass bearing: the sphere turned by -northOffset (0 for k1, facing north).
  EXPECT_NEAR(psv["nodes"][0]["sphereCorrection"]["pan"].get<double>(), -M_PI / 2, 1e-9);
  EXPECT_NEAR(psv["nodes"][2]["sphereCorrection"]["pan"].get<double>(), -M_PI / 3, 1e-9);
  // Links at the bearing of the neighbour: from k1, k2 lies east (90 deg), k0 west (270 deg).
  ASSERT_EQ(k1["links"].size(), 2u);
  EXPECT_EQ(k1["links"][0]["nodeId"], "k0");
  EXPECT_NEAR(k1["links"][0]["position"]["yaw"].get<double>(), 3 * M_PI / 2, 1e-9);
  EXPECT_NEAR(k1["links"][1]["position"]["yaw"].get<double>(), M_PI / 2, 1e-9);
  // plan.svg spans the plan's extents plus 0.5 m at 100 px a metre: x -0.5..4.5, y 3.5 (top)..-0.5.
  EXPECT_EQ(psv["map"]["imageUrl"], "plan.svg");
  EXPECT_EQ(psv["map"]["size"]["width"], 500);
  EXPECT_EQ(psv["map"]["size"]["height"], 400);
  EXPECT_NEAR(k1["map"]["x"].get<double>(), 250.0, 1e-9);
  EXPECT_NEAR(k1["map"]["y"].get<double>(), 200.0, 1e-9);
  std::ifstream svg(out() / "plan.svg");
  std::string head;
  std::getline(svg, head);
  EXPECT_NE(head.find("width=\"500\" height=\"400\""), std::string::npos) << head;
}

TEST(InteropGeo, NorthFromTheAnchor) {
  // Plan +X 35 deg counter-clockwise from east; a keyframe facing plan +X looks along bearing 90 - 35 = 55.
  Project p;
  p.path.frames = {{0, "", 0.0, 0.0, 0.0, 1.0, 0, ""}, {1, "", 1.0, 0.0, 0.0, 1.0, 0, ""}};
  p.keyframes.indices = {0, 1};
  p.geo = {true, 48.0, 2.0, 35.0, radians(35.0), 1.0, {0.0, 0.0}};
  const std::vector<KeyframeImageFiles> images = {{0, "p0.js", "f0.jpg", ""}, {1, "p1.js", "f1.jpg", ""}};
  EXPECT_NEAR(pannellum_config(p, images)["scenes"]["k0"]["northOffset"].get<double>(), 55.0, 1e-9);
  const nlohmann::json psv = psv_tour(p, images);
  EXPECT_NEAR(psv["nodes"][0]["sphereCorrection"]["pan"].get<double>(), -radians(55.0), 1e-9);
  // The link to k1 (1 m along plan +X) at bearing 55 deg.
  EXPECT_NEAR(psv["nodes"][0]["links"][0]["position"]["yaw"].get<double>(), radians(55.0), 1e-9);
  // On plan.svg north lies 35 deg clockwise from up: the map plugin turns the image back by 35 deg.
  EXPECT_NEAR(psv["map"]["rotation"].get<double>(), radians(35.0), 1e-9);
  // gps in PSV's order: longitude, latitude, altitude; the origin of the plan is the anchor.
  EXPECT_NEAR(psv["nodes"][0]["gps"][0].get<double>(), 2.0, 1e-9);
  EXPECT_NEAR(psv["nodes"][0]["gps"][1].get<double>(), 48.0, 1e-9);
}

TEST(InteropExportOptions, TileSizeIsChecked) {
  TourExportOptions o;
  o.output = "x";
  o.tile_size = 8;
  try {
    o.check();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tile_size"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plenopath
