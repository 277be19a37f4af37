#include "processing/capture/blender_render.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <thread>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/util/child_process.h"
#include "processing/util/scoped_folder.h"

namespace plenopath {
namespace fs = std::filesystem;
namespace {

// The script Blender runs (`-- JOB.json`). Per pose i of the job it writes colour_i.png and depth_i.exr
// into the job's folder, then done_i (the scene's units per metre), which tells the studio both are complete.
constexpr const char* kScript =
    R"PY(# Written by Plenopath Studio (processing/capture/blender_render.cpp): the scene Blender opened,
# rendered by Cycles with an equirectangular camera at each pose of the job.
import bpy, json, math, os, sys

job = json.load(open(sys.argv[sys.argv.index("--") + 1]))
if os.path.realpath(bpy.data.filepath or "") != os.path.realpath(job["scene"]):
    raise RuntimeError("Blender did not open " + job["scene"])
scene = bpy.context.scene
layer = bpy.context.view_layer
units = job["units_per_metre"]
if units <= 0:
    units = 1.0 / scene.unit_settings.scale_length if scene.unit_settings.scale_length > 0 else 1.0
print("PLENOPATH units_per_metre %.9g" % units, flush=True)

data = bpy.data.cameras.new("PlenopathCamera")
data.type = 'PANO'
if hasattr(data, "panorama_type"):  # Blender 4
    data.panorama_type = 'EQUIRECTANGULAR'
else:  # Blender 3: Cycles' own property
    data.cycles.panorama_type = 'EQUIRECTANGULAR'
data.clip_start = 1e-4 * units
data.clip_end = 1e6 * units
camera = bpy.data.objects.new("PlenopathCamera", data)
scene.collection.objects.link(camera)
scene.camera = camera
for marker in scene.timeline_markers:  # markers bound to cameras would switch back to the author's
    marker.camera = None

render = scene.render
render.engine = 'CYCLES'
cycles = scene.cycles
cycles.device = 'CPU'
render.resolution_x = job["width"]
render.resolution_y = job["width"] // 2
render.resolution_percentage = 100
render.pixel_aspect_x = render.pixel_aspect_y = 1.0
render.use_border = False
render.use_multiview = False
render.use_motion_blur = False
render.use_persistent_data = True
if job["threads"] > 0:
    render.threads_mode = 'FIXED'
    render.threads = job["threads"]
colour_settings = {"samples": job["samples"] if job["samples"] > 0 else cycles.samples,
                   "filter_width": cycles.filter_width, "use_denoising": cycles.use_denoising}
compositing = render.use_compositing
import _cycles
if cycles.use_denoising and not getattr(_cycles, "with_openimagedenoise", True):
    # Debian's Blender 3.4 is built without OpenImageDenoise: Cycles would refuse to render.
    print("PLENOPATH warning: this Blender has no denoiser: the colour is rendered without denoising", flush=True)
    colour_settings["use_denoising"] = False
# Depth: Cycles writes the Z pass from the first sample only, so one sample through the pixel's centre.
depth_settings = {"samples": 1, "filter_width": 0.01, "use_denoising": False}

def use(settings):
    for key, value in settings.items():
        setattr(cycles, key, value)

out = job["out"]
for i, (x, y, heading) in enumerate(job["poses"]):
    camera.location = (x * units, y * units, job["camera_height_m"] * units)
    camera.rotation_euler = (math.pi / 2, 0.0, heading - math.pi / 2)
    if job["colour"]:
        use(colour_settings)
        layer.use_pass_z = False
        render.use_compositing = compositing
        bpy.ops.render.render()
        settings = render.image_settings
        settings.file_format = 'PNG'
        settings.color_mode = 'RGB'
        settings.color_depth = '8'
        bpy.data.images["Render Result"].save_render(os.path.join(out, "colour_%d.png" % i))
    if job["depth"]:
        use(depth_settings)
        layer.use_pass_z = True
        render.use_compositing = False
        bpy.ops.render.render(layer=layer.name)
        settings = render.image_settings
        settings.file_format = 'OPEN_EXR_MULTILAYER'
        settings.color_depth = '32'
        settings.exr_codec = 'NONE'
        bpy.data.images["Render Result"].save_render(os.path.join(out, "depth_%d.exr" % i))
    # The depth's units, for the studio, which may look for done_i at any moment: written whole under
    # another name, then renamed (atomic), so it never reads an empty marker.
    with open(os.path.join(out, "writing_done_%d" % i), "w") as done:
        done.write("%.17g\n" % units)
    os.replace(os.path.join(out, "writing_done_%d" % i), os.path.join(out, "done_%d" % i))
    print("PLENOPATH frame %d of %d" % (i + 1, len(job["poses"])), flush=True)
)PY";

// Blender's last messages without its per-tile status lines ("Fra:1 Mem:...").
std::string last_messages(const std::string& log, std::size_t bytes) {
  std::ifstream in(log);
  std::string line, text;
  while (std::getline(in, line))
    if (line.rfind("Fra:", 0) != 0 && !line.empty()) text += line + "\n";
  return text.size() > bytes ? "..." + text.substr(text.size() - bytes) : text;
}

float half_to_float(std::uint16_t h) {
  const std::uint32_t sign = (h >> 15) & 1u, exponent = (h >> 10) & 0x1fu, mantissa = h & 0x3ffu;
  float value;
  if (exponent == 0)
    value = std::ldexp(static_cast<float>(mantissa), -24);
  else if (exponent == 31)
    value = mantissa ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
  else
    value = std::ldexp(static_cast<float>(mantissa | 0x400u), static_cast<int>(exponent) - 25);
  return sign ? -value : value;
}

}  // namespace

void BlenderOptions::check() const {
  const std::string s = "BlenderOptions.";
  require_option(!executable.empty(), s + "executable", "must name the blender program", executable);
  require_option(width >= 16 && width % 2 == 0, s + "width", "must be even and >= 16", width);
  require_option(std::isfinite(camera_height_m), s + "camera_height_m", "must be finite", camera_height_m);
  require_option(units_per_metre >= 0 && std::isfinite(units_per_metre), s + "units_per_metre",
                 "must be >= 0 (0 = the scene's unit scale)", units_per_metre);
  require_option(colour || depth, s + "colour", "or depth must be on", colour);
  require_option(samples >= 0, s + "samples", "must be >= 0 (0 = the scene's)", samples);
  require_option(threads >= 0, s + "threads", "must be >= 0 (0 = every core)", threads);
  require_option(max_depth_m > 0, s + "max_depth_m", "must be > 0", max_depth_m);
  require_option(timeout_s > 0, s + "timeout_s", "must be > 0", timeout_s);
}

bool is_blender_scene(const std::string& scene_file) {
  std::string e = fs::path(scene_file).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e == ".blend";
}

std::string find_blender(const std::string& executable) {
  return find_program(executable, "Blender", "blender");
}

cv::Mat read_uncompressed_exr_channel(const std::string& file, const std::string& suffix) {
  std::ifstream in(file, std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto fail = [&](const std::string& why) { return Error("EXR " + file + ": " + why); };
  std::size_t p = 0;
  auto need = [&](std::size_t n) {
    if (p + n > b.size()) throw fail("truncated");
  };
  auto i32 = [&] {
    need(4);
    std::int32_t v;
    std::memcpy(&v, b.data() + p, 4);
    p += 4;
    return v;
  };
  auto text = [&] {
    const std::size_t end = b.find('\0', p);
    if (end == std::string::npos) throw fail("truncated header");
    std::string s = b.substr(p, end - p);
    p = end + 1;
    return s;
  };
  if (b.size() < 8 || std::memcmp(b.data(), "\x76\x2f\x31\x01", 4) != 0) throw fail("not an OpenEXR file");
  p = 4;
  const std::int32_t version = i32();
  if ((version & 0xff) != 2 || (version & 0x1a00) != 0)
    throw fail("not a single-part scanline image (version flags " + std::to_string(version) + ")");
  struct Channel {
    std::string name;
    int type;  // 0 uint, 1 half, 2 float
  };
  std::vector<Channel> channels;
  int compression = -1, xmin = 0, ymin = 0, xmax = -1, ymax = -1;
  for (;;) {
    const std::string name = text();
    if (name.empty()) break;
    const std::string type = text();
    const std::int32_t size = i32();
    if (size < 0) throw fail("corrupt header");
    need(static_cast<std::size_t>(size));
    const std::size_t next = p + static_cast<std::size_t>(size);
    if (name == "channels" && type == "chlist") {
      while (p < next && b[p] != '\0') {
        Channel c;
        c.name = text();
        c.type = i32();
        p += 4;  // pLinear, reserved
        const std::int32_t xs = i32(), ys = i32();
        if (xs != 1 || ys != 1) throw fail("subsampled channel " + c.name);
        if (c.type < 0 || c.type > 2) throw fail("channel " + c.name + " of unknown type");
        channels.push_back(c);
      }
    } else if (name == "compression" && size == 1) {
      compression = static_cast<unsigned char>(b[p]);
    } else if (name == "dataWindow" && size == 16) {
      xmin = i32();
      ymin = i32();
      xmax = i32();
      ymax = i32();
    }
    p = next;
  }
  if (compression != 0) throw fail("compressed (" + std::to_string(compression) + "), expected NONE");
  const int width = xmax - xmin + 1, height = ymax - ymin + 1;
  if (width <= 0 || height <= 0 || width > 1 << 16 || height > 1 << 16) throw fail("bad data window");
  std::size_t line_bytes = 0, offset = 0, bytes = 0;
  int type = -1;
  for (const Channel& c : channels) {
    const std::size_t size = c.type == 1 ? 2 : 4;
    if (type < 0 && c.name.size() >= suffix.size() &&
        c.name.compare(c.name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      type = c.type;
      offset = line_bytes;
      bytes = size;
    }
    line_bytes += size * static_cast<std::size_t>(width);
  }
  if (type < 0 || type == 0) throw fail("no float channel named *" + suffix);
  const std::size_t table = p;
  cv::Mat image(height, width, CV_32F);
  for (int line = 0; line < height; ++line) {
    p = table + 8 * static_cast<std::size_t>(line);
    need(8);
    std::uint64_t at;
    std::memcpy(&at, b.data() + p, 8);
    p = static_cast<std::size_t>(at);
    const std::int32_t y = i32(), size = i32();
    if (y < ymin || y > ymax || static_cast<std::size_t>(size) != line_bytes) throw fail("corrupt scanline");
    need(line_bytes);
    const char* src = b.data() + p + offset;
    float* row = image.ptr<float>(y - ymin);
    for (int x = 0; x < width; ++x) {
      if (bytes == 4) {
        std::memcpy(&row[x], src + 4 * x, 4);
      } else {
        std::uint16_t h;
        std::memcpy(&h, src + 2 * x, 2);
        row[x] = half_to_float(h);
      }
    }
  }
  return image;
}

void render_blender_frames(const std::string& scene_file, const std::vector<PathFrame>& poses,
                           const BlenderOptions& o, const std::string& work_dir,
                           const std::function<void(int index, BlenderFrame&& frame)>& deliver,
                           Progress& progress) {
  o.check();
  const fs::path scene = fs::absolute(scene_file);
  if (!fs::is_regular_file(scene)) throw Error("Blender scene " + scene_file + ": no such file");
  const std::string blender = find_blender(o.executable);
  if (poses.empty()) return;
  const int total = static_cast<int>(poses.size()), height = o.width / 2;
  const fs::path work = fs::absolute(work_dir) / "blender";
  fs::remove_all(work);
  fs::create_directories(work);
  const RemoveFolderOnExit remove_work(work);  // whatever happens
  const fs::path script = work / "plenopath_render.py", job_file = work / "job.json",
                 log = work / "blender.log";
  {
    std::ofstream out(script);
    out << kScript;
    nlohmann::json job = {{"scene", scene.string()},
                          {"out", work.string()},
                          {"width", o.width},
                          {"camera_height_m", o.camera_height_m},
                          {"units_per_metre", o.units_per_metre},
                          {"colour", o.colour},
                          {"depth", o.depth},
                          {"samples", o.samples},
                          {"threads", o.threads},
                          {"poses", nlohmann::json::array()}};
    for (const PathFrame& f : poses) job["poses"].push_back({f.x, f.y, f.heading});
    std::ofstream(job_file) << job.dump();
    if (!out) throw Error("Blender: cannot write " + script.string());
  }
  const std::vector<std::string> argv = {
      blender,         "-b", scene.string(),   "--factory-startup", "--python-exit-code", "1", "--python",
      script.string(), "--", job_file.string()};
  // Blender runs in the scene's folder (relative paths in the .blend resolve against the file anyway).
  const std::string log_name = log.string();
  auto failure = [&](const std::string& what) {
    return Error("Blender failed on " + scene_file + " (" + what + "):\n" + last_messages(log_name, 1500));
  };
  int done = 0;
  // Delivers the frames Blender has finished, in order; false when the next one is not there yet.
  auto take_ready = [&] {
    bool any = false;
    while (done < total && fs::exists(work / ("done_" + std::to_string(done)))) {
      BlenderFrame frame;
      const fs::path colour = work / ("colour_" + std::to_string(done) + ".png"),
                     depth = work / ("depth_" + std::to_string(done) + ".exr");
      if (o.colour) {
        frame.rgb = cv::imread(colour.string(), cv::IMREAD_COLOR);
        if (frame.rgb.cols != o.width || frame.rgb.rows != height)
          throw failure("no readable " + std::to_string(o.width) + "x" + std::to_string(height) +
                        " colour image for frame " + std::to_string(done));
      }
      if (o.depth) {
        cv::Mat z = read_uncompressed_exr_channel(depth.string(), ".Depth.Z");
        if (z.cols != o.width || z.rows != height)
          throw failure("a depth image of " + std::to_string(z.cols) + "x" + std::to_string(z.rows));
        // Blender units to metres (done_i holds the units per metre the script used); sky (1e10) and what
        // lies beyond max_depth_m have no depth.
        double units_per_metre = 0.0;
        std::ifstream(work / ("done_" + std::to_string(done))) >> units_per_metre;
        if (!(units_per_metre > 0)) throw failure("no scene units for frame " + std::to_string(done));
        const double metres_per_unit = 1.0 / units_per_metre;
        frame.depth = cv::Mat(height, o.width, CV_32F, cv::Scalar(0));
        for (int r = 0; r < height; ++r) {
          const float* in = z.ptr<float>(r);
          float* d = frame.depth.ptr<float>(r);
          for (int c = 0; c < o.width; ++c) {
            const double m = in[c] * metres_per_unit;
            if (std::isfinite(m) && m > 0 && m < o.max_depth_m) d[c] = static_cast<float>(m);
          }
        }
      }
      fs::remove(colour);
      fs::remove(depth);
      fs::remove(work / ("done_" + std::to_string(done)));
      deliver(done, std::move(frame));
      ++done;
      any = true;
      progress.checkpoint(double(done) / total);
    }
    return any;
  };
  const int code = run_child_process(
      argv, {scene.parent_path().string(), log_name, o.timeout_s, "Blender", " for a frame of " + scene_file},
      progress, take_ready);
  if (done < total)
    throw failure(code != 0
                      ? "exit " + std::to_string(code)
                      : "it wrote " + std::to_string(done) + " of " + std::to_string(total) + " frames");
}

BlenderFrame render_blender_frame(const std::string& scene_file, const PathFrame& pose,
                                  const BlenderOptions& options, const std::string& work_dir,
                                  Progress& progress) {
  BlenderFrame frame;
  render_blender_frames(
      scene_file, {pose}, options, work_dir, [&](int, BlenderFrame&& f) { frame = std::move(f); }, progress);
  return frame;
}

}  // namespace plenopath
