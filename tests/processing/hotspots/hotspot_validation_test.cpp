// Hotspot validation: each kind of problem an author can make gives a warning naming the hotspot and the
// field, and a clean hotspot gives none. Media files are made here (a real PNG, a file of garbage bytes).
#include "processing/hotspots/hotspot_validation.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "model/error.h"
#include "processing/hotspots/hotspot_geometry.h"

namespace plenopath {
namespace {

namespace fs = std::filesystem;

struct Files {
  fs::path dir;
  std::string good_png, good_video, broken_png, broken_mp4, sound;
  Files() {
    dir = fs::temp_directory_path() / ("plenopath-hotspot-validation-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    good_png = (dir / "poster.png").string();
    cv::imwrite(good_png, cv::Mat(16, 24, CV_8UC3, cv::Scalar(20, 200, 40)));
    good_video = (dir / "doors.avi").string();
    cv::VideoWriter doors(good_video, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10.0,
                          cv::Size(32, 24));
    for (int k = 0; k < 5; ++k) doors.write(cv::Mat(24, 32, CV_8UC3, cv::Scalar(40 * k, 80, 200)));
    doors.release();
    broken_png = (dir / "broken.png").string();
    std::ofstream(broken_png) << "this is not a PNG at all";
    broken_mp4 = (dir / "broken.mp4").string();
    std::ofstream(broken_mp4) << "nor is this a video";
    sound = (dir / "bell.wav").string();
    std::ofstream(sound) << "RIFF....WAVE";
  }
  ~Files() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};
const Files& files() {
  static const Files f;
  return f;
}

// One frame at (1, 3.5) looking +x, camera 1.6 m up; a poster on the wall x = 8 marked from there.
Project project_with(const Hotspot& h) {
  Project p;
  PathFrame f;
  f.index = 5;
  f.x = 1.0;
  f.y = 3.5;
  p.path.frames.push_back(f);
  p.capture.camera_height_m = 1.6;
  p.hotspots.push_back(h);
  return p;
}

Hotspot good_movie_texture() {
  Hotspot h;
  h.id = "tv";
  h.title = "TV";
  h.kind = HotspotKind::kMovieTexture;
  h.media = files().good_png;
  h.frame = 5;
  PathFrame f;
  f.x = 1.0;
  f.y = 3.5;
  h.world_corners = {{8, 4.5, 2.2}, {8, 3, 2.2}, {8, 3, 1}, {8, 4.5, 1}};
  for (const auto& c : h.world_corners) {
    const SphericalAngles a = direction_in_frame(c, f, 1.6);
    h.image_corners.push_back({a.azimuth, a.elevation});
  }
  return h;
}

bool has_field(const std::vector<HotspotWarning>& w, const std::string& field) {
  for (const auto& x : w)
    if (x.field == field) return true;
  return false;
}

std::string all(const std::vector<HotspotWarning>& w) {
  std::string s;
  for (const auto& x : w) s += x.field + ": " + x.message + "\n";
  return s;
}

TEST(HotspotValidation, ACleanMovieTextureHasNoWarnings) {
  const Hotspot h = good_movie_texture();
  const auto w = validate_hotspots(project_with(h));
  EXPECT_TRUE(w.empty()) << all(w);
}

TEST(HotspotValidation, MissingAndUnreadableMedia) {
  Hotspot h = good_movie_texture();
  h.media = (files().dir / "gone.png").string();
  auto w = validate_hotspot(h, project_with(h));
  ASSERT_TRUE(has_field(w, "media")) << all(w);
  EXPECT_NE(w[0].message.find("not found"), std::string::npos);
  EXPECT_NE(w[0].message.find("'tv'"), std::string::npos) << "names the hotspot";
  h.media = files().broken_png;
  w = validate_hotspot(h, project_with(h));
  ASSERT_TRUE(has_field(w, "media")) << all(w);
  EXPECT_NE(w[0].message.find("cannot be decoded"), std::string::npos) << w[0].message;
  h.media = files().broken_mp4;
  w = validate_hotspot(h, project_with(h));
  ASSERT_TRUE(has_field(w, "media")) << all(w);
  EXPECT_NE(w[0].message.find("video cannot be decoded"), std::string::npos) << w[0].message;
  h.media = files().sound;
  w = validate_hotspot(h, project_with(h));
  ASSERT_TRUE(has_field(w, "media")) << all(w);
  EXPECT_NE(w[0].message.find("audio"), std::string::npos) << w[0].message;
  h.media.clear();
  EXPECT_TRUE(has_field(validate_hotspot(h, project_with(h)), "media"));
  // Without decoding, the broken PNG passes (existence only).
  h.media = files().broken_png;
  HotspotValidationOptions quick;
  quick.decode_media = false;
  EXPECT_FALSE(has_field(validate_hotspot(h, project_with(h), quick), "media"));
}

TEST(HotspotValidation, QuadInconsistentWithItsMarksOrNotPlanar) {
  // Moving one 3-D corner 30 cm off the wall: not planar (rms 0.3 / 4 = 0.075 m > 0.05).
  Hotspot h = good_movie_texture();
  h.world_corners[0].x() -= 0.3;
  auto w = validate_hotspot(h, project_with(h));
  ASSERT_TRUE(has_field(w, "world_corners")) << all(w);
  EXPECT_NE(all(w).find("not on one plane (rms 0.07"), std::string::npos) << all(w);
  // A mark moved 5 degrees to the right: on the wall 7 m away it lands about 0.6 m from its 3-D corner.
  h = good_movie_texture();
  h.image_corners[2].x() += 5.0 * M_PI / 180.0;
  w = validate_hotspot(h, project_with(h));
  ASSERT_EQ(w.size(), 1u) << all(w);
  EXPECT_NE(w[0].message.find("not consistent with one plane across frames"), std::string::npos) << all(w);
  // Sliding the whole quad 40 cm along its wall keeps it planar but no longer under its marks.
  h = good_movie_texture();
  for (auto& c : h.world_corners) c.y() -= 0.4;
  w = validate_hotspot(h, project_with(h));
  ASSERT_EQ(w.size(), 1u) << all(w);
  EXPECT_NE(w[0].message.find("0.40 m"), std::string::npos) << w[0].message;
}

TEST(HotspotValidation, MarkupIsReportedAsShownAsText) {
  EXPECT_TRUE(text_has_markup("<b>Lift</b>"));
  EXPECT_TRUE(text_has_markup("see <img src=x onerror=alert(1)>"));
  EXPECT_TRUE(text_has_markup("fish &amp; chips"));
  EXPECT_TRUE(text_has_markup("&#60;script&#62;"));
  EXPECT_FALSE(text_has_markup("3 < 4 and 5 > 2"));
  EXPECT_FALSE(text_has_markup("Fish & chips"));
  Hotspot h = good_movie_texture();
  h.title = "<i>TV</i>";
  EXPECT_TRUE(has_field(validate_hotspot(h, project_with(h)), "title"));
  h = good_movie_texture();
  h.kind = HotspotKind::kEvent;
  h.action = HotspotAction::kShowText;
  h.action_target = "<script>alert(1)</script>";
  const auto w = validate_hotspot(h, project_with(h));
  ASSERT_TRUE(has_field(w, "action_target")) << all(w);
  EXPECT_NE(all(w).find("shown as plain text"), std::string::npos);
}

TEST(HotspotValidation, EventActionsNeedUsableTargets) {
  Hotspot h = good_movie_texture();
  h.kind = HotspotKind::kEvent;
  h.media.clear();
  auto warnings_for = [&](HotspotAction action, const std::string& target) {
    h.action = action;
    h.action_target = target;
    return validate_hotspot(h, project_with(h));
  };
  EXPECT_TRUE(warnings_for(HotspotAction::kJump, "5").empty());
  EXPECT_TRUE(has_field(warnings_for(HotspotAction::kJump, "6"), "action_target"))
      << "frame 6 is not on the path";
  EXPECT_TRUE(warnings_for(HotspotAction::kJump, "https://example.org/other-tour/").empty());
  EXPECT_TRUE(has_field(warnings_for(HotspotAction::kJump, "somewhere"), "action_target"));
  EXPECT_TRUE(warnings_for(HotspotAction::kOpenUrl, "https://example.org").empty());
  EXPECT_TRUE(has_field(warnings_for(HotspotAction::kOpenUrl, "javascript:alert(1)"), "action_target"));
  EXPECT_TRUE(warnings_for(HotspotAction::kSwapImage, files().good_png).empty());
  EXPECT_TRUE(has_field(warnings_for(HotspotAction::kSwapImage, files().broken_png), "action_target"));
  // An image sequence (the lift doors opening) is swapped in as a video; an unreadable one is reported.
  EXPECT_TRUE(warnings_for(HotspotAction::kSwapImage, files().good_video).empty());
  EXPECT_TRUE(has_field(warnings_for(HotspotAction::kSwapImage, files().broken_mp4), "action_target"));
  EXPECT_TRUE(warnings_for(HotspotAction::kPlaySound, files().sound).empty());
  EXPECT_TRUE(has_field(warnings_for(HotspotAction::kPlaySound, (files().dir / "none.wav").string()),
                        "action_target"));
  EXPECT_TRUE(has_field(warnings_for(HotspotAction::kPlayVideo, files().broken_mp4), "action_target"));
  EXPECT_TRUE(has_field(warnings_for(HotspotAction::kNone, ""), "action"));
  EXPECT_TRUE(warnings_for(HotspotAction::kShowText, "Plain words").empty());
  h.trigger = HotspotTrigger::kProximity;
  h.trigger_distance_m = 0;
  EXPECT_TRUE(has_field(warnings_for(HotspotAction::kShowText, "Plain words"), "trigger_distance_m"));
  // Unknown action or trigger names cannot reach here: reading the file refuses them (project_io_test).
}

TEST(HotspotValidation, ProjectLevelProblems) {
  Project p = project_with(good_movie_texture());
  p.hotspots.push_back(good_movie_texture());  // same id
  Hotspot orphan = good_movie_texture();
  orphan.id = "orphan";
  orphan.frame = 99;
  p.hotspots.push_back(orphan);
  const auto w = validate_hotspots(p);
  EXPECT_TRUE(has_field(w, "id")) << all(w);
  EXPECT_TRUE(has_field(w, "frame")) << all(w);
  HotspotValidationOptions bad;
  bad.max_planarity_m = 0;
  EXPECT_THROW(validate_hotspots(p, bad), Error);
}

}  // namespace
}  // namespace plenopath
