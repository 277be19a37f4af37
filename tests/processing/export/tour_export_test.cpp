// The tour package: contents, tour.json round trip, images against the source frames, interop files against
// hand-computed values, safety of paths inside the package, and failure modes.
#include "processing/export/tour_export.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "model/error.h"
#include "model/json_reader.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/video_encode.h"
#include "processing/export/package_path.h"
#include "processing/export/tour_interop.h"
#include "rig/synthetic_camera.h"
#include "tests/processing/cleanplate/masked_psnr.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

// One folder per process: ctest runs each test of this suite as its own process, in parallel.
fs::path test_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("plenopath_export_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Renders `walk` into dir/frames (PNG) and makes it the project's capture and path.
void write_rendered_capture(const fs::path& dir, const SyntheticScene& scene, const RenderOptions& render,
                            CameraPath* walk, Project* p) {
  fs::create_directories(dir / "frames");
  for (PathFrame& f : walk->frames) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.png", f.index);
    cv::imwrite((dir / "frames" / name).string(), render_panorama(scene, f, render).rgb);
    f.file = std::string("frames/") + name;
    p->capture.frame_names.push_back(name);
  }
  p->path = *walk;
  p->capture.kind = CaptureKind::kImageFolder;
  p->capture.source = (dir / "frames").string();
  p->capture.frame_count = static_cast<int>(walk->frames.size());
  p->capture.width = render.width;
  p->capture.height = render.height;
  p->capture.camera_height_m = 1.6;
}

// Temporary files or folders an export left beside `dir`'s entries (package_writer.cpp names them
// ".<name>.partial<pid>" and ".<name>.old<pid>").
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".partial") != std::string::npos || name.find(".old") != std::string::npos)
      found.push_back(name);
  }
  return found;
}

// The bytes of a base64 text (RFC 4648), decoded here independently of the exporter's encoder.
std::vector<unsigned char> decode_base64(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> out;
  unsigned bits = 0, value = 0;
  for (char c : text) {
    if (c == '=') break;
    value = (value << 6) | static_cast<unsigned>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((value >> bits) & 0xFF));
    }
  }
  return out;
}

// The image a preview script (images/*_preview.js) hands the player: plenopathAsset("name","data:...").
cv::Mat image_of_preview_script(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::string marker = ";base64,";
  const std::size_t at = text.find(marker);
  if (at == std::string::npos) return {};
  const std::size_t end = text.find('"', at);
  const std::vector<unsigned char> jpeg =
      decode_base64(text.substr(at + marker.size(), end - at - marker.size()));
  return cv::imdecode(jpeg, cv::IMREAD_COLOR);
}

// A small rendered capture of the office sample with keyframes, hotspots and a geo-anchor.
Project make_rendered_project(const fs::path& dir, int frame_count = 12, int width = 256) {
  Project p;
  p.plan = make_office_sample_plan();
  p.tour.title = "Export test <b>tour</b>";
  CameraPath walk = auto_walk(p.plan);
  walk.frames.resize(std::min<std::size_t>(walk.frames.size(), frame_count));
  const SyntheticScene scene = build_synthetic_scene(p.plan);
  RenderOptions render;
  render.width = width;
  render.height = width / 2;
  render.depth = false;
  write_rendered_capture(dir, scene, render, &walk, &p);
  p.keyframes.indices = {0, 5, frame_count - 1};
  p.keyframes.rank = {0, 2, 1};
  p.visibility.cells = {{0, 5, 0.0, 0.4, 0.4, 20.0, 21.0}, {5, frame_count - 1, 0.4, 0.8, 0.4, 30.0, 29.0}};

  const PathFrame& f0 = walk.frames.front();
  const Eigen::Vector2d ahead =
      f0.position() + 2.0 * Eigen::Vector2d(std::cos(f0.heading), std::sin(f0.heading));
  const Eigen::Vector2d side(-std::sin(f0.heading), std::cos(f0.heading));
  cv::imwrite((dir / "poster.png").string(), cv::Mat(32, 48, CV_8UC3, cv::Scalar(0, 0, 255)));
  Hotspot tv;
  tv.id = "../../tv screen";  // an id that would escape the package if used as a path
  tv.kind = HotspotKind::kMovieTexture;
  tv.title = "<img src=x onerror=alert(1)>";
  tv.media = (dir / "poster.png").string();
  tv.frame = 0;
  for (auto [u, z] : {std::pair{0.5, 2.0}, {-0.5, 2.0}, {-0.5, 1.2}, {0.5, 1.2}}) {
    const Eigen::Vector2d c = ahead + u * side;
    tv.world_corners.emplace_back(c.x(), c.y(), z);
  }
  tv.action = HotspotAction::kShowText;
  tv.action_target = "It is a poster.";
  Hotspot lift;
  lift.id = "lift";
  lift.kind = HotspotKind::kEvent;
  lift.title = "Lift";
  lift.media = (dir / "missing.mp4").string();  // missing media: a warning, not a failure
  lift.frame = 5;
  lift.image_corners = {{0.1, 0.2}, {0.3, 0.2}, {0.3, -0.1}, {0.1, -0.1}};
  lift.action = HotspotAction::kJump;
  lift.action_target = "11";
  p.hotspots = {tv, lift};
  p.geo = {true, 48.0, 2.0, 35.0, 0.0, 1.0, {0.0, 0.0}};
  return p;
}

class TourExportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test_dir("suite"));
    project_ = new Project(make_rendered_project(*dir_));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete project_;
    delete dir_;
  }
  static fs::path* dir_;
  static Project* project_;
};
fs::path* TourExportTest::dir_ = nullptr;
Project* TourExportTest::project_ = nullptr;

TEST_F(TourExportTest, FolderHoldsEverythingThePlayerNeeds) {
  TourExportOptions options;
  options.output = (*dir_ / "package").string();
  options.max_size = 200;
  options.preview_size = 100;
  options.pannellum = true;
  options.geojson = true;
  const TourExportReport report = export_tour(*project_, options);
  EXPECT_EQ(report.keyframes, 3);
  EXPECT_EQ(report.capture_frames, 12);
  const fs::path out = options.output;
  for (const char* f : {"index.html", "player.js", "player.css", "tour.json", "tour.js", "tour.schema.json",
                        "plan.svg", "pannellum.json", "path.geojson", "images/k000000_full.jpg",
                        "images/k000000_preview.js", "images/k000005_preview.js"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  // Each image once: no preview JPEG beside its script, no script copy of the full image.
  for (const char* f : {"images/k000000_preview.jpg", "images/k000000_full.js"})
    EXPECT_FALSE(fs::exists(out / f)) << f;
  EXPECT_TRUE(leftovers(*dir_).empty());
  std::uintmax_t total = 0;
  for (const auto& e : fs::recursive_directory_iterator(out))
    if (e.is_regular_file()) total += e.file_size();
  EXPECT_EQ(report.package_bytes, total);

  // Media: copied under media/ with a safe name; the missing one reported.
  const nlohmann::json tour = read_json_file((out / "tour.json").string());
  EXPECT_EQ(tour["hotspots"][0]["media"], "media/______tv_screen.png");
  EXPECT_TRUE(fs::is_regular_file(out / "media/______tv_screen.png"));
  EXPECT_EQ(tour["hotspots"][1]["media"], "");
  // Validation warnings, each once: the lift's missing video, and the markup in the TV's title.
  int missing = 0, markup = 0;
  for (const std::string& w : report.warnings) {
    missing += w.find("missing.mp4") != std::string::npos;
    markup += w.find("markup") != std::string::npos;
  }
  EXPECT_EQ(missing, 1);
  EXPECT_EQ(markup, 1);
  for (const std::string& f : report.files) EXPECT_TRUE(is_safe_package_path(f)) << f;
  // Titles stay plain strings (the player shows them with textContent).
  EXPECT_EQ(tour["hotspots"][0]["title"], "<img src=x onerror=alert(1)>");
  // Keyframes in progressive order (rank 0, 1, 2 = frames 0, 11, 5).
  ASSERT_EQ(tour["keyframes"].size(), 3u);
  EXPECT_EQ(tour["keyframes"][0]["frame"], 0);
  EXPECT_EQ(tour["keyframes"][1]["frame"], 11);
  EXPECT_EQ(tour["keyframes"][2]["frame"], 5);
}

TEST_F(TourExportTest, KeyframeImagesMatchTheSourceFrames) {
  TourExportOptions options;
  options.output = (*dir_ / "images_check").string();
  options.max_size = 4096;  // larger than the capture: never upscaled
  options.preview_size = 128;
  options.jpeg_quality = 95;
  export_tour(*project_, options);
  for (int frame : {0, 5, 11}) {
    char name[64];
    std::snprintf(name, sizeof name, "%06d.png", frame);
    const cv::Mat source = cv::imread((*dir_ / "frames" / name).string());
    std::snprintf(name, sizeof name, "images/k%06d_full.jpg", frame);
    const cv::Mat full = cv::imread((fs::path(options.output) / name).string());
    ASSERT_EQ(full.size(), source.size());
    EXPECT_GT(cv::PSNR(full, source), 30.0) << frame;
    std::snprintf(name, sizeof name, "images/k%06d_preview.js", frame);
    const cv::Mat preview = image_of_preview_script(fs::path(options.output) / name);
    ASSERT_EQ(preview.size(), cv::Size(128, 64));
    cv::Mat reduced;
    cv::resize(source, reduced, preview.size(), 0, 0, cv::INTER_AREA);
    EXPECT_GT(cv::PSNR(preview, reduced), 28.0) << frame;  // at the preview's lower JPEG quality
  }
}

TEST_F(TourExportTest, TourJsonRoundTrips) {
  TourExportOptions options;
  options.output = (*dir_ / "roundtrip").string();
  options.max_size = 128;
  options.preview_size = 64;
  export_tour(*project_, options);
  const std::string file = (fs::path(options.output) / "tour.json").string();
  const Project back = project_from_tour_json(read_json_file(file), file);
  const Project& p = *project_;
  EXPECT_EQ(back.tour.title, p.tour.title);
  ASSERT_EQ(back.path.size(), p.path.size());
  for (std::size_t i = 0; i < p.path.size(); ++i) {
    EXPECT_EQ(back.path.frames[i].index, p.path.frames[i].index);
    EXPECT_EQ(back.path.frames[i].x, p.path.frames[i].x);
    EXPECT_EQ(back.path.frames[i].y, p.path.frames[i].y);
    EXPECT_NEAR(back.path.frames[i].heading, p.path.frames[i].heading, 1e-12);
  }
  EXPECT_EQ(back.keyframes.indices, p.keyframes.indices);
  EXPECT_EQ(back.keyframes.rank, p.keyframes.rank);
  EXPECT_EQ(back.visibility.cells, p.visibility.cells);
  ASSERT_EQ(back.plan.segments.size(), p.plan.segments.size());
  for (std::size_t i = 0; i < p.plan.segments.size(); ++i) {
    EXPECT_EQ(back.plan.segments[i].a, p.plan.segments[i].a);
    EXPECT_EQ(back.plan.segments[i].b, p.plan.segments[i].b);
    EXPECT_EQ(back.plan.segments[i].layer, p.plan.segments[i].layer);
    EXPECT_EQ(back.plan.segments[i].occluder, p.plan.segments[i].occluder);
  }
  ASSERT_EQ(back.hotspots.size(), 2u);
  EXPECT_EQ(back.hotspots[0].world_corners, p.hotspots[0].world_corners);
  EXPECT_EQ(back.hotspots[1].action_target, "11");
  ASSERT_EQ(back.hotspots[1].image_corners.size(), 4u);
  EXPECT_LT((back.hotspots[1].image_corners[2] - p.hotspots[1].image_corners[2]).norm(), 1e-12);
  EXPECT_TRUE(back.geo.valid);
  EXPECT_EQ(back.geo.latitude_deg, 48.0);
}

TEST_F(TourExportTest, TourJsonValidatesAgainstTheSchema) {
  TourExportOptions options;
  options.output = (*dir_ / "schema").string();
  options.max_size = 128;
  options.preview_size = 64;
  export_tour(*project_, options);
  const std::string cmd =
      "/usr/bin/python3 -c \"import json,jsonschema,sys; "
      "jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))\" '" +
      options.output + "/tour.json' '" + options.output + "/tour.schema.json'";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  // And a broken document is rejected by the same schema.
  nlohmann::json bad = read_json_file(options.output + "/tour.json");
  bad["keyframes"][0]["preview"] = "../../etc/passwd";
  std::ofstream(options.output + "/bad.json") << bad.dump();
  const std::string bad_cmd =
      "/usr/bin/python3 -c \"import json,jsonschema,sys; "
      "jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))\" '" +
      options.output + "/bad.json' '" + options.output + "/tour.schema.json' 2>/dev/null";
  EXPECT_NE(std::system(bad_cmd.c_str()), 0);
}

TEST_F(TourExportTest, ZipPackageIsReadableByAnIndependentUnzip) {
  TourExportOptions options;
  options.output = (*dir_ / "tour.zip").string();
  options.max_size = 128;
  options.preview_size = 64;
  const TourExportReport report = export_tour(*project_, options);
  EXPECT_EQ(report.package_bytes, fs::file_size(options.output));
  // Text deflated, JPEGs stored (python's zipfile reads the method of each entry).
  const std::string cmd =
      "/usr/bin/python3 -c \"import zipfile,sys; z=zipfile.ZipFile(sys.argv[1]); "
      "assert z.testzip() is None; n=z.namelist(); assert 'tour.json' in n and 'index.html' in n, n; "
      "i={e.filename: e for e in z.infolist()}; "
      "assert i['tour.json'].compress_type == zipfile.ZIP_DEFLATED; "
      "assert i['player.js'].compress_type == zipfile.ZIP_DEFLATED; "
      "assert i['images/k000000_full.jpg'].compress_type == zipfile.ZIP_STORED; "
      "assert i['tour.json'].compress_size < i['tour.json'].file_size; "
      "assert len(n) == " +
      std::to_string(report.files.size()) + ", len(n)\" '" + options.output + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const std::string unzip = "unzip -tq '" + options.output + "' >/dev/null";
  EXPECT_EQ(std::system(unzip.c_str()), 0) << unzip;
  // The ratio against the full JPEGs' bytes as the zip lists them.
  const std::string sum_cmd =
      "/usr/bin/python3 -c \"import zipfile,sys; z=zipfile.ZipFile(sys.argv[1]); "
      "print(sum(e.file_size for e in z.infolist() if e.filename.endswith('_full.jpg')))\" '" +
      options.output + "'";
  FILE* pipe = popen(sum_cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  unsigned long long full_bytes = 0;
  EXPECT_EQ(std::fscanf(pipe, "%llu", &full_bytes), 1);
  pclose(pipe);
  EXPECT_EQ(report.full_image_bytes, full_bytes);
  EXPECT_NEAR(report.package_ratio, static_cast<double>(report.package_bytes) / full_bytes, 1e-12);
}

TEST_F(TourExportTest, CancelLeavesNoPackage) {
  TourExportOptions options;
  options.output = (*dir_ / "cancelled").string();
  options.max_size = 128;
  options.preview_size = 64;
  int calls = 0;
  FunctionProgress progress([&](double, const std::string&) {
    if (++calls >= 3) progress.cancel();
  });
  EXPECT_THROW(export_tour(*project_, options, progress), Cancelled);
  EXPECT_EQ(calls, 3) << "stopped at the report that saw the cancel";
  EXPECT_FALSE(fs::exists(options.output));
  EXPECT_TRUE(leftovers(*dir_).empty());
}

// A second export cancelled half-way (after its first keyframe is written) keeps the first package whole,
// as a folder and as a zip.
TEST_F(TourExportTest, CancelKeepsThePreviousPackage) {
  for (const std::string name : {"kept", "kept.zip"}) {
    TourExportOptions options;
    options.output = (*dir_ / name).string();
    options.max_size = 128;
    options.preview_size = 64;
    const TourExportReport first = export_tour(*project_, options);
    int encoding = 0;
    FunctionProgress progress([&](double, const std::string& stage) {
      if (stage == "encoding keyframes" && ++encoding == 2) progress.cancel();  // the first one is written
    });
    options.max_size = 256;  // a different package, had it been finished
    EXPECT_THROW(export_tour(*project_, options, progress), Cancelled) << name;
    EXPECT_EQ(encoding, 2) << name;
    std::uintmax_t bytes = 0;
    if (fs::is_directory(options.output)) {
      for (const auto& e : fs::recursive_directory_iterator(options.output))
        if (e.is_regular_file()) bytes += e.file_size();
      const cv::Mat full = cv::imread(options.output + "/images/k000000_full.jpg");
      EXPECT_EQ(full.cols, 128) << "the first package's image";
    } else {
      bytes = fs::file_size(options.output);
      const std::string cmd =
          "/usr/bin/python3 -c \"import zipfile,sys; assert zipfile.ZipFile(sys.argv[1]).testzip() is None\" "
          "'" +
          options.output + "'";
      EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    }
    EXPECT_EQ(bytes, first.package_bytes) << name;
    EXPECT_TRUE(leftovers(*dir_).empty()) << name;
  }
}

TEST_F(TourExportTest, CancelAfterTheFirstReportWritesNoZip) {
  TourExportOptions options;
  options.output = (*dir_ / "cancelled.zip").string();
  int calls = 0;
  FunctionProgress progress([&](double, const std::string&) {
    ++calls;
    progress.cancel();
  });
  EXPECT_THROW(export_tour(*project_, options, progress), Cancelled);
  EXPECT_EQ(calls, 1);
  EXPECT_FALSE(fs::exists(options.output));
  EXPECT_TRUE(leftovers(*dir_).empty());
}

TEST_F(TourExportTest, ClearErrors) {
  TourExportOptions options;
  options.output = (*dir_ / "errors").string();
  Project p = *project_;
  p.keyframes = {};
  try {
    export_tour(p, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no keyframes"), std::string::npos) << e.what();
  }
  p = *project_;
  p.keyframes.indices.push_back(400);
  p.keyframes.rank.push_back(3);
  EXPECT_THROW(export_tour(p, options), Error);
  options.jpeg_quality = 0;
  EXPECT_THROW(export_tour(*project_, options), Error);
  options = TourExportOptions{};
  options.output = "/proc/no/such/place/tour.zip";
  options.max_size = 128;
  options.preview_size = 64;
  EXPECT_THROW(export_tour(*project_, options), Error);
}

// export --clean-plates on a capture with people walking and no depth maps: the static depth comes from the
// plan, the keyframe comes out without the people (against the same walk rendered without them).
// A walk through the office sample rendered 1024 x 512 into a temporary folder as the project's capture,
// with what `add` turns on (people, the rig); `without` is the same with them off: the truth.
struct CleanPlateWalk {
  fs::path dir;
  Project p;
  CameraPath walk;
  SyntheticScene scene;
  RenderOptions render, without;
};
CleanPlateWalk clean_plate_walk(const std::string& name, int frames, std::uint32_t seed,
                                const std::function<void(RenderOptions&)>& add) {
  const fs::path dir = fs::temp_directory_path() / ("plenopath_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  Project p;
  p.plan = make_office_sample_plan();
  AutoWalkOptions walk_options;
  walk_options.max_frames = frames;
  walk_options.seed = seed;
  CameraPath walk = auto_walk(p.plan, walk_options);
  SyntheticScene scene = build_synthetic_scene(p.plan);
  RenderOptions without;
  without.width = 1024;
  without.height = 512;
  without.depth = false;
  RenderOptions render = without;
  add(render);
  write_rendered_capture(dir, scene, render, &walk, &p);
  return {dir, std::move(p), std::move(walk), std::move(scene), render, without};
}

TEST(TourExportCleanPlates, ThePeopleLeaveTheKeyframe) {
  CleanPlateWalk w = clean_plate_walk("clean_export", 50, AutoWalkOptions{}.seed, [](RenderOptions& r) {
    r.people = 12;
    r.frame_rate = 10;
  });
  const fs::path& dir = w.dir;
  Project& p = w.p;
  const CameraPath& walk = w.walk;
  const SyntheticScene& scene = w.scene;
  const RenderOptions &render = w.render, &without = w.without;
  const int key = 25;
  p.keyframes.indices = {key};
  p.keyframes.rank = {0};
  TourExportOptions options;
  options.output = (dir / "tour").string();
  options.max_size = render.width;
  options.jpeg_quality = 98;
  options.cleaning.clean_plates = true;
  const TourExportReport report = export_tour(p, options);
  EXPECT_EQ(report.clean_plates, 1);
  EXPECT_GT(report.replaced_pct, 0.5);
  const cv::Mat exported = cv::imread((dir / "tour" / "images" / "k000025_full.jpg").string());
  ASSERT_FALSE(exported.empty());
  const cv::Mat original = render_panorama(scene, walk.frames[key], render).rgb;
  const cv::Mat truth = render_panorama(scene, walk.frames[key], without).rgb;
  const cv::Mat people = test::differing_pixels(original, truth, 8);
  ASSERT_GT(cv::countNonZero(people), 500) << "the keyframe should show people";
  auto psnr = [&](const cv::Mat& a) { return test::masked_psnr(a, truth, people); };
  std::printf("people pixels %d: PSNR %.1f dB in the frame, %.1f dB exported; %.2f %% replaced\n",
              cv::countNonZero(people), psnr(original), psnr(exported), report.replaced_pct);
  EXPECT_GT(psnr(exported), psnr(original) + 12.0);
  fs::remove_all(dir);
}

// export --clean-plates on a trolley capture: the rig (found by the tracker's static mask over the first
// frames) is filled from frames further along, what none saw gets the author's nadir image, and the rig
// filled matches the same walk rendered without trolley and operator.
TEST(TourExportCleanPlates, TheRigIsFilledAndTheNadirPatched) {
  CleanPlateWalk w =
      clean_plate_walk("rig_export", 110, 3, [](RenderOptions& r) { r.trolley = r.operator_person = true; });
  const fs::path& dir = w.dir;
  Project& p = w.p;
  const CameraPath& walk = w.walk;
  const SyntheticScene& scene = w.scene;
  const RenderOptions &render = w.render, &without = w.without;
  p.capture.camera_height_m = SceneOptions{}.camera_height;
  const int key = 60;
  p.keyframes.indices = {key};
  p.keyframes.rank = {0};
  p.tour.export_clean_plates = true;
  p.tour.nadir_patch = NadirPatch::kImage;
  p.tour.nadir_image = (dir / "logo.png").string();
  cv::imwrite(p.tour.nadir_image, cv::Mat(64, 64, CV_8UC3, cv::Scalar(255, 0, 255)));  // magenta
  TourExportOptions options = TourExportOptions::from_project(p, (dir / "tour").string());
  options.max_size = render.width;
  options.jpeg_quality = 98;
  const TourExportReport report = export_tour(p, options);
  EXPECT_GT(report.rig_pct, 10.0);
  EXPECT_GT(report.rig_filled_pct, 60.0);
  const cv::Mat exported = cv::imread((dir / "tour" / "images" / "k000060_full.jpg").string());
  ASSERT_FALSE(exported.empty());
  const cv::Mat original = render_panorama(scene, walk.frames[key], render).rgb;
  const cv::Mat truth = render_panorama(scene, walk.frames[key], without).rgb;
  const cv::Mat rig = test::differing_pixels(original, truth, 8);
  // The nadir image is a disc of at most 40 deg round the nadir (rows below 0.78 h); above it, most of the
  // rig (the operator, the trolley's handle) now looks like the scene behind it.
  const int disc_top = static_cast<int>(0.78 * exported.rows);
  cv::Mat now_diff, scene_now;
  cv::absdiff(exported, truth, now_diff);
  cv::cvtColor(now_diff, now_diff, cv::COLOR_BGR2GRAY);
  cv::threshold(now_diff, scene_now, 24, 255, cv::THRESH_BINARY_INV);
  cv::Mat rig_above = rig.clone();
  rig_above.rowRange(disc_top, rig.rows).setTo(0);
  const cv::Mat filled = rig_above & scene_now;
  const double filled_share = double(cv::countNonZero(filled)) / cv::countNonZero(rig_above);
  std::printf(
      "rig %.1f %% of the image (report %.1f %%, %.1f %% filled); above the disc %.1f %% of the rig now "
      "the scene, at %.1f dB\n",
      100.0 * cv::countNonZero(rig) / rig.total(), report.rig_pct, report.rig_filled_pct, 100 * filled_share,
      test::masked_psnr(exported, truth, filled));
  EXPECT_GT(filled_share, 0.6);
  // The patch: the author's magenta all round the nadir, and nowhere above the disc.
  cv::Mat magenta, scene_magenta;
  cv::inRange(exported, cv::Scalar(200, 0, 200), cv::Scalar(255, 60, 255), magenta);
  cv::inRange(truth, cv::Scalar(180, 0, 180), cv::Scalar(255, 80, 255), scene_magenta);  // posters
  cv::dilate(scene_magenta, scene_magenta, cv::Mat(), cv::Point(-1, -1), 2);
  magenta &= ~scene_magenta;
  EXPECT_GT(cv::countNonZero(magenta.row(exported.rows - 1)), exported.cols * 9 / 10);
  EXPECT_EQ(cv::countNonZero(magenta.rowRange(0, disc_top - 2)), 0);
  if (!std::getenv("PLENOPATH_KEEP_TEST_OUTPUT")) fs::remove_all(dir);
}

TEST(TourInterop, PannellumLinksPointAtTheNeighbours) {
  // Keyframe A at the origin facing +X; B 1 m to its left (+Y): B lies at azimuth -90 deg (left).
  Project p;
  p.path.frames = {{0, "", 0.0, 0.0, 0.0, 1.0, 0, ""}, {1, "", 0.0, 1.0, M_PI / 2, 1.0, 0, ""}};
  p.keyframes.indices = {0, 1};
  const std::vector<KeyframeImageFiles> images = {{0, "p0.js", "f0.jpg", ""}, {1, "p1.js", "f1.jpg", ""}};
  const nlohmann::json config = pannellum_config(p, images);
  const auto& a = config["scenes"]["k0"]["hotSpots"];
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0]["sceneId"], "k1");
  EXPECT_NEAR(a[0]["yaw"].get<double>(), -90.0, 1e-9);
  // From B (facing +Y), A lies behind (-Y): azimuth 180.
  const auto& b = config["scenes"]["k1"]["hotSpots"];
  EXPECT_NEAR(std::abs(b[0]["yaw"].get<double>()), 180.0, 1e-9);
  EXPECT_EQ(config["default"]["firstScene"], "k0");
  EXPECT_EQ(config["scenes"]["k0"]["panorama"], "f0.jpg");
}

TEST(TourInterop, GeoJsonPlacesThePathOnEarth) {
  // At latitude 48 deg one degree of latitude is 111 190.3 m and one of longitude 74 625.2 m (meridian and
  // parallel arc lengths on WGS84, hand-computed from the series 111132.954 - 559.822 cos 2phi + ...).
  Project p;
  p.geo = {true, 48.0, 2.0, 0.0, 0.0, 1.0, {0.0, 0.0}};
  p.path.frames = {{0, "", 0.0, 0.0, 0.0, 1.0, 0, ""},
                   {1, "", 0.0, 111.1903, 0.0, 1.0, 0, ""},
                   {2, "", 74.6252, 0.0, 0.0, 1.0, 0, ""}};
  p.keyframes.indices = {0, 1};
  const nlohmann::json g = path_geojson(p);
  const auto& line = g["features"][0]["geometry"]["coordinates"];
  EXPECT_NEAR(line[0][0].get<double>(), 2.0, 1e-9);
  EXPECT_NEAR(line[0][1].get<double>(), 48.0, 1e-9);
  EXPECT_NEAR(line[1][1].get<double>(), 48.001, 2e-7);  // 111.19 m north
  EXPECT_NEAR(line[1][0].get<double>(), 2.0, 1e-9);
  EXPECT_NEAR(line[2][0].get<double>(), 2.001, 2e-7);  // 74.63 m east
  EXPECT_EQ(g["features"].size(), 3u);                 // the line and two keyframes
  // A plan rotated by 90 deg: plan +X points north.
  p.geo.plan_rotation = M_PI / 2;
  const nlohmann::json r = path_geojson(p);
  EXPECT_NEAR(r["features"][0]["geometry"]["coordinates"][2][1].get<double>(), 48.0 + 74.6252 / 111190.3,
              2e-7);
  p.geo.valid = false;
  EXPECT_THROW(path_geojson(p), Error);
}

TEST(PackagePath, OnlyPathsThatStayInside) {
  EXPECT_TRUE(is_safe_package_path("images/k000001_full.jpg"));
  for (const char* bad : {"../x", "a/../../x", "/etc/passwd", "a\\b", "C:evil", "a//b", "a/", "", "./a"})
    EXPECT_FALSE(is_safe_package_path(bad)) << bad;
}

TEST(PlanSvg, EscapesTextAndFlipsY) {
  FloorPlan plan;
  plan.segments = {{{0, 0}, {2, 1}, "WALLS", true}};
  plan.labels = {{{1, 1}, "A & <B>", 0.3, "TEXT"}};
  const std::string svg = plan_svg(plan);
  EXPECT_NE(svg.find("A &amp; &lt;B&gt;"), std::string::npos);
  EXPECT_NE(svg.find("y2=\"-1.000000\""), std::string::npos);
  EXPECT_EQ(svg.find("<B>"), std::string::npos);
}

}  // namespace
}  // namespace plenopath

namespace plenopath {
namespace {

// The exported player in Debian's headless Chromium (tests/app/player_check.py): non-blank canvas, a walk key
// changes keyframe and picture, a hotspot click fires, a markup title stays text, the start label names the
// first keyframe; as on a phone without WebGL2 whose GPU holds 512-pixel textures, the 1024-pixel keyframes
// are scaled down to fit, with mipmaps; no page exception or console error. The package and the screenshots
// are left in the build folder (player_check/) to look at.
TEST(TourPlayer, WalksAndReactsInHeadlessChromium) {
  const fs::path work = fs::path(PLENOPATH_BINARY_DIR) / "player_check";
  fs::remove_all(work);
  fs::create_directories(work);
  Project p = make_rendered_project(work / "capture", 12, 1024);
  const std::string xss = "<img src=x onerror=\"window.__pwned=1\">";
  p.hotspots[0].title = xss;
  // The path's last keyframe first in progressive order: its preview loads first, yet the start shows the
  // first keyframe (the label once read "Keyframe 3 of 3" at 0.0 m).
  p.keyframes.rank = {2, 1, 0};
  TourExportOptions options;
  options.output = (work / "tour").string();
  options.max_size = 1024;
  options.preview_size = 256;
  export_tour(p, options);
  const std::string cmd = "/usr/bin/python3 '" + std::string(PLENOPATH_SOURCE_DIR) +
                          "/tests/app/player_check.py' '" + options.output + "' '" +
                          (work / "player").string() + "' --xss-title '" + xss +
                          "' --webgl1 --max-texture 512";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

// An event hotspot that swaps its region for an image sequence (the lift doors opening), given as a video:
// a click swaps the poster for the sequence, which plays (the picture keeps changing) and then holds its last
// frame; a second click brings the poster back.
TEST(TourPlayer, SwapsARegionForAnImageSequence) {
  const fs::path work = fs::path(PLENOPATH_BINARY_DIR) / "player_check_sequence";
  fs::remove_all(work);
  fs::create_directories(work);
  Project p = make_rendered_project(work / "capture", 12, 1024);
  // 24 frames at 8 fps, 3 s (long enough that a loaded machine draws some of it before the end): red to
  // blue, so consecutive frames differ.
  const auto frames = FrameSource::from_generator(
      24, 64, 48, 8.0, [](int k) { return cv::Mat(48, 64, CV_8UC3, cv::Scalar(10 * k, 40, 240 - 10 * k)); });
  const std::string doors = (work / "doors.mp4").string();
  encode_video(*frames, doors);
  Hotspot& tv = p.hotspots[0];
  tv.kind = HotspotKind::kEvent;
  tv.title = "Lift doors";
  tv.action = HotspotAction::kSwapImage;
  tv.action_target = doors;
  TourExportOptions options;
  options.output = (work / "tour").string();
  options.max_size = 1024;
  options.preview_size = 256;
  const TourExportReport report = export_tour(p, options);
  for (const std::string& w : report.warnings) EXPECT_EQ(w.find("Lift doors"), std::string::npos) << w;
  const std::string cmd = "/usr/bin/python3 '" + std::string(PLENOPATH_SOURCE_DIR) +
                          "/tests/app/player_check.py' '" + options.output + "' '" +
                          (work / "player").string() + "' --swap-sequence";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

// Stills in two rooms: the tour's path goes from one to the other along the walkable route, through both
// doorways (waypoints of index -1), crossing no wall (an orientation test of this file's own); the stills'
// arc lengths stay those of the project's path, and reading the tour back drops the waypoints.
TEST(TourExport, StillsInTwoRoomsAreJoinedThroughTheDoors) {
  const fs::path work = fs::path(PLENOPATH_BINARY_DIR) / "tour_stills_route";
  fs::remove_all(work);
  Project p;
  p.plan = make_office_sample_plan();
  CameraPath stills;
  for (auto [x, y] : {std::pair{2.6, 9.4}, {1.0, 1.0}}) {
    PathFrame f;
    f.index = static_cast<int>(stills.frames.size());
    f.x = x;
    f.y = y;
    stills.frames.push_back(f);
  }
  RenderOptions render;
  render.width = 256;
  render.height = 128;
  render.depth = false;
  write_rendered_capture(work / "capture", build_synthetic_scene(p.plan), render, &stills, &p);
  p.capture.stills = true;
  p.keyframes.indices = {0, 1};
  p.keyframes.rank = {0, 1};
  TourExportOptions options;
  options.output = (work / "tour").string();
  export_tour(p, options);
  const std::string file = (fs::path(options.output) / "tour.json").string();
  const nlohmann::json tour = read_json_file(file);
  std::vector<Eigen::Vector2d> line;
  int waypoints = 0;
  for (const auto& f : tour["path"]["frames"]) {
    line.emplace_back(f[1].get<double>(), f[2].get<double>());
    waypoints += f[0].get<int>() == -1;
  }
  EXPECT_GE(waypoints, 1);
  const auto orient = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  };
  for (std::size_t k = 1; k < line.size(); ++k)
    for (const PlanSegment& w : p.plan.occluder_segments())
      EXPECT_FALSE(orient(line[k - 1], line[k], w.a) * orient(line[k - 1], line[k], w.b) < 0 &&
                   orient(w.a, w.b, line[k - 1]) * orient(w.a, w.b, line[k]) < 0)
          << "leg " << k << " crosses a wall";
  const double straight = (stills.frames[1].position() - stills.frames[0].position()).norm();
  EXPECT_NEAR(tour["path"]["frames"].back()[4].get<double>(), straight, 1e-9);  // s as the project's path
  EXPECT_NEAR(tour["path"]["length_m"].get<double>(), straight, 1e-9);
  const Project back = project_from_tour_json(tour, file);
  EXPECT_EQ(back.path.size(), 2u);
}

// Stills metres apart are walked through, not jump-cut: three tripod stills 1.5 m apart in a line across
// the open office, at unrelated headings, all keyframes. Looking from the first toward the last, the view the
// walk from the first to the last draws at the middle still's spot must be closer to the middle still's own
// picture (the renderer's truth there) than a plain cross-fade of the two.
TEST(TourPlayer, WalksBetweenSparseStillsThroughTheRoom) {
  const fs::path work = fs::path(PLENOPATH_BINARY_DIR) / "player_check_stills";
  fs::remove_all(work);
  fs::create_directories(work);
  Project p;
  p.plan = make_office_sample_plan();
  p.tour.title = "Stills";
  CameraPath stills;
  const double headings[] = {0.3, 2.0, -1.0};
  for (int i = 0; i < 3; ++i) {
    PathFrame f;
    f.index = i;
    f.x = 2.4 + 1.5 * i;
    f.y = 10.0;
    f.heading = headings[i];
    stills.frames.push_back(f);
  }
  const SyntheticScene scene = build_synthetic_scene(p.plan);
  RenderOptions render;
  render.width = 1024;
  render.height = 512;
  render.depth = false;
  write_rendered_capture(work / "capture", scene, render, &stills, &p);
  p.capture.stills = true;
  p.keyframes.indices = {0, 1, 2};
  p.keyframes.rank = {0, 2, 1};
  p.visibility.cells = {{0, 2, 0.0, 0.4, 0.4, 20.0, 21.0}};
  TourExportOptions options;
  options.output = (work / "tour").string();
  options.max_size = 1024;
  options.preview_size = 512;
  export_tour(p, options);
  const std::string cmd = "/usr/bin/python3 '" + std::string(PLENOPATH_SOURCE_DIR) +
                          "/tests/app/player_check.py' '" + options.output + "' '" +
                          (work / "player").string() + "' --no-hotspots --transition 0 1 2";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

}  // namespace
}  // namespace plenopath
