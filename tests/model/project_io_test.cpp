#include "model/project_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "model/error.h"
#include "model/json_reader.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

class ProjectIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("plenopath_project_io_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(file(name)) << text; }
  fs::path dir_;
};

// A project with every part filled, with awkward values (unicode, negative numbers, empty strings).
Project make_full_project(const fs::path& dir) {
  Project p;
  p.plan.source_file = (dir / "plans" / "office.dxf").string();
  p.plan.units = "mm";
  p.plan.metres_per_unit = 0.001;
  p.plan.layers = {{"WALLS", 7, true, true, 12}, {"FURNITURE", 3, false, false, 4}};
  p.plan.segments = {{{0.0, 0.0}, {5.25, 0.0}, "WALLS", true},
                     {{1e-3, -2.5}, {1.0 / 3.0, 7.0}, "FURNITURE", false}};
  p.plan.outlines = {{{{0, 0}, {1, 0}, {1, 1}}, "COLUMNS", true}};
  p.plan.labels = {{{2.5, 3.5}, "Salle de réunion ✓", 0.25, "TEXT"}};
  p.capture.kind = CaptureKind::kImageFolder;
  p.capture.source = (dir / "capture" / "frames").string();
  p.capture.frame_count = 3;
  p.capture.width = 2048;
  p.capture.height = 1024;
  p.capture.frame_rate = 29.97;
  p.capture.stride = 2;
  p.capture.frame_names = {"a.jpg", "b.jpg", "c.jpg"};
  p.capture.depth_folder = (dir / "capture" / "depth").string();
  p.capture.gps_track = {{0.0, 48.85, 2.35, 35.0}, {1.0, 48.8501, 2.3502, 35.5}};
  p.capture.gps_time_offset_s = -1.5;
  p.capture.camera_height_m = 1.6;
  for (int i = 0; i < 3; ++i) {
    PathFrame f;
    f.index = i;
    f.file = "frames/" + std::to_string(i) + ".jpg";
    f.x = 0.1 * i;
    f.y = -0.2 * i;
    f.heading = 0.7 - 0.3 * i;
    f.confidence = i == 1 ? 0.25 : 1.0;
    f.flags = i == 2 ? (kFrameDuplicate | kFrameBridged) : kFrameOk;
    f.reason = i == 2 ? "trolley stopped" : "";
    p.path.frames.push_back(f);
  }
  p.path.scale_source = "camera_height";
  p.anchors = {{0, {1.0, 2.0}, std::nullopt}, {2, {3.0, -4.0}, 1.25}};
  p.visibility.events = {{1, 0.15}};
  p.visibility.cells = {{0, 1, 0.0, 0.15, 0.15, 12.5, 12.25}, {1, 2, 0.15, 0.44, 0.29, 30.0, 29.5}};
  p.visibility.critical_lines = {{{0, 1}, {2, 3}}};
  p.keyframes.indices = {0, 2};
  p.keyframes.rank = {0, 1};
  p.keyframes.pinned = {2};
  p.keyframes.parameters.method = SamplingMethod::kVisibility;
  p.keyframes.parameters.rule = VisibilityRule::cell_rule;
  p.keyframes.parameters.count = 2;
  p.keyframes.parameters.exponent = 2.0;
  p.keyframes.sampler.cell_rule = {0.75, 0.02};
  p.keyframes.sampler.expected_loss.loss_power = 0.6;
  p.keyframes.sampler.refinement = {true, 4, 0.12};
  p.keyframes.sampler.depth_changes = {0.3, true, 0.4, 512};
  Hotspot h;
  h.id = "tv";
  h.kind = HotspotKind::kEvent;
  h.title = "<img src=x onerror=alert(1)>";
  h.media = (dir / "media" / "lift.mp4").string();
  h.frame = 1;
  h.image_corners = {{0.1, 0.2}, {0.3, 0.2}, {0.3, -0.1}, {0.1, -0.1}};
  h.world_corners = {{1, 2, 1.5}, {2, 2, 1.5}, {2, 2, 0.5}, {1, 2, 0.5}};
  h.trigger = HotspotTrigger::kProximity;
  h.trigger_distance_m = 1.5;
  h.action = HotspotAction::kSwapImage;
  h.action_target = (dir / "media" / "open.png").string();
  p.hotspots = {h};
  p.geo = {true, 48.8566, 2.3522, 35.0, 0.3, 1.01, {5.0, 5.0}};
  p.tour.title = "Office tour";
  p.tour.description = "Line one\nLine \"two\"";
  p.tour.max_size = 2048;
  p.tour.jpeg_quality = 90;
  p.tour.export_geojson = true;
  p.tour.export_marzipano = true;
  p.tour.export_psv = true;
  p.tour.export_kml_gpx = false;  // a default changed: read back as written, not as the default
  p.tour.export_nerfstudio = true;
  p.tour.export_photo_metadata = false;
  p.tour.export_clean_plates = true;
  p.tour.nadir_patch = NadirPatch::kImage;
  p.tour.nadir_image = (dir / "media" / "logo.png").string();
  p.tour.blur_faces = true;
  p.tour.clean_plate_edits = {{12, (dir / "test.masks" / "k000012_1.png").string()}};
  p.capture.rig_mask = (dir / "frames" / "rig mask.png").string();
  return p;
}

// Angles travel as degrees in files; bring them back within 1e-12 rad, then compare everything exactly.
void expect_equal_up_to_angle_rounding(Project expected, Project actual) {
  ASSERT_EQ(expected.path.frames.size(), actual.path.frames.size());
  for (std::size_t i = 0; i < expected.path.frames.size(); ++i) {
    EXPECT_NEAR(expected.path.frames[i].heading, actual.path.frames[i].heading, 1e-12);
    actual.path.frames[i].heading = expected.path.frames[i].heading;
  }
  ASSERT_EQ(expected.anchors.size(), actual.anchors.size());
  for (std::size_t i = 0; i < expected.anchors.size(); ++i) {
    ASSERT_EQ(expected.anchors[i].heading.has_value(), actual.anchors[i].heading.has_value());
    if (expected.anchors[i].heading) {
      EXPECT_NEAR(*expected.anchors[i].heading, *actual.anchors[i].heading, 1e-12);
      actual.anchors[i].heading = expected.anchors[i].heading;
    }
  }
  ASSERT_EQ(expected.hotspots.size(), actual.hotspots.size());
  for (std::size_t i = 0; i < expected.hotspots.size(); ++i) {
    ASSERT_EQ(expected.hotspots[i].image_corners.size(), actual.hotspots[i].image_corners.size());
    for (std::size_t k = 0; k < expected.hotspots[i].image_corners.size(); ++k) {
      EXPECT_LT((expected.hotspots[i].image_corners[k] - actual.hotspots[i].image_corners[k]).norm(), 1e-12);
      actual.hotspots[i].image_corners[k] = expected.hotspots[i].image_corners[k];
    }
  }
  EXPECT_NEAR(expected.geo.plan_rotation, actual.geo.plan_rotation, 1e-12);
  actual.geo.plan_rotation = expected.geo.plan_rotation;

  EXPECT_EQ(expected.plan, actual.plan);
  EXPECT_EQ(expected.capture, actual.capture);
  EXPECT_EQ(expected.path, actual.path);
  EXPECT_EQ(expected.anchors, actual.anchors);
  EXPECT_EQ(expected.visibility, actual.visibility);
  EXPECT_EQ(expected.keyframes, actual.keyframes);
  EXPECT_EQ(expected.hotspots, actual.hotspots);
  EXPECT_EQ(expected.geo, actual.geo);
  EXPECT_EQ(expected.tour, actual.tour);
  EXPECT_TRUE(expected == actual);
}

TEST_F(ProjectIoTest, FullProjectRoundTrips) {
  const Project p = make_full_project(dir_);
  save_project(p, file("tour.plenopath"));
  expect_equal_up_to_angle_rounding(p, load_project(file("tour.plenopath")));
}

TEST_F(ProjectIoTest, EmptyProjectRoundTrips) {
  save_project(Project{}, file("empty.plenopath"));
  EXPECT_EQ(Project{}, load_project(file("empty.plenopath")));
}

TEST_F(ProjectIoTest, MediaPathsAreStoredRelativeAndResolvedOnLoad) {
  const Project p = make_full_project(dir_);
  save_project(p, file("tour.plenopath"));
  const nlohmann::json j = read_json_file(file("tour.plenopath"));
  EXPECT_EQ(j["plan"]["source_file"], "plans/office.dxf");
  EXPECT_EQ(j["capture"]["source"], "capture/frames");
  EXPECT_EQ(j["hotspots"][0]["media"], "media/lift.mp4");
  EXPECT_EQ(j["hotspots"][0]["action_target"], "media/open.png");  // a swap_image target is media too
  EXPECT_EQ(j["format"], "plenopath-project");
  EXPECT_EQ(j["version"], kProjectFormatVersion);

  // Moving the whole folder keeps the project valid: paths follow the project file.
  const fs::path moved = dir_.string() + "_moved";
  fs::remove_all(moved);
  fs::rename(dir_, moved);
  const Project loaded = load_project((moved / "tour.plenopath").string());
  EXPECT_EQ(loaded.plan.source_file, (moved / "plans" / "office.dxf").string());
  EXPECT_EQ(loaded.hotspots.at(0).action_target, (moved / "media" / "open.png").string());
  fs::rename(moved, dir_);
}

// How the keyframes were made travels with them, by name.
TEST_F(ProjectIoTest, KeyframesRecordTheirMethodRuleAndSettings) {
  save_project(make_full_project(dir_), file("k.plenopath"));
  const nlohmann::json j = read_json_file(file("k.plenopath"));
  EXPECT_EQ(j["version"], 2);
  const nlohmann::json& k = j["keyframes"];
  EXPECT_EQ(k["parameters"]["method"], "visibility");
  EXPECT_EQ(k["parameters"]["rule"], "cell_rule");
  EXPECT_EQ(k["sampler"]["cell_rule"]["transition_window_m"], 0.75);
  EXPECT_EQ(k["sampler"]["refinement"]["applied"], true);
  EXPECT_EQ(k["sampler"]["refinement"]["sweeps"], 4);
  EXPECT_EQ(k["sampler"]["depth_changes"]["max_depth_width"], 512);
  EXPECT_EQ(j["hotspots"][0]["trigger"], "proximity");
  EXPECT_EQ(j["hotspots"][0]["action"], "swap_image");
  EXPECT_EQ(j["hotspots"][0]["kind"], "event");
}

// A file of format version 1 (tests/data/projects/version1.plenopath) still opens: no rule and no sampler
// settings recorded, so the defaults of that version (expected_loss, refined by loss); hotspots by name.
TEST_F(ProjectIoTest, ReadsVersion1Files) {
  const std::string v1 = std::string(PLENOPATH_TEST_DATA_DIR) + "/projects/version1.plenopath";
  ASSERT_EQ(read_json_file(v1)["version"], 1);
  const Project p = load_project(v1);
  EXPECT_EQ(p.keyframes.indices, (std::vector<int>{0, 2}));
  EXPECT_EQ(p.keyframes.parameters.method, SamplingMethod::kVisibility);
  EXPECT_EQ(p.keyframes.parameters.rule, VisibilityRule::expected_loss);
  EXPECT_EQ(p.keyframes.parameters.count, 2);
  EXPECT_EQ(p.keyframes.sampler.expected_loss.probe_spacing_m, 0.25);
  EXPECT_EQ(p.keyframes.sampler.expected_loss.loss_power, 0.5);
  EXPECT_TRUE(p.keyframes.sampler.refinement.applied);
  EXPECT_EQ(p.keyframes.sampler.refinement.sweeps, 6);
  ASSERT_EQ(p.hotspots.size(), 2u);
  EXPECT_EQ(p.hotspots[0].kind, HotspotKind::kEvent);
  EXPECT_EQ(p.hotspots[0].trigger, HotspotTrigger::kProximity);
  EXPECT_EQ(p.hotspots[0].action, HotspotAction::kPlaySound);
  EXPECT_EQ(p.hotspots[0].action_target, (fs::path(v1).parent_path() / "media" / "bell.wav").string())
      << "a play_sound target is media: resolved against the project";
  EXPECT_EQ(p.hotspots[1].kind, HotspotKind::kMovieTexture);
  EXPECT_EQ(p.hotspots[1].trigger, HotspotTrigger::kClick);
  EXPECT_EQ(p.hotspots[1].action, HotspotAction::kNone);
  // Saved again, it is a version 2 file that reads back the same.
  save_project(p, file("again.plenopath"));
  EXPECT_EQ(read_json_file(file("again.plenopath"))["version"], 2);
  EXPECT_EQ(load_project(file("again.plenopath")), p);
}

TEST_F(ProjectIoTest, SaveKeepsPreviousVersionAsBak) {
  Project p;
  p.tour.title = "first";
  save_project(p, file("t.plenopath"));
  EXPECT_FALSE(fs::exists(file("t.plenopath.bak")));
  p.tour.title = "second";
  save_project(p, file("t.plenopath"));
  EXPECT_EQ(load_project(file("t.plenopath")).tour.title, "second");
  EXPECT_EQ(load_project(file("t.plenopath.bak")).tour.title, "first");
  // No temporary files are left behind.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) {
    (void)e;
    ++entries;
  }
  EXPECT_EQ(entries, 2);
}

TEST_F(ProjectIoTest, SaveIntoMissingFolderFailsWithoutTouchingAnything) {
  try {
    save_project(Project{}, file("no/such/folder/t.plenopath"));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("t.plenopath"), std::string::npos) << e.what();
  }
}

std::string error_of(const std::string& file) {
  try {
    load_project(file);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST_F(ProjectIoTest, TruncatedJsonIsReportedWithFileName) {
  save_project(make_full_project(dir_), file("t.plenopath"));
  std::ifstream in(file("t.plenopath"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write("cut.plenopath", text.substr(0, text.size() / 2));
  const std::string e = error_of(file("cut.plenopath"));
  EXPECT_NE(e.find("cut.plenopath"), std::string::npos) << e;
  EXPECT_NE(e.find("invalid JSON"), std::string::npos) << e;
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;
}

TEST_F(ProjectIoTest, NumberTooLargeForADoubleIsAnErrorNamingTheFile) {
  // Found by fuzz.project_replay: nlohmann reports 1e400 as out_of_range, not as a parse error, and it
  // escaped load_project as a foreign exception.
  write("big.plenopath", R"({"format":"plenopath-project","version":2,"tour":{"title":"x"},"n":1e400})");
  const std::string e = error_of(file("big.plenopath"));
  EXPECT_NE(e.find("big.plenopath"), std::string::npos) << e;
  EXPECT_NE(e.find("1e400"), std::string::npos) << e;
}

TEST_F(ProjectIoTest, NewerVersionIsRefusedClearly) {
  write("new.plenopath", R"({"format":"plenopath-project","version":99})");
  const std::string e = error_of(file("new.plenopath"));
  EXPECT_NE(e.find("new.plenopath"), std::string::npos) << e;
  EXPECT_NE(e.find("newer"), std::string::npos) << e;
  EXPECT_NE(e.find("99"), std::string::npos) << e;
}

TEST_F(ProjectIoTest, MissingFieldNamesItsJsonPath) {
  write(
      "m.plenopath",
      R"({"format":"plenopath-project","version":1,"path":{"frames":[{"index":0,"x":1,"y":2,"heading_deg":0},)"
      R"({"index":1,"x":1,"heading_deg":0}]}})");
  const std::string e = error_of(file("m.plenopath"));
  EXPECT_NE(e.find("m.plenopath: /path/frames/1: missing field 'y'"), std::string::npos) << e;
}

TEST_F(ProjectIoTest, WrongTypeNamesItsJsonPath) {
  write("w.plenopath", R"({"format":"plenopath-project","version":1,"capture":{"frame_count":"many"}})");
  const std::string e = error_of(file("w.plenopath"));
  EXPECT_NE(e.find("/capture/frame_count: expected an integer, got a string"), std::string::npos) << e;
}

TEST_F(ProjectIoTest, MissingVersionAndWrongFormat) {
  write("v.plenopath", R"({"format":"plenopath-project"})");
  EXPECT_NE(error_of(file("v.plenopath")).find("missing field 'version'"), std::string::npos);
  write("f.plenopath", R"({"format":"something-else","version":1})");
  EXPECT_NE(error_of(file("f.plenopath")).find("not a Plenopath project"), std::string::npos);
  write("a.plenopath", R"([1,2,3])");
  EXPECT_NE(error_of(file("a.plenopath")).find("not a Plenopath project"), std::string::npos);
}

TEST_F(ProjectIoTest, UnreadableOrEmptyFile) {
  EXPECT_NE(error_of(file("absent.plenopath")).find("absent.plenopath: cannot open"), std::string::npos);
  write("empty.plenopath", "");
  EXPECT_NE(error_of(file("empty.plenopath")).find("empty.plenopath: file is empty"), std::string::npos);
  if (::geteuid() != 0) {  // root reads anything; the permission check only means something for users
    write("locked.plenopath", "{}");
    fs::permissions(file("locked.plenopath"), fs::perms::none);
    EXPECT_NE(error_of(file("locked.plenopath")).find("cannot open"), std::string::npos);
  }
  fs::create_directories(file("folder.plenopath"));
  EXPECT_FALSE(error_of(file("folder.plenopath")).empty());
}

TEST_F(ProjectIoTest, InvalidValuesAreRejected) {
  write("k.plenopath", R"({"format":"plenopath-project","version":1,"capture":{"kind":"hologram"}})");
  EXPECT_NE(error_of(file("k.plenopath")).find("/capture/kind: unknown capture kind 'hologram'"),
            std::string::npos);
  write(
      "d.plenopath",
      R"({"format":"plenopath-project","version":1,"path":{"frames":[{"index":3,"x":0,"y":0,"heading_deg":0},)"
      R"({"index":3,"x":1,"y":0,"heading_deg":0}]}})");
  EXPECT_NE(error_of(file("d.plenopath")).find("duplicate frame index 3"), std::string::npos);
  write("q.plenopath", R"({"format":"plenopath-project","version":1,"tour":{"jpeg_quality":400}})");
  EXPECT_NE(error_of(file("q.plenopath")).find("/tour/jpeg_quality"), std::string::npos);
}

// Variable-rate video: the frames' own times travel with the capture; a list that does not fit is refused.
TEST_F(ProjectIoTest, VideoFrameTimesRoundTripAndBadListsAreRejected) {
  Project p;
  p.capture.kind = CaptureKind::kVideo;
  p.capture.source = file("walk.mp4");
  p.capture.frame_count = 4;
  p.capture.frame_rate = 30.0;
  p.capture.first_frame = 10;
  p.capture.stride = 2;
  p.capture.frame_times_s = {0.5, 0.5 + 1.0 / 15, 0.5 + 2.0 / 15, 0.7};
  save_project(p, file("vfr.plenopath"));
  EXPECT_EQ(load_project(file("vfr.plenopath")).capture, p.capture);
  save_project(Project{}, file("cfr.plenopath"));
  EXPECT_FALSE(read_json_file(file("cfr.plenopath"))["capture"].contains("frame_times_s"))
      << "evenly spaced captures store no list";

  const std::string head = R"({"format":"plenopath-project","version":1,"capture":{"kind":"video",)";
  write("n.plenopath", head + R"("frame_count":3,"frame_times_s":[0,0.1]}})");
  EXPECT_NE(error_of(file("n.plenopath")).find("/capture/frame_times_s: has 2 times for 3 frames"),
            std::string::npos)
      << error_of(file("n.plenopath"));
  write("o.plenopath", head + R"("frame_count":3,"frame_times_s":[0,0.2,0.1]}})");
  EXPECT_NE(error_of(file("o.plenopath")).find("/capture/frame_times_s/2: must be a finite time after"),
            std::string::npos)
      << error_of(file("o.plenopath"));
}

TEST(CaptureTimes, KeptFramesAndVideoFrameNumbersMapToTime) {
  Capture c;
  c.kind = CaptureKind::kVideo;
  c.frame_rate = 10.0;
  c.first_frame = 4;
  c.stride = 3;
  c.frame_count = 3;
  EXPECT_DOUBLE_EQ(c.frame_time_s(2), 1.0);      // video frame 4 + 2 * 3 = 10, at 10 fps
  EXPECT_DOUBLE_EQ(c.time_at_index_s(10), 1.0);  // the same frame by its number
  c.frame_times_s = {0.5, 0.9, 1.5};             // frames 4, 7, 10
  EXPECT_DOUBLE_EQ(c.frame_time_s(1), 0.9);
  EXPECT_DOUBLE_EQ(c.time_at_index_s(7), 0.9);
  EXPECT_DOUBLE_EQ(c.time_at_index_s(8), 1.0);   // between kept frames: 0.1 s on from frame 7
  EXPECT_DOUBLE_EQ(c.time_at_index_s(12), 1.7);  // after the last: 0.2 s on from frame 10
  EXPECT_DOUBLE_EQ(c.time_at_index_s(2), 0.3);   // before the first: 0.2 s before frame 4
}

// A name this build does not know (a project from a newer studio, or edited by hand): an error naming the
// file, the JSON path and the value.
TEST_F(ProjectIoTest, UnknownNamesAreRefusedNamingFileAndValue) {
  const std::string head = R"({"format":"plenopath-project","version":2,)";
  const std::string spot = R"("hotspots":[{"id":"a","kind":"event","frame":0,)";
  struct Case {
    std::string name, json, path, value;
  };
  const std::vector<Case> cases = {
      {"action", head + spot + R"("action":"teleport"}]})", "/hotspots/0/action", "'teleport'"},
      {"trigger", head + spot + R"("trigger":"telepathy"}]})", "/hotspots/0/trigger", "'telepathy'"},
      {"kind", head + R"("hotspots":[{"id":"a","kind":"hologram"}]})", "/hotspots/0/kind", "'hologram'"},
      {"method", head + R"("keyframes":{"parameters":{"method":"learned"}}})", "/keyframes/parameters/method",
       "'learned'"},
      {"rule", head + R"("keyframes":{"parameters":{"method":"visibility","rule":"oracle"}}})",
       "/keyframes/parameters/rule", "'oracle'"},
  };
  for (const Case& c : cases) {
    write(c.name + ".plenopath", c.json);
    const std::string e = error_of(file(c.name + ".plenopath"));
    EXPECT_NE(e.find(c.name + ".plenopath: " + c.path + ": unknown"), std::string::npos) << e;
    EXPECT_NE(e.find(c.value), std::string::npos) << e;
    EXPECT_NE(e.find("newer Plenopath Studio"), std::string::npos) << e;
  }
  // The message lists what is known.
  EXPECT_NE(error_of(file("action.plenopath")).find("'swap_image'"), std::string::npos);
  EXPECT_NE(error_of(file("trigger.plenopath")).find("'click' or 'proximity'"), std::string::npos);
}

}  // namespace
}  // namespace plenopath
