// Online sampling of a CG path on a scene the project's renderer did not make (issue 23): the POV-Ray
// corpus's office walk (tests/bench/povray/corpus.py) rendered by POV-Ray along its truth poses, once in
// full (every frame at full size with depth, then the depth sampler) and once online (the whole path as
// 256-wide depth only, full frames only for the keyframes chosen from it). Both keyframe sets are judged
// by their geometric loss against the exact envelopes of the scene's DXF plan (CGAL), which neither saw.
// Prints one JSON object: keyframes, frames rendered at full size, loss, seconds and their ratios, with the
// commit, the load and a baseline measured in the same run.
// Usage: bench_povray_online [SCENE [RATIO [WIDTH [FRAMES]]]] (office, 20, 1024, all).
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "model/path_io.h"
#include "processing/capture/povray_render.h"
#include "processing/plan/dxf_import.h"
#include "processing/sampling/online_sampling.h"
#include "processing/visibility/visibility.h"
#include "tests/bench/bench_common.h"

using namespace plenopath;
using namespace plenopath::bench;
namespace fs = std::filesystem;

namespace {

// A fixed amount of work to divide the seconds by (this machine's speed varies severalfold).
double baseline_seconds() {
  cv::Mat image(1024, 2048, CV_8UC3), out;
  cv::randu(image, 0, 255);
  const auto t0 = Clock::now();
  for (int i = 0; i < 20; ++i) cv::GaussianBlur(image, out, cv::Size(15, 15), 3.0);
  return seconds_since(t0);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string scene_name = argc > 1 ? argv[1] : "office";
    const double ratio = argc > 2 ? std::atof(argv[2]) : 20.0;
    const int width = argc > 3 ? std::atoi(argv[3]) : 1024;
    const int max_frames = argc > 4 ? std::atoi(argv[4]) : 0;
    const std::string source = PLENOPATH_SOURCE_DIR;
    const std::string corpus = source + "/tests/bench/povray/corpus.py";
    const fs::path work =
        fs::temp_directory_path() / ("plenopath_bench_online_" + std::to_string(::getpid()));
    fs::create_directories(work);
    const std::string walk = (work / "truth.json").string(), dxf = (work / "plan.dxf").string();
    for (const std::string& command : {"/usr/bin/python3 '" + corpus + "' walk " + scene_name + " " + walk,
                                       "/usr/bin/python3 '" + corpus + "' dxf " + scene_name + " " + dxf})
      if (std::system(command.c_str()) != 0) throw std::runtime_error(command + " failed");
    const nlohmann::json truth_json = nlohmann::json::parse(std::ifstream(walk));
    CameraPath path = read_path_file(walk);
    if (max_frames > 0 && static_cast<int>(path.size()) > max_frames) path.frames.resize(max_frames);
    // The corpus's scene files (corpus.py SCENES "pov"); the clean walks only: the others' nuisances are set
    // per frame by corpus.py.
    const std::map<std::string, std::string> pov = {
        {"office", "office.pov"}, {"gap", "office.pov"}, {"gallery", "gallery.pov"}};
    if (!pov.count(scene_name)) throw std::runtime_error("scene " + scene_name + ": office, gap or gallery");
    const std::string scene = source + "/tests/bench/povray/scenes/" + pov.at(scene_name);
    PovrayOptions povray;
    povray.width = width;
    povray.camera_height_m = truth_json.value("camera_height_m", 1.6);
    SamplingParameters parameters;
    parameters.method = SamplingMethod::kDepth;
    parameters.ratio = ratio;
    const double baseline = baseline_seconds();

    // The judge: the plan's exact envelopes.
    const FloorPlan plan = import_dxf(dxf);
    const PathEnvelopes truth = compute_path_envelopes(VisibilityIndex(plan), path, 1);

    // Full: every frame at full size (colour and depth), the sampler on their depth.
    const auto t_full = Clock::now();
    DepthSamplingOptions depth_options;
    std::vector<DepthVolume> volumes(path.size());
    PathEnvelopes envelopes;
    envelopes.frames.resize(path.size());
    render_povray_frames(scene, path.frames, povray, (work / "full").string(), [&](int i, PovrayFrame&& f) {
      volumes[i] = summarise_depth(f.depth, path.frames[i], depth_options, &envelopes.frames[i]);
    });
    const Keyframes full = sample_by_depth(path, volumes, parameters, {}, depth_options, &envelopes);
    const double full_seconds = seconds_since(t_full);

    // Online.
    const auto t_online = Clock::now();
    double coarse_seconds = 0.0;
    const OnlineSamplingResult online = sample_online(
        path, parameters,
        [&](const std::vector<PathFrame>& poses, int coarse_width,
            const std::function<void(int, const cv::Mat&)>& deliver, Progress& progress) {
          PovrayOptions coarse = povray;
          coarse.width = coarse_width;
          coarse.colour = false;
          render_povray_frames(
              scene, poses, coarse, (work / "coarse").string(),
              [&](int i, PovrayFrame&& f) { deliver(i, f.depth); }, progress);
          coarse_seconds = seconds_since(t_online);
        },
        [&](const std::vector<PathFrame>& poses, Progress& progress) {
          render_povray_frames(
              scene, poses, povray, (work / "keyframes").string(), [](int, PovrayFrame&&) {}, progress);
        });
    const double online_seconds = seconds_since(t_online);
    fs::remove_all(work);

    const GeometricLoss loss_full = geometric_loss(path, full, truth),
                        loss_online = geometric_loss(path, online.keyframes, truth);
    const nlohmann::json out = {
        {"benchmark", "povray_online"},
        {"scene", scene_name},
        {"commit", git_commit()},
        {"load_average", load_average()},
        {"baseline_seconds", baseline},
        {"frames", path.size()},
        {"size", std::to_string(width) + "x" + std::to_string(width / 2)},
        {"ratio", ratio},
        {"full",
         {{"keyframes", full.indices.size()},
          {"frames_rendered_full_size", path.size()},
          {"loss_mean", loss_full.mean},
          {"loss_p95", loss_full.p95},
          {"seconds", full_seconds},
          {"seconds_to_baseline", full_seconds / baseline}}},
        {"online",
         {{"keyframes", online.keyframes.indices.size()},
          {"frames_rendered_full_size", online.full_frames},
          {"frames_rendered_coarse", online.coarse_frames},
          {"loss_mean", loss_online.mean},
          {"loss_p95", loss_online.p95},
          {"seconds", online_seconds},
          {"seconds_coarse", coarse_seconds},
          {"seconds_to_baseline", online_seconds / baseline}}},
        {"loss_online_over_full", loss_full.mean > 0 ? loss_online.mean / loss_full.mean : 1.0},
        {"full_size_frames_share", double(online.full_frames) / path.size()},
        {"seconds_online_over_full", online_seconds / full_seconds},
        {"targets", "same keyframe count, loss <= 1.1x, at most a quarter of the frames at full size"}};
    std::cout << out.dump(2) << std::endl;
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_povray_online: " << e.what() << "\n";
    return 1;
  }
}
