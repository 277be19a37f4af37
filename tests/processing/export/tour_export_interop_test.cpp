// The interop files as export_tour writes them into a package: KML/GPX by default when georeferenced and
// never otherwise (an error only when asked for), TUM and OpenSfM on request, GPano/EXIF in every keyframe
// JPEG as exiftool reads it, matching path.geojson (tested against hand-computed positions) and the path.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "model/error.h"
#include "processing/export/tour_export.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/export/interop_test_util.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

// Six frames of the office sample rendered at 128 x 64, keyframes 0, 3 and 5, the plan anchored at 48 N 2 E
// with its +X pointing east (so a compass heading is 90 deg - the plan heading).
Project rendered_project(const fs::path& dir) {
  Project p;
  p.plan = make_office_sample_plan();
  p.tour.title = "Interop";
  CameraPath walk = auto_walk(p.plan);
  walk.frames.resize(6);
  const SyntheticScene scene = build_synthetic_scene(p.plan);
  RenderOptions render;
  render.width = 128;
  render.height = 64;
  render.depth = false;
  fs::create_directories(dir / "frames");
  for (PathFrame& f : walk.frames) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.png", f.index);
    cv::imwrite((dir / "frames" / name).string(), render_panorama(scene, f, render).rgb);
    f.file = std::string("frames/") + name;
    p.capture.frame_names.push_back(name);
  }
  p.path = walk;
  p.capture.kind = CaptureKind::kImageFolder;
  p.capture.source = (dir / "frames").string();
  p.capture.frame_count = 6;
  p.capture.width = 128;
  p.capture.height = 64;
  p.capture.camera_height_m = 1.6;
  p.keyframes.indices = {0, 3, 5};
  p.keyframes.rank = {0, 1, 2};
  p.geo = {true, 48.0, 2.0, 35.0, 0.0, 1.0, {0.0, 0.0}};
  return p;
}

nlohmann::json exiftool(const fs::path& file) {
  const interop_test::CommandResult r =
      interop_test::run_command("exiftool -j -n -G '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return nlohmann::json::parse(r.output).at(0);
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

class TourExportInteropTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ =
        new fs::path(fs::temp_directory_path() / ("plenopath_export_interop_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    project_ = new Project(rendered_project(*dir_));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete project_;
    delete dir_;
  }
  TourExportOptions options(const std::string& name) const {
    TourExportOptions o;
    o.output = (*dir_ / name).string();
    o.max_size = 128;
    o.preview_size = 64;
    return o;
  }
  static fs::path* dir_;
  static Project* project_;
};
fs::path* TourExportInteropTest::dir_ = nullptr;
Project* TourExportInteropTest::project_ = nullptr;

TEST_F(TourExportInteropTest, GeoreferencedByDefaultKeyframesCarryGPanoAndGps) {
  if (!interop_test::have_program("exiftool")) GTEST_SKIP() << "exiftool is not installed";
  TourExportOptions o = options("default");
  o.geojson = true;
  const TourExportReport report = export_tour(*project_, o);
  const fs::path out = o.output;
  EXPECT_TRUE(fs::is_regular_file(out / "path.kml"));
  EXPECT_TRUE(fs::is_regular_file(out / "path.gpx"));
  EXPECT_FALSE(fs::exists(out / "trajectory.tum"));
  EXPECT_FALSE(fs::exists(out / "reconstruction.json"));
  EXPECT_EQ(std::count(report.files.begin(), report.files.end(), "path.kml"), 1);

  // Each keyframe's GPS is its point in path.geojson (hand-checked in tour_export_test), at the camera's
  // height above the anchor's 35 m; its heading is the path's.
  const nlohmann::json geojson = read_json(out / "path.geojson");
  int checked = 0;
  for (const nlohmann::json& feature : geojson["features"]) {
    if (feature["properties"]["kind"] != "keyframe") continue;
    const int frame = feature["properties"]["frame"];
    const PathFrame* f = project_->path.find_frame(frame);
    ASSERT_NE(f, nullptr);
    char stem[32];
    std::snprintf(stem, sizeof stem, "images/k%06d", frame);
    // The full JPEG (the preview is a script, for the player alone).
    for (auto [suffix, width] : {std::pair{"_full.jpg", 128}}) {
      const nlohmann::json e = exiftool(out / (std::string(stem) + suffix));
      EXPECT_EQ(e.at("XMP:ProjectionType"), "equirectangular");
      EXPECT_EQ(e.at("XMP:FullPanoWidthPixels"), width);
      EXPECT_EQ(e.at("XMP:FullPanoHeightPixels"), width / 2);
      EXPECT_EQ(e.at("File:ImageWidth"), width);
      double compass = std::fmod(90.0 - f->heading * 180.0 / M_PI, 360.0);
      if (compass < 0) compass += 360.0;
      EXPECT_NEAR(e.at("XMP:PoseHeadingDegrees").get<double>(), compass, 0.005) << frame;
      EXPECT_NEAR(e.at("Composite:GPSLongitude").get<double>(),
                  feature["geometry"]["coordinates"][0].get<double>(), 1e-8);
      EXPECT_NEAR(e.at("Composite:GPSLatitude").get<double>(),
                  feature["geometry"]["coordinates"][1].get<double>(), 1e-8);
      EXPECT_NEAR(e.at("Composite:GPSAltitude").get<double>(), 36.6, 0.01);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 3);
}

TEST_F(TourExportInteropTest, WithoutAnAnchorNoMapFilesUnlessAskedForThenAnError) {
  Project p = *project_;
  p.geo.valid = false;
  TourExportOptions o = options("no_anchor");
  export_tour(p, o);
  EXPECT_TRUE(fs::is_regular_file(fs::path(o.output) / "tour.json"));
  EXPECT_FALSE(fs::exists(fs::path(o.output) / "path.kml"));
  EXPECT_FALSE(fs::exists(fs::path(o.output) / "path.gpx"));

  o.output = (*dir_ / "asked").string();
  o.kml_gpx = GeoTrackFiles::kOn;
  try {
    export_tour(p, o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("geo-anchor"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(o.output));
  EXPECT_FALSE(fs::exists(o.output + ".partial"));
}

TEST_F(TourExportInteropTest, TumAndOpenSfmOnRequestNameThePackagesImages) {
  TourExportOptions o = options("poses");
  o.tum = true;
  o.opensfm = true;
  o.kml_gpx = GeoTrackFiles::kOff;
  o.photo_metadata = false;
  export_tour(*project_, o);
  const fs::path out = o.output;
  EXPECT_FALSE(fs::exists(out / "path.kml"));
  std::ifstream tum(out / "trajectory.tum");
  std::string line;
  std::size_t poses = 0;
  while (std::getline(tum, line))
    if (!line.empty() && line[0] != '#') ++poses;
  EXPECT_EQ(poses, project_->path.size());
  const nlohmann::json rec = read_json(out / "reconstruction.json");
  EXPECT_EQ(read_json(out / "reference_lla.json")["latitude"], 48.0);
  ASSERT_EQ(rec[0]["shots"].size(), 3u);
  for (const auto& [name, shot] : rec[0]["shots"].items()) {
    const cv::Mat image = cv::imread((out / "images" / name).string());
    ASSERT_FALSE(image.empty()) << name;
    const nlohmann::json& camera = rec[0]["cameras"][shot["camera"].get<std::string>()];
    EXPECT_EQ(camera["width"], image.cols);
    EXPECT_EQ(camera["height"], image.rows);
  }
  if (interop_test::have_program("exiftool")) {
    const nlohmann::json e = exiftool(out / "images/k000000_full.jpg");
    EXPECT_FALSE(e.contains("XMP:ProjectionType")) << "photo_metadata = false still tagged";
  }
}

}  // namespace
}  // namespace plenopath
