// CG capture through POV-Ray: the depth coded by two fogged passes must agree with the scene's geometry,
// computed here by intersecting each pixel's ray with the room and the sphere by hand (the spherical camera's
// pixel mapping of ARCHITECTURE.md), to 1 mm; scene units other than metres, and the errors a user meets.
#include "processing/capture/povray_render.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "model/error.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("plenopath_povray_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

// A room 10 x 6 x 3 m (POV x in [-5, 5], z in [-3, 3], y in [0, 3]; plan x, y = POV x, z), a mirror-ish
// white sphere at plan (2, 1.5), 1 m up, radius 0.5; one light; the author's own perspective camera, which
// the studio's must replace. `scale`: scene units per metre. `solid`: the room is a plain box, so the camera
// is inside a solid object (not hollow: POV-Ray puts no fog there, and so no depth).
// `z_up`: the same room modelled with z up (POV <x, y, z> = plan X, Y and height), as CAD exports write.
void write_room(const fs::path& file, double scale, bool solid = false, bool z_up = false) {
  auto v = [z_up](double x, double up, double y) {
    return "<" + std::to_string(x) + ", " + std::to_string(z_up ? y : up) + ", " +
           std::to_string(z_up ? up : y) + ">";
  };
  std::ofstream out(file);
  out << "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n#declare S = " << scale << ";\n"
      << "camera { perspective location <1, 1, 1> * S look_at <0, 0, 0> }\n"
      << "light_source { " << v(2, 2.8, 1) << " * S color rgb 1 }\n"
      << "box { " << v(-5, 0, -3) << " * S, " << v(5, 3, 3) << " * S" << (solid ? "" : " inverse") << "\n"
      << "  pigment { checker rgb <0.8, 0.7, 0.6> rgb <0.2, 0.3, 0.4> scale 0.5 * S } finish { diffuse 0.8 } "
         "}\n"
      << "sphere { " << v(2, 1, 1.5) << " * S, 0.5 * S pigment { rgb 1 } finish { reflection 0.5 } }\n";
}

// Distance from the camera centre along the ray of pixel (u, v) to the room or the sphere (plan metres).
double true_depth(int u, int v, int width, const PathFrame& pose, double camera_height) {
  const int height = width / 2;
  const double azimuth = ((u + 0.5) / width * 2.0 - 1.0) * M_PI;  // clockwise from the heading
  const double elevation = M_PI / 2 - (v + 0.5) / height * M_PI;
  const double a = pose.heading - azimuth;
  const double dx = std::cos(elevation) * std::cos(a), dy = std::cos(elevation) * std::sin(a),
               dz = std::sin(elevation);
  const double px = pose.x, py = pose.y, pz = camera_height;
  double t = 1e9;
  auto wall = [&](double d, double p, double lo, double hi) {
    if (std::abs(d) > 1e-12) t = std::min(t, std::max((lo - p) / d, (hi - p) / d));
  };
  wall(dx, px, -5, 5);
  wall(dy, py, -3, 3);
  wall(dz, pz, 0, 3);
  const double cx = 2 - px, cy = 1.5 - py, cz = 1 - pz;
  const double b = dx * cx + dy * cy + dz * cz, disc = b * b - (cx * cx + cy * cy + cz * cz - 0.25);
  if (disc > 0 && b - std::sqrt(disc) > 0) t = std::min(t, b - std::sqrt(disc));
  return t;
}

void expect_depth_matches(const PovrayFrame& frame, const PathFrame& pose, double camera_height) {
  const int width = frame.depth.cols, height = frame.depth.rows;
  int compared = 0, within = 0;
  double worst = 0, sum = 0;
  for (int v = 1; v < height - 1; ++v)
    for (int u = 1; u < width - 1; ++u) {
      const double d = true_depth(u, v, width, pose, camera_height);
      // Away from silhouettes and room corners (a neighbour's ray lands elsewhere): those pixels' depth is
      // right for their centre too, but a hundredth of a pixel there is centimetres.
      bool edge = false;
      for (int k = -1; k <= 1 && !edge; ++k)
        for (int l = -1; l <= 1 && !edge; ++l)
          edge = std::abs(true_depth(u + k, v + l, width, pose, camera_height) - d) > 0.03 * d;
      if (edge) continue;
      const double e = std::abs(frame.depth.at<float>(v, u) - d);
      ++compared;
      within += e < 0.001;
      worst = std::max(worst, e);
      sum += e;
    }
  std::printf(
      "POV-Ray depth against the geometry: %d pixels, mean error %.3f mm, worst %.3f mm, %.2f %% "
      "within 1 mm\n",
      compared, 1000 * sum / compared, 1000 * worst, 100.0 * within / compared);
  EXPECT_GT(compared, width * height / 3);
  EXPECT_GE(within, compared * 995 / 1000);
  EXPECT_LT(sum / compared, 0.0003);
}

TEST(PovrayRender, DepthAgreesWithTheSceneGeometryToAMillimetre) {
  TempDir dir;
  write_room(dir.path / "room.pov", 1.0);
  PovrayOptions options;
  options.width = 192;
  options.quality = 2;  // the colour pass is not what is checked here
  options.antialias = false;
  PathFrame pose;
  pose.x = -1.2;
  pose.y = 0.4;
  pose.heading = 0.7;
  const PovrayFrame frame =
      render_povray_frame((dir.path / "room.pov").string(), pose, options, dir.path.string());
  ASSERT_EQ(frame.rgb.size(), cv::Size(192, 96));
  ASSERT_EQ(frame.rgb.type(), CV_8UC3);
  ASSERT_EQ(frame.depth.size(), cv::Size(192, 96));
  expect_depth_matches(frame, pose, options.camera_height_m);
  // The colour pass sees the room from the same camera: the white sphere where its depth says.
  const double sphere_azimuth = pose.heading - std::atan2(1.5 - pose.y, 2 - pose.x);
  const int su = static_cast<int>((sphere_azimuth / (2 * M_PI) + 0.5) * 192);
  const double sphere_elevation = std::atan2(1.0 - 1.6, std::hypot(2 - pose.x, 1.5 - pose.y));
  const int sv = static_cast<int>((0.5 - sphere_elevation / M_PI) * 96);
  const cv::Vec3b at_sphere = frame.rgb.at<cv::Vec3b>(sv, su);
  EXPECT_NEAR(frame.depth.at<float>(sv, su), std::hypot(std::hypot(2 - pose.x, 1.5 - pose.y), 0.6) - 0.5,
              0.05);
  // The sphere is white (grey where shaded), the walls are coloured.
  EXPECT_LE(std::abs(at_sphere[0] - at_sphere[2]), 3) << "not the sphere's colour";
  EXPECT_GT(at_sphere[0], 40);
  const cv::Vec3b at_wall = frame.rgb.at<cv::Vec3b>(48, (su + 96) % 192);
  EXPECT_GT(std::abs(at_wall[0] - at_wall[2]), 10);
}

// The author's own atmosphere (a fog in the scene, radiosity in an include) is kept in the colour pass but
// must not disturb the coded depth: still within a millimetre of the geometry.
TEST(PovrayRender, TheAuthorsFogAndRadiosityDoNotDisturbTheDepth) {
  TempDir dir;
  write_room(dir.path / "room.pov", 1.0);
  std::ofstream(dir.path / "room.pov", std::ios::app)
      << "#include \"settings.inc\"\nfog { fog_type 1 distance 2 color rgb <0.5, 0.7, 0.95> }\n";
  std::ofstream(dir.path / "settings.inc") << "global_settings { radiosity { count 20 error_bound 1.8 } }\n";
  PovrayOptions options;
  options.width = 192;
  options.quality = 9;  // fog (and radiosity) need it in the colour pass too
  options.antialias = false;
  PathFrame pose;
  pose.x = -1.2;
  pose.y = 0.4;
  pose.heading = 0.7;
  const PovrayFrame frame =
      render_povray_frame((dir.path / "room.pov").string(), pose, options, dir.path.string());
  expect_depth_matches(frame, pose, options.camera_height_m);
  // The colour pass is the author's: the wall ahead (4 m away at the horizon) is mostly the bluish fog.
  const cv::Vec3b far = frame.rgb.at<cv::Vec3b>(48, 96);
  std::printf("far wall through the author's fog: BGR %d %d %d\n", far[0], far[1], far[2]);
  EXPECT_GT(far[0], far[2] + 40);  // blue well above red
  EXPECT_GT(far[0], 150);
  EXPECT_FALSE(std::filesystem::exists(dir.path / "depth-scene"));  // the copy is cleaned up
}

// A walk rendered in animation mode, two processes of three frames and one of one: every frame delivered
// once, in order, each with the depth of its own pose (a mixed-up camera array would put frames at another
// pose: 0.3 m apart, far above the 1 mm checked). Depth only, as online sampling's coarse pass renders.
TEST(PovrayRender, AWalkInChunksDeliversEachFrameAtItsOwnPose) {
  TempDir dir;
  write_room(dir.path / "room.pov", 1.0);
  PovrayOptions options;
  options.width = 160;
  options.colour = false;
  options.frames_per_process = 3;
  options.processes = 2;
  std::vector<PathFrame> walk(7);
  for (int i = 0; i < 7; ++i) {
    walk[i].index = 100 + i;
    walk[i].x = -3.0 + 0.3 * i;
    walk[i].y = -0.5 + 0.1 * i;
    walk[i].heading = 0.2 * i;
  }
  std::vector<int> delivered;
  render_povray_frames((dir.path / "room.pov").string(), walk, options, dir.path.string(),
                       [&](int index, PovrayFrame&& frame) {
                         delivered.push_back(index);
                         EXPECT_TRUE(frame.rgb.empty());
                         ASSERT_EQ(frame.depth.size(), cv::Size(160, 80));
                         expect_depth_matches(frame, walk[static_cast<std::size_t>(index)], 1.6);
                       });
  EXPECT_EQ(delivered, std::vector<int>({0, 1, 2, 3, 4, 5, 6}));
  // Nothing of the passes is left behind.
  for (const auto& entry : fs::directory_iterator(dir.path))
    EXPECT_EQ(entry.path().filename(), "room.pov") << entry.path();
}

// A scene modelled with z up renders the same room at the same pose: depth against the same geometry.
TEST(PovrayRender, ScenesModelledWithZUp) {
  TempDir dir;
  write_room(dir.path / "room_z.pov", 1.0, false, true);
  PovrayOptions options;
  options.width = 160;
  options.colour = false;
  options.z_up = true;
  PathFrame pose;
  pose.x = 1.1;
  pose.y = -0.7;
  pose.heading = -2.2;
  const PovrayFrame frame =
      render_povray_frame((dir.path / "room_z.pov").string(), pose, options, dir.path.string());
  expect_depth_matches(frame, pose, options.camera_height_m);
}

TEST(PovrayRender, SceneUnitsOtherThanMetres) {
  TempDir dir;
  write_room(dir.path / "room_cm.pov", 100.0);  // the same room drawn in centimetres
  PovrayOptions options;
  options.width = 128;
  options.quality = 0;
  options.antialias = false;
  options.units_per_metre = 100.0;
  PathFrame pose;
  pose.x = 0.5;
  pose.y = -1.0;
  pose.heading = -2.0;
  const PovrayFrame frame =
      render_povray_frame((dir.path / "room_cm.pov").string(), pose, options, dir.path.string());
  expect_depth_matches(frame, pose, options.camera_height_m);
}

TEST(PovrayRender, ClearErrorsForMissingScenesBrokenScenesAndNoPovray) {
  TempDir dir;
  PovrayOptions options;
  options.width = 32;
  try {
    render_povray_frame((dir.path / "missing.pov").string(), {}, options, dir.path.string());
    FAIL() << "no error for a missing scene";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.pov"), std::string::npos) << e.what();
  }
  {
    std::ofstream out(dir.path / "broken.pov");
    out << "sphere { <0, 1, 0>, 1 pigment { rgb 1 }\n";  // unclosed
  }
  try {
    render_povray_frame((dir.path / "broken.pov").string(), {}, options, dir.path.string());
    FAIL() << "no error for a broken scene";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("broken.pov"), std::string::npos) << what;
    EXPECT_NE(what.find("POV-Ray failed"), std::string::npos) << what;
  }
  write_room(dir.path / "solid_room.pov", 1.0, true);
  try {
    render_povray_frame((dir.path / "solid_room.pov").string(), {}, options, dir.path.string());
    FAIL() << "no error for a camera inside a solid object";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("hollow"), std::string::npos) << e.what();
    // It says which frame, where: the frame at the origin, 1.6 m up.
    EXPECT_NE(std::string(e.what()).find("at frame 0 (0.000, 0.000) m, 1.600 m up"), std::string::npos)
        << e.what();
  }
  options.executable = "no-such-povray-program";
  write_room(dir.path / "room.pov", 1.0);
  try {
    render_povray_frame((dir.path / "room.pov").string(), {}, options, dir.path.string());
    FAIL() << "no error without povray";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("apt-get install povray"), std::string::npos) << e.what();
  }
  options = {};
  options.width = 15;
  EXPECT_THROW(options.check(), Error);
}

}  // namespace
}  // namespace plenopath
