#include "processing/capture/povray_render.h"

#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <thread>
#include <vector>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/capture/povray_atmosphere.h"
#include "processing/util/child_process.h"

namespace plenopath {
namespace fs = std::filesystem;
namespace {

std::string pov_vector(double x, double y, double z) {
  char text[160];
  std::snprintf(text, sizeof text, "<%.9g, %.9g, %.9g>", x, y, z);
  return text;
}

}  // namespace

void PovrayOptions::check() const {
  const std::string s = "PovrayOptions.";
  require_option(!executable.empty(), s + "executable", "must name the povray program", executable);
  require_option(width >= 16 && width % 2 == 0, s + "width", "must be even and >= 16", width);
  require_option(std::isfinite(camera_height_m), s + "camera_height_m", "must be finite", camera_height_m);
  require_option(units_per_metre > 0 && std::isfinite(units_per_metre), s + "units_per_metre", "must be > 0",
                 units_per_metre);
  require_option(depth_fog_m >= 0 && std::isfinite(depth_fog_m), s + "depth_fog_m", "must be >= 0 (0 = 8 m)",
                 depth_fog_m);
  require_option(max_depth_m > 0, s + "max_depth_m", "must be > 0", max_depth_m);
  require_option(quality >= 0 && quality <= 11, s + "quality", "must be in [0, 11]", quality);
  require_option(timeout_s > 0, s + "timeout_s", "must be > 0", timeout_s);
  require_option(colour || depth, s + "colour", "or depth must be on", colour);
  require_option(frames_per_process >= 1, s + "frames_per_process", "must be >= 1", frames_per_process);
  require_option(processes >= 0, s + "processes", "must be >= 0 (0 = the cores + 2)", processes);
}

std::string find_povray(const std::string& executable) {
  return find_program(executable, "POV-Ray", "povray");
}

namespace {

// The frames of one chunk, rendered by one POV-Ray process per pass in animation mode (frame_number indexes
// the chunk's camera poses): a POV-Ray process idles about a quarter of a second before and after each frame
// whatever its size, which dominates small frames.
// `depth_scene`: the scene's copy without its own atmosphere (povray_atmosphere.h), for the depth passes.
std::vector<PovrayFrame> render_chunk(const fs::path& scene, const fs::path& depth_scene,
                                      const std::string& scene_file, const std::string& povray,
                                      const std::vector<PathFrame>& poses, const PovrayOptions& o,
                                      const fs::path& work, Progress& progress) {
  const int height = o.width / 2;
  const double u = o.units_per_metre;
  const double fog_m = o.depth_fog_m > 0 ? o.depth_fog_m : 8.0;
  const int count = static_cast<int>(poses.size());
  // The camera basis in POV coordinates: forward along the heading, right 90 deg clockwise of it.
  std::string location = "#declare Plenopath_Location = array[" + std::to_string(count) + "] {",
              direction = "#declare Plenopath_Direction = array[" + std::to_string(count) + "] {",
              right = "#declare Plenopath_Right = array[" + std::to_string(count) + "] {";
  for (int i = 0; i < count; ++i) {
    const PathFrame& pose = poses[static_cast<std::size_t>(i)];
    const double c = std::cos(pose.heading), s = std::sin(pose.heading);
    const std::string comma = i + 1 < count ? ", " : "}\n";
    // Plan (X, Y, up) is POV <X, up, Y> (y up), or <X, Y, up> for a scene modelled z up (a right-handed
    // world). For the latter the vectors are the y-up ones with y and z swapped and right and up turned
    // over: POV-Ray's spherical camera takes its basis as left-handed (PovrayRender.ScenesModelledWithZUp
    // checks the result against the room's geometry).
    if (o.z_up) {
      location += pov_vector(pose.x * u, pose.y * u, o.camera_height_m * u) + comma;
      direction += pov_vector(c, s, 0) + comma;
      right += pov_vector(-s, c, 0) + comma;
    } else {
      location += pov_vector(pose.x * u, o.camera_height_m * u, pose.y * u) + comma;
      direction += pov_vector(c, 0, s) + comma;
      right += pov_vector(s, 0, -c) + comma;
    }
  }
  const std::string index = count > 1 ? "frame_number" : "0";
  const std::string camera = location + direction + right +
                             "camera {\n  spherical\n  angle 360 180\n  location Plenopath_Location[" +
                             index + "]\n  direction Plenopath_Direction[" + index +
                             "]\n  right Plenopath_Right[" + index + "]\n  up " +
                             (o.z_up ? "<0, 0, -1>" : "<0, 1, 0>") + "\n}\n";
  // POV-Ray runs in the folder of the scene it includes (the author's, or the depth passes' copy, which then
  // reads the other copied files first) with the author's folder as its library path.
  auto pass = [&](const std::string& name, const std::string& extra_sdl,
                  const std::vector<std::string>& flags, const fs::path& included) {
    const fs::path wrapper = work / (name + ".pov");
    {
      std::ofstream out(wrapper);
      out << "// Written by Plenopath Studio: the author's scene, seen by the studio's spherical camera.\n"
          << "#include \"" << included.string() << "\"\n"
          << camera << extra_sdl;
      if (!out) throw Error("POV-Ray: cannot write " + wrapper.string());
    }
    const fs::path log = work / (name + ".log");
    // Animation output is the name plus the frame number, zero-padded to the last frame's digits.
    auto image_of = [&](int i) {
      if (count == 1) return work / (name + ".png");
      std::string number = std::to_string(i);
      number.insert(0, std::to_string(count - 1).size() - number.size(), '0');
      return work / (name + number + ".png");
    };
    for (int i = 0; i < count; ++i) fs::remove(image_of(i));
    std::vector<std::string> argv = {povray,
                                     "+I" + wrapper.string(),
                                     "+O" + (work / (name + ".png")).string(),
                                     "+L" + scene.parent_path().string(),
                                     "+W" + std::to_string(o.width),
                                     "+H" + std::to_string(height),
                                     "-D",
                                     "-V",
                                     "+WT1"};
    if (count > 1) {
      argv.push_back("+KFI0");
      argv.push_back("+KFF" + std::to_string(count - 1));
    }
    argv.insert(argv.end(), flags.begin(), flags.end());
    const int status = run_child_process(
        argv, {included.parent_path().string(), log.string(), o.timeout_s * count, "POV-Ray", " for a pass"},
        progress);
    std::vector<cv::Mat> images;
    for (int i = 0; i < count; ++i) {
      const fs::path image = image_of(i);
      if (status != 0 || !fs::exists(image))
        throw Error("POV-Ray failed on " + scene_file + " (" + name + " pass, exit " +
                    std::to_string(status) + "):\n" + tail_of_file(log.string(), 1500));
      cv::Mat m = cv::imread(image.string(), cv::IMREAD_UNCHANGED);
      if (m.empty() || m.cols != o.width || m.rows != height)
        throw Error("POV-Ray wrote no readable " + std::to_string(o.width) + "x" + std::to_string(height) +
                    " image for " + scene_file + " (" + name + " pass)");
      images.push_back(m);
      fs::remove(image);
    }
    return images;
  };
  std::vector<PovrayFrame> frames(static_cast<std::size_t>(count));
  if (o.colour) {
    std::vector<std::string> colour_flags = {"+FN8", "+Q" + std::to_string(o.quality)};
    colour_flags.push_back(o.antialias ? "+A0.3" : "-A");
    std::vector<cv::Mat> colour = pass("colour", "", colour_flags, scene);
    for (int i = 0; i < count; ++i) {
      cv::Mat& rgb = colour[static_cast<std::size_t>(i)];
      if (rgb.channels() == 4) cv::cvtColor(rgb, rgb, cv::COLOR_BGRA2BGR);
      if (rgb.channels() == 1) cv::cvtColor(rgb, rgb, cv::COLOR_GRAY2BGR);
      if (rgb.depth() == CV_16U) rgb.convertTo(rgb, CV_8U, 1.0 / 257.0);
      frames[static_cast<std::size_t>(i)].rgb = rgb;
    }
  }
  if (!o.depth) return frames;
  const double fog_units = fog_m * u;
  // Fog needs quality 9 (POV-Ray's atmosphere); max_trace_level 1 keeps reflected and refracted rays out.
  const std::vector<std::string> depth_flags = {"+FN16", "File_Gamma=1.0", "-A", "+Q9"};
  auto fog = [&](int white) {
    return "global_settings { max_trace_level 1 }\nfog { fog_type 1 distance " + std::to_string(fog_units) +
           " color rgb " + std::to_string(white) + " }\n";
  };
  const std::vector<cv::Mat> blacks = pass("depth_black", fog(0), depth_flags, depth_scene);
  const std::vector<cv::Mat> whites = pass("depth_white", fog(1), depth_flags, depth_scene);
  for (int i = 0; i < count; ++i) {
    const cv::Mat &black = blacks[static_cast<std::size_t>(i)], &white = whites[static_cast<std::size_t>(i)];
    if (black.size() != white.size() || black.depth() != CV_16U || white.depth() != CV_16U)
      throw Error("POV-Ray wrote depth passes that are not 16-bit for " + scene_file);
    cv::Mat depth(height, o.width, CV_32F, cv::Scalar(0));
    const int channels = black.channels();
    // POV-Ray puts fog only where a ray runs through empty or hollow space: a camera inside a solid object
    // (a room modelled as a box, not declared hollow) shows none, and there is no depth to code.
    {
      cv::Mat difference;
      cv::absdiff(white, black, difference);
      if (cv::countNonZero(difference.reshape(1)) < static_cast<int>(difference.total()) / 100) {
        const PathFrame& pose = poses[static_cast<std::size_t>(i)];
        std::ostringstream where;
        where.precision(3);
        where << std::fixed << " at frame " << pose.index << " (" << pose.x << ", " << pose.y << ") m, "
              << o.camera_height_m << " m up";
        throw Error(
            "POV-Ray scene " + scene_file + ": the depth passes show no fog" + where.str() +
            ", so no depth: the camera is inside an object that is not hollow (add `hollow` to the "
            "object around the camera: the room's box, or a ceiling `plane { y, H }`, whose inside is "
            "everything below it; an object cut by `clipped_by` keeps the inside of its whole shape), "
            "or move the camera out of it");
      }
    }
    for (int r = 0; r < height; ++r) {
      const std::uint16_t* b = black.ptr<std::uint16_t>(r);
      const std::uint16_t* w = white.ptr<std::uint16_t>(r);
      float* d = depth.ptr<float>(r);
      for (int col = 0; col < o.width; ++col) {
        // The channels agree (fog is grey); their mean lowers the quantisation noise.
        double fogged = 0.0;
        for (int k = 0; k < std::min(channels, 3); ++k)
          fogged += (double(w[col * channels + k]) - double(b[col * channels + k])) / 65535.0;
        fogged /= std::min(channels, 3);
        const double t = 1.0 - fogged;
        if (!(t > 0.0)) continue;  // fully fogged: sky
        const double metres = -fog_m * std::log(std::min(1.0, t));
        if (metres < o.max_depth_m) d[col] = static_cast<float>(metres);
      }
    }
    frames[static_cast<std::size_t>(i)].depth = depth;
  }
  return frames;
}

}  // namespace

void render_povray_frames(const std::string& scene_file, const std::vector<PathFrame>& poses,
                          const PovrayOptions& o, const std::string& work_dir,
                          const std::function<void(int index, PovrayFrame&& frame)>& deliver,
                          Progress& progress) {
  o.check();
  const fs::path scene = fs::absolute(scene_file);
  if (!fs::is_regular_file(scene)) throw Error("POV-Ray scene " + scene_file + ": no such file");
  const std::string povray = find_povray(o.executable);
  const int total = static_cast<int>(poses.size());
  const int processes =
      o.processes > 0 ? o.processes : static_cast<int>(std::max(1u, std::thread::hardware_concurrency())) + 2;
  // Chunks of at most frames_per_process, spread over the processes so that a short path still uses them.
  const int per_chunk =
      std::max(1, std::min(o.frames_per_process, (total + processes - 1) / std::max(1, processes)));
  // The depth passes read the scene without the author's fogs, media and radiosity.
  fs::path depth_scene = scene;
  if (o.depth)
    depth_scene = copy_scene_without_atmosphere(scene.string(), (fs::path(work_dir) / "depth-scene").string())
                      .scene_file;
  int done = 0;
  for (int wave_begin = 0; wave_begin < total; wave_begin += per_chunk * processes) {
    const int wave_end = std::min(total, wave_begin + per_chunk * processes);
    const int chunks = (wave_end - wave_begin + per_chunk - 1) / per_chunk;
    std::vector<std::vector<PovrayFrame>> rendered(static_cast<std::size_t>(chunks));
    std::vector<std::exception_ptr> failed(static_cast<std::size_t>(chunks));
    std::vector<std::thread> threads;
    for (int c = 0; c < chunks; ++c) {
      const int first = wave_begin + c * per_chunk, last = std::min(wave_end, first + per_chunk);
      threads.emplace_back([&, c, first, last] {
        try {
          const fs::path work = fs::path(work_dir) / ("chunk" + std::to_string(c));
          fs::create_directories(work);
          const std::vector<PathFrame> chunk(poses.begin() + first, poses.begin() + last);
          rendered[static_cast<std::size_t>(c)] =
              render_chunk(scene, depth_scene, scene_file, povray, chunk, o, work, progress);
        } catch (...) {
          failed[static_cast<std::size_t>(c)] = std::current_exception();
        }
      });
    }
    for (std::thread& t : threads) t.join();
    progress.throw_if_cancelled();
    for (const std::exception_ptr& e : failed)
      if (e) std::rethrow_exception(e);
    for (auto& chunk : rendered)
      for (PovrayFrame& frame : chunk) deliver(done++, std::move(frame));
    progress.checkpoint(double(done) / total);
  }
  for (int c = 0; c < processes; ++c) fs::remove_all(fs::path(work_dir) / ("chunk" + std::to_string(c)));
  fs::remove_all(fs::path(work_dir) / "depth-scene");
}

PovrayFrame render_povray_frame(const std::string& scene_file, const PathFrame& pose,
                                const PovrayOptions& options, const std::string& work_dir,
                                Progress& progress) {
  PovrayFrame frame;
  render_povray_frames(
      scene_file, {pose}, options, work_dir, [&](int, PovrayFrame&& f) { frame = std::move(f); }, progress);
  return frame;
}

}  // namespace plenopath
