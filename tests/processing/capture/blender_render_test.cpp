// CG capture through Blender (Cycles): the test makes its own scene with Blender's Python (a box room whose
// walls, floor and ceiling glow in six colours, and a magenta cube), and checks every pixel against the room
// intersected here by hand along the pixel's ray (the spherical camera's mapping of ARCHITECTURE.md): the
// depth to a millimetre, and the colour of the surface hit, which pins the orientation (heading, clockwise
// azimuth, zenith at the top). Skipped, saying so, where blender is not installed.
#include "processing/capture/blender_render.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "model/error.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name = "work")
      : path(fs::temp_directory_path() / ("plenopath_blender_" + std::to_string(::getpid()) + "_" + name)) {
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

// The room: x in [-5, 5], y in [-3, 3], z in [0, 3] metres (Blender is z up, like the plan); a cube of side
// 0.6 m centred at (2, 1.5, 1). Surfaces: 0 east (x = 5), 1 west, 2 north (y = 3), 3 south, 4 floor,
// 5 ceiling, 6 the cube. Emission shaders and the Standard view transform: each pixel shows its colour.
const cv::Vec3b kColours[7] = {{0, 0, 255},     {0, 255, 0},     {255, 0, 0},  {0, 255, 255},
                               {149, 149, 149}, {255, 255, 255}, {255, 0, 255}};  // BGR

// Writes room.blend (metres) and room_cm.blend (the same room drawn in centimetres: unit scale 0.01) with
// one Blender run, each with its own perspective camera, which the studio's must replace.
void make_rooms(const fs::path& dir) {
  const fs::path script = dir / "make_rooms.py";
  std::ofstream(script) << R"PY(
import bpy, sys
out = sys.argv[sys.argv.index("--") + 1]
def room(file, s):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.unit_settings.system = 'METRIC'
    scene.unit_settings.scale_length = 1.0 / s
    scene.view_settings.view_transform = 'Standard'
    def material(name, rgb):
        m = bpy.data.materials.new(name)
        m.use_nodes = True
        nodes = m.node_tree.nodes
        nodes.clear()
        e = nodes.new("ShaderNodeEmission")
        e.inputs[0].default_value = (rgb[0], rgb[1], rgb[2], 1)
        o = nodes.new("ShaderNodeOutputMaterial")
        m.node_tree.links.new(e.outputs[0], o.inputs[0])
        return m
    def quad(name, corners, rgb):
        mesh = bpy.data.meshes.new(name)
        mesh.from_pydata([(x * s, y * s, z * s) for x, y, z in corners], [], [(0, 1, 2, 3)])
        mesh.materials.append(material(name, rgb))
        scene.collection.objects.link(bpy.data.objects.new(name, mesh))
    quad("east", [(5, -3, 0), (5, 3, 0), (5, 3, 3), (5, -3, 3)], (1, 0, 0))
    quad("west", [(-5, -3, 0), (-5, 3, 0), (-5, 3, 3), (-5, -3, 3)], (0, 1, 0))
    quad("north", [(-5, 3, 0), (5, 3, 0), (5, 3, 3), (-5, 3, 3)], (0, 0, 1))
    quad("south", [(-5, -3, 0), (5, -3, 0), (5, -3, 3), (-5, -3, 3)], (1, 1, 0))
    quad("floor", [(-5, -3, 0), (5, -3, 0), (5, 3, 0), (-5, 3, 0)], (0.3, 0.3, 0.3))
    quad("ceiling", [(-5, -3, 3), (5, -3, 3), (5, 3, 3), (-5, 3, 3)], (1, 1, 1))
    bpy.ops.mesh.primitive_cube_add(size=0.6 * s, location=(2 * s, 1.5 * s, 1 * s))
    bpy.context.object.data.materials.append(material("marker", (1, 0, 1)))
    camera = bpy.data.objects.new("AuthorCamera", bpy.data.cameras.new("AuthorCamera"))
    camera.location = (s, s, s)
    scene.collection.objects.link(camera)
    scene.camera = camera
    bpy.ops.wm.save_as_mainfile(filepath=file)
room(out + "/room.blend", 1.0)
room(out + "/room_cm.blend", 100.0)
)PY";
  const std::string command = "blender -b --factory-startup --python-exit-code 1 --python '" +
                              script.string() + "' -- '" + dir.string() + "' > '" +
                              (dir / "make_rooms.log").string() + "' 2>&1";
  if (std::system(command.c_str()) != 0 || !fs::exists(dir / "room.blend") ||
      !fs::exists(dir / "room_cm.blend"))
    ADD_FAILURE() << "Blender could not make the test scenes: " << command;
}

// The scenes, made once for the suite (a Blender start is a second or two).
class BlenderRender : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    try {
      find_blender("blender");
    } catch (const Error&) {
      return;
    }
    scenes_ = new TempDir("scenes");
    make_rooms(scenes_->path);
  }
  static void TearDownTestSuite() {
    delete scenes_;
    scenes_ = nullptr;
  }
  static fs::path scene(const std::string& name) { return scenes_->path / name; }
  static TempDir* scenes_;
};
TempDir* BlenderRender::scenes_ = nullptr;

#define SKIP_WITHOUT_BLENDER()                                                                       \
  try {                                                                                              \
    find_blender("blender");                                                                         \
  } catch (const Error&) {                                                                           \
    GTEST_SKIP()                                                                                     \
        << "blender is not installed (cmake/install-deps.sh installs it): the Blender route is not " \
           "tested";                                                                                 \
  }

struct Hit {
  double distance = 1e9;
  int surface = -1;
};

// The first surface along the ray of pixel (u, v) of a width x width/2 panorama at `pose`, camera 1.6 m up.
Hit intersect(double u, double v, int width, const PathFrame& pose) {
  const int height = width / 2;
  const double azimuth = (u + 0.5) / width * 2 * M_PI - M_PI;  // clockwise from the heading
  const double elevation = M_PI / 2 - (v + 0.5) / height * M_PI;
  const double a = pose.heading - azimuth;
  const double d[3] = {std::cos(elevation) * std::cos(a), std::cos(elevation) * std::sin(a),
                       std::sin(elevation)};
  const double p[3] = {pose.x, pose.y, 1.6};
  Hit hit;
  // The room from inside: the nearest wall ahead on each axis.
  const double lo[3] = {-5, -3, 0}, hi[3] = {5, 3, 3};
  const int low_surface[3] = {1, 3, 4}, high_surface[3] = {0, 2, 5};
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) continue;
    const double t = ((d[k] > 0 ? hi[k] : lo[k]) - p[k]) / d[k];
    if (t < hit.distance) hit = {t, d[k] > 0 ? high_surface[k] : low_surface[k]};
  }
  // The cube from outside (slabs).
  const double c[3] = {2, 1.5, 1};
  double near = -1e9, far = 1e9;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (std::abs(p[k] - c[k]) > 0.3) far = -1;
      continue;
    }
    const double t1 = (c[k] - 0.3 - p[k]) / d[k], t2 = (c[k] + 0.3 - p[k]) / d[k];
    near = std::max(near, std::min(t1, t2));
    far = std::min(far, std::max(t1, t2));
  }
  if (near <= far && near > 0 && near < hit.distance) hit = {near, 6};
  return hit;
}

struct Agreement {
  int compared = 0, colour_right = 0;
  double mean_mm = 0, worst_mm = 0;
};

// Every pixel whose 3 x 3 neighbourhood sees one surface (elsewhere a hundredth of a pixel moves the hit
// across an edge); depth in metres, colour of the surface hit.
Agreement compare(const BlenderFrame& frame, const PathFrame& pose, bool colour) {
  const int width = frame.depth.cols, height = frame.depth.rows;
  Agreement a;
  double sum = 0;
  for (int v = 1; v < height - 1; ++v)
    for (int u = 1; u < width - 1; ++u) {
      const Hit h = intersect(u, v, width, pose);
      bool edge = false;
      for (int k = -1; k <= 1 && !edge; ++k)
        for (int l = -1; l <= 1 && !edge; ++l)
          edge = intersect(u + k, v + l, width, pose).surface != h.surface;
      if (edge) continue;
      const double e = 1000 * std::abs(frame.depth.at<float>(v, u) - h.distance);
      ++a.compared;
      sum += e;
      a.worst_mm = std::max(a.worst_mm, e);
      if (colour) {
        const cv::Vec3b got = frame.rgb.at<cv::Vec3b>(v, u), want = kColours[h.surface];
        a.colour_right += std::abs(got[0] - want[0]) <= 8 && std::abs(got[1] - want[1]) <= 8 &&
                          std::abs(got[2] - want[2]) <= 8;
      }
    }
  a.mean_mm = sum / std::max(1, a.compared);
  return a;
}

TEST_F(BlenderRender, PosesOfOneCallAgreeWithTheRoomInDepthAndColourInOrder) {
  SKIP_WITHOUT_BLENDER();
  TempDir dir;
  BlenderOptions options;
  options.width = 128;
  options.samples = 2;  // emission only: every sample is the same colour
  std::vector<PathFrame> poses(3);
  poses[0].x = -4.0;  // heading 0: the east (red) wall ahead, 9 m
  poses[1].x = -1.2;
  poses[1].y = 0.4;
  poses[1].heading = 0.7;
  poses[2].x = 3.1;
  poses[2].y = -1.7;
  poses[2].heading = 2.4;  // the cube 28 deg right of the centre (14 deg left from the first pose)
  std::vector<int> delivered;
  render_blender_frames(
      scene("room.blend").string(), poses, options, dir.path.string(), [&](int index, BlenderFrame&& frame) {
        delivered.push_back(index);
        ASSERT_EQ(frame.rgb.size(), cv::Size(128, 64));
        ASSERT_EQ(frame.rgb.type(), CV_8UC3);
        ASSERT_EQ(frame.depth.size(), cv::Size(128, 64));
        ASSERT_EQ(frame.depth.type(), CV_32F);
        const PathFrame& pose = poses[static_cast<std::size_t>(index)];
        const Agreement a = compare(frame, pose, true);
        std::printf(
            "Blender pose %d: %d pixels, depth error mean %.4f mm, worst %.4f mm; colour of "
            "the surface hit right at %.2f %%\n",
            index, a.compared, a.mean_mm, a.worst_mm, 100.0 * a.colour_right / a.compared);
        EXPECT_GT(a.compared, 128 * 64 / 2);
        EXPECT_LE(a.mean_mm, 1.0);
        EXPECT_LE(a.worst_mm, 1.0);
        EXPECT_GE(a.colour_right, a.compared * 99 / 100);
        // The cube where its bearing says (ARCHITECTURE.md: a bearing at azimuth a from
        // heading h points along world angle h - a).
        const double dx = 2 - pose.x, dy = 1.5 - pose.y;
        const double azimuth = std::remainder(pose.heading - std::atan2(dy, dx), 2 * M_PI);
        const double elevation = std::atan2(1.0 - 1.6, std::hypot(dx, dy));
        const int u = static_cast<int>((azimuth + M_PI) / (2 * M_PI) * 128);
        const int v = static_cast<int>((M_PI / 2 - elevation) / M_PI * 64);
        const cv::Vec3b at = frame.rgb.at<cv::Vec3b>(v, u);
        EXPECT_TRUE(at[0] > 200 && at[1] < 60 && at[2] > 200)
            << "pose " << index << ": no magenta cube at column " << u << ", row " << v;
        EXPECT_NEAR(frame.depth.at<float>(v, u), intersect(u, v, 128, pose).distance, 0.001);
      });
  EXPECT_EQ(delivered, std::vector<int>({0, 1, 2}));
  for (const auto& entry : fs::directory_iterator(dir.path))
    EXPECT_NE(entry.path().filename(), "blender") << "the work folder was left behind";
}

// The same room drawn in centimetres (unit scale 0.01): the pose is in metres, depth comes back in metres.
// Depth only, as online sampling's coarse pass renders.
TEST_F(BlenderRender, SceneUnitsOtherThanMetresAndDepthOnly) {
  SKIP_WITHOUT_BLENDER();
  TempDir dir;
  BlenderOptions options;
  options.width = 96;
  options.colour = false;
  PathFrame pose;
  pose.x = 0.5;
  pose.y = -1.0;
  pose.heading = -2.0;
  const BlenderFrame frame =
      render_blender_frame(scene("room_cm.blend").string(), pose, options, dir.path.string());
  EXPECT_TRUE(frame.rgb.empty());
  ASSERT_EQ(frame.depth.size(), cv::Size(96, 48));
  const Agreement a = compare(frame, pose, false);
  std::printf("Blender, scene in cm: %d pixels, depth error mean %.4f mm, worst %.4f mm\n", a.compared,
              a.mean_mm, a.worst_mm);
  EXPECT_LE(a.mean_mm, 1.0);
  EXPECT_LE(a.worst_mm, 1.0);
  // Told the units instead of reading them: the same.
  options.units_per_metre = 100.0;
  const BlenderFrame told =
      render_blender_frame(scene("room_cm.blend").string(), pose, options, dir.path.string());
  EXPECT_LE(compare(told, pose, false).mean_mm, 1.0);
}

TEST_F(BlenderRender, CancellingStopsBlenderAfterTheFrameInHand) {
  SKIP_WITHOUT_BLENDER();
  TempDir dir;
  BlenderOptions options;
  options.width = 32;
  options.colour = false;
  std::vector<PathFrame> poses(20);
  for (int i = 0; i < 20; ++i) poses[i].x = -4.0 + 0.4 * i;
  struct Cancellable : CancellableProgress {
    void report(double, const std::string&) override {}
  } progress;
  int delivered = 0;
  EXPECT_THROW(render_blender_frames(
                   scene("room.blend").string(), poses, options, dir.path.string(),
                   [&](int, BlenderFrame&&) {
                     ++delivered;
                     progress.cancel();
                   },
                   progress),
               Cancelled);
  EXPECT_EQ(delivered, 1);
  EXPECT_FALSE(fs::exists(dir.path / "blender"));
}

TEST_F(BlenderRender, ClearErrorsForMissingOrBrokenScenesAndNoBlender) {
  TempDir dir;
  BlenderOptions options;
  options.width = 32;
  try {
    render_blender_frame((dir.path / "missing.blend").string(), {}, options, dir.path.string());
    FAIL() << "no error for a missing scene";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.blend"), std::string::npos) << e.what();
  }
  std::ofstream(dir.path / "broken.blend") << "not a blend file\n";
  options.executable = "no-such-blender-program";
  try {
    render_blender_frame((dir.path / "broken.blend").string(), {}, options, dir.path.string());
    FAIL() << "no error without blender";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("apt-get install blender"), std::string::npos) << e.what();
  }
  options.executable = "blender";
  bool have_blender = true;
  try {
    find_blender("blender");
  } catch (const Error&) {
    have_blender = false;
  }
  if (have_blender) {
    try {
      render_blender_frame((dir.path / "broken.blend").string(), {}, options, dir.path.string());
      FAIL() << "no error for a broken scene";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("Blender failed on"), std::string::npos) << what;
      EXPECT_NE(what.find("broken.blend"), std::string::npos) << what;
      EXPECT_NE(what.find("not supported"), std::string::npos) << "Blender's own message: " << what;
    }
  }
  options = {};
  options.width = 15;
  try {
    options.check();
    FAIL() << "an odd width passed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("BlenderOptions.width"), std::string::npos) << e.what();
  }
  options = {};
  options.colour = options.depth = false;
  EXPECT_THROW(options.check(), Error);
  EXPECT_TRUE(is_blender_scene("a/b/Scene.BLEND"));
  EXPECT_FALSE(is_blender_scene("a/b/scene.pov"));
  EXPECT_FALSE(is_blender_scene("a/b.blend/scene.pov"));
}

// An uncompressed EXR written here byte by byte (the OpenEXR layout: magic, version, attributes, a line
// offset table, scanlines of channels in name order): a HALF channel before the FLOAT one wanted.
TEST_F(BlenderRender, ReadsAChannelOfAnUncompressedExr) {
  TempDir dir;
  std::string b("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
  auto i32 = [&](std::int32_t v) { b.append(reinterpret_cast<const char*>(&v), 4); };
  auto attribute = [&](const std::string& name, const std::string& type, const std::string& value) {
    b += name + '\0' + type + '\0';
    i32(static_cast<std::int32_t>(value.size()));
    b += value;
  };
  std::string channels;
  for (const auto& [name, type] :
       {std::pair<std::string, int>{"Layer.Combined.A", 1}, {"Layer.Depth.Z", 2}}) {
    channels += name + '\0';
    const std::int32_t fields[4] = {type, 0, 1, 1};
    channels.append(reinterpret_cast<const char*>(fields), 16);
  }
  channels += '\0';
  attribute("channels", "chlist", channels);
  attribute("compression", "compression", std::string(1, '\0'));
  const std::int32_t window[4] = {0, 0, 2, 1};  // 3 x 2
  attribute("dataWindow", "box2i", std::string(reinterpret_cast<const char*>(window), 16));
  attribute("lineOrder", "lineOrder", std::string(1, '\0'));
  b += '\0';
  const std::size_t table = b.size(), line_bytes = 3 * 2 + 3 * 4;
  for (int y = 0; y < 2; ++y) {
    const std::uint64_t at = table + 16 + y * (8 + line_bytes);
    b.append(reinterpret_cast<const char*>(&at), 8);
  }
  for (int y = 0; y < 2; ++y) {
    i32(y);
    i32(static_cast<std::int32_t>(line_bytes));
    for (int x = 0; x < 3; ++x) b.append("\x00\x3c", 2);  // half 1.0
    for (int x = 0; x < 3; ++x) {
      const float z = 10.0f * y + x + 0.25f;
      b.append(reinterpret_cast<const char*>(&z), 4);
    }
  }
  const fs::path file = dir.path / "tiny.exr";
  std::ofstream(file, std::ios::binary) << b;
  const cv::Mat z = read_uncompressed_exr_channel(file.string(), ".Depth.Z");
  ASSERT_EQ(z.size(), cv::Size(3, 2));
  EXPECT_FLOAT_EQ(z.at<float>(0, 0), 0.25f);
  EXPECT_FLOAT_EQ(z.at<float>(1, 2), 12.25f);
  const cv::Mat alpha = read_uncompressed_exr_channel(file.string(), ".A");
  EXPECT_FLOAT_EQ(alpha.at<float>(1, 1), 1.0f);
  EXPECT_THROW(read_uncompressed_exr_channel(file.string(), ".Normal.X"), Error);
  std::ofstream(file, std::ios::binary) << "not an exr";
  EXPECT_THROW(read_uncompressed_exr_channel(file.string(), ".Depth.Z"), Error);
}

}  // namespace
}  // namespace plenopath
